#include <algorithm>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "erpt/error.h"
#include "erpt/integrators.h"
#include "erpt/render.h"
#include "erpt/render_request.h"
#include "erpt/scene_loader.h"
#include "option_scope.h"
#include "pass_writer.h"
#include "process_group.h"
#include "progress.h"
#include "stop_signals.h"

namespace erpt::cli {

std::map<std::string, std::string> parseDefines(const std::vector<std::string>& defines) {
  std::map<std::string, std::string> out;
  for (const std::string& d : defines) {
    size_t eq = d.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError("-D expects name=value, got '" + d + "'");
    out[d.substr(0, eq)] = d.substr(eq + 1);
  }
  return out;
}

namespace {
std::string optionTypeName(const OptionSpec& o) {
  switch (o.kind) {
    case OptionKind::Integer: return "INT";
    case OptionKind::Real: return "FLOAT";
    case OptionKind::List: return "LIST";
    default: break;
  }
  std::string words;
  for (const std::string& c : o.choices) words += (words.empty() ? "{" : ",") + c;
  return words + "}";
}

// "path, direct, ..." : the integrators that take `option`.
std::string takenBy(const std::string& option) {
  std::string users;
  for (const std::string& u : integratorsUsing(option)) users += (users.empty() ? "" : ", ") + u;
  return users;
}
}  // namespace

void addRenderOptions(CLI::App* cmd, RenderArgs& a) {
  cmd->add_option("--spp", a.spp, "Samples per pixel (default: the scene's sample_count)")->check(CLI::Range(int(kSppRange.low), int(kSppRange.high)));
  cmd->add_option("--width", a.width, "Image width in pixels (default: the scene's film)")
      ->check(CLI::Range(int(kImageSizeRange.low), int(kImageSizeRange.high)));
  cmd->add_option("--height", a.height, "Image height in pixels (default: the scene's film)")
      ->check(CLI::Range(int(kImageSizeRange.low), int(kImageSizeRange.high)));
  cmd->add_option("--threads", a.threads, "Worker threads (default 0 = all cores)")
      ->check(CLI::Range(int(kThreadsRange.low), int(kThreadsRange.high)));
  cmd->add_option("--seed", a.seed, "Random seed; the same seed gives the same image for any --threads");
  cmd->add_option("--max-depth", a.maxDepth, "Longest path in segments, Mitsuba's meaning (-1 = unbounded)")
      ->check(CLI::Range(int(kMaxDepthRange.low), int(kMaxDepthRange.high)));
  cmd->add_option("--filter", a.filter, "Pixel filter: box, tent or gaussian (default: the scene's rfilter)")
      ->check(CLI::IsMember({"box", "tent", "gaussian"}));
  cmd->add_option("-D,--define", a.defines, "Override a scene <default>: -D name=value (repeatable)");
  cmd->add_flag("-q,--quiet", a.quiet, "No progress output");
  cmd->add_flag("--tessellate-spheres", a.tessellateSpheres, "Load sphere shapes as 256 x 512 triangle meshes instead of exact spheres (for comparisons)");
  // Each integrator's options, as it declares them; values are checked when applied.
  for (const IntegratorModule& m : integratorModules())
    for (const OptionSpec& o : m.options) {
      if (cmd->get_option_no_throw(o.flag())) continue;  // declared by an earlier integrator too
      const std::string users = takenBy(o.flag());
      const bool numeric = o.kind == OptionKind::Integer || o.kind == OptionKind::Real;
      const std::string help = "[" + users + "] " + o.help +
                               (numeric ? " (" + o.allowed() + ", default " + o.defaultText() + ")"
                                : o.kind == OptionKind::Flag ? std::string()
                                                             : " (default " + o.defaultText() + ")");
      if (o.kind == OptionKind::Flag) cmd->add_flag(o.flag(), help);
      else cmd->add_option(o.flag(), a.integratorOptions[o.name], help)->type_name(optionTypeName(o));
    }
}

void addRenderCommand(CLI::App& app, RenderArgs& a) {
  CLI::App* cmd = app.add_subcommand("render", "Render a Mitsuba XML scene to a linear EXR and a tone-mapped PNG");
  cmd->add_option("scene", a.scene, "Scene file (Mitsuba 0.6 or 3 XML)")->required();
  cmd->add_option("-o,--output", a.output, "Output EXR path; the PNG is written beside it")->required();
  std::string integrators;
  for (const IntegratorModule& m : integratorModules()) integrators += (integrators.empty() ? "" : "; ") + m.name + ": " + m.description;
  cmd->add_option("--integrator", a.integrator, "Integrator (default: the scene's, if it is one of these, else path). " + integrators);
  cmd->add_option("--time", a.time, "Render for this many seconds instead of --spp samples per pixel (passes of growing spp; the image then depends on the machine's speed)")
      ->check(CLI::Range(kTimeRange.low, kTimeRange.high));
  cmd->add_option("--checkpoint", a.checkpoint, "Write the render's state to FILE (atomically) every --checkpoint-every seconds and when it ends or is stopped; continue it with `erpt resume FILE` (" + takenBy("--checkpoint") + ")");
  cmd->add_option("--checkpoint-every", a.checkpointEvery, "Seconds between checkpoints (default 300; written at the end of a group of sample passes)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--display", a.display, "Stream the image as it converges to the tev viewer listening at HOST:PORT (tev's default: 127.0.0.1:14158)");
  cmd->add_option("--write-partial", a.writePartial, "Write the image of the sample passes completed so far to the output every this many seconds (" + takenBy("--write-partial") + ")")
      ->check(CLI::Range(0.0, 1e7));
  addRenderOptions(cmd, a);
}

void addResumeCommand(CLI::App& app, ResumeArgs& a) {
  CLI::App* cmd = app.add_subcommand("resume", "Continue a render from its checkpoint (--checkpoint): same scene, options and output; the image is bit-identical to an uninterrupted render");
  cmd->add_option("checkpoint", a.checkpoint, "Checkpoint file")->required();
  cmd->add_option("--threads", a.threads, "Worker threads (default: as the render was started; the image does not depend on it)")
      ->check(CLI::Range(0, 1024));
  cmd->add_flag("-q,--quiet", a.quiet, "No progress output");
}

int runResume(const ResumeArgs& r) {
  namespace fs = std::filesystem;
  const ProcessGroup& group = ProcessGroup::current();
  const std::string given = fs::absolute(r.checkpoint).string();
  const std::string path = group.size() > 1 ? given + "." + std::to_string(group.rank()) : given;  // one per rank
  const Checkpoint checkpoint = readCheckpoint(path);
  std::error_code ec;
  fs::current_path(checkpoint.directory, ec);  // the render's paths are relative to it
  if (ec) throw InputError({path, 0}, "cannot enter the render's directory '" + checkpoint.directory + "': " + ec.message());
  CLI::App app;
  RenderArgs a;
  addRenderCommand(app, a);
  std::vector<std::string> argv{"erpt", "render"};
  argv.insert(argv.end(), checkpoint.args.begin(), checkpoint.args.end());
  std::vector<const char*> cargs;
  for (const std::string& s : argv) cargs.push_back(s.c_str());
  try {
    app.parse(int(cargs.size()), cargs.data());
  } catch (const CLI::ParseError& e) {
    throw InputError({path, 0}, std::string("checkpoint holds arguments this erpt does not take: ") + e.what());
  }
  a.commandArgs = checkpoint.args;
  a.given = givenOptions(*app.get_subcommand("render"));
  a.checkpoint = given;  // runRender adds the rank in a split render
  a.resumeFrom = &checkpoint;
  if (r.threads >= 0) a.threads = r.threads;
  a.quiet = a.quiet || r.quiet;
  return runRender(a);
}

Scene loadSceneFor(const RenderArgs& a) {
  LoadOptions load;
  load.defines = parseDefines(a.defines);
  load.tessellateSpheres = a.tessellateSpheres;
  Scene scene = loadScene(a.scene, load);
  for (const std::string& w : scene.warnings.messages) std::cerr << w << "\n";
  return scene;
}

RenderSettings settingsFromArgs(const RenderArgs& a, const Scene& scene) {
  RenderRequest r;
  r.integrator = a.integrator;
  r.spp = a.spp;
  r.width = a.width;
  r.height = a.height;
  r.threads = a.threads;
  r.maxDepth = a.maxDepth;
  r.seed = a.seed;
  r.time = a.time;
  r.filter = a.filter;
  r.given = a.given;
  const auto given = [&](const std::string& option) { return std::find(a.given.begin(), a.given.end(), option) != a.given.end(); };
  for (const IntegratorModule& m : integratorModules())
    for (const OptionSpec& o : m.options)
      if (given(o.flag()) && std::none_of(r.options.begin(), r.options.end(), [&](const auto& p) { return p.first == o.name; }))
        r.options.emplace_back(o.name, o.kind == OptionKind::Flag ? "true" : a.integratorOptions.at(o.name));
  if (given("--checkpoint-every") && a.checkpoint.empty()) throw UsageError("--checkpoint-every needs --checkpoint FILE");
  std::string note;
  RenderSettings s = settingsFor(scene, r, &note);
  if (!note.empty() && !a.quiet) std::cerr << note << "\n";
  return s;
}

int runRender(const RenderArgs& given) {
  namespace fs = std::filesystem;
  const ProcessGroup& group = ProcessGroup::current();
  RenderArgs a = given;
  if (group.size() > 1 && !a.checkpoint.empty())  // one checkpoint per rank (resume reads the same names)
    a.checkpoint += "." + std::to_string(group.rank());
  fs::path out(a.output);
  if (out.extension() != ".exr") throw UsageError("-o must name an .exr file (the PNG is written beside it)");
  fs::path dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(dir)) throw UsageError("output directory '" + dir.string() + "' does not exist");
  if (!a.checkpoint.empty() && a.time > 0) throw UsageError("--checkpoint needs a fixed --spp, not --time");
  Scene scene = loadSceneFor(a);
  RenderSettings s = settingsFromArgs(a, scene);  // an unknown integrator first, before its options are judged
  checkOptionScope(a.given, {s.integrator});
  const bool longRender = !a.checkpoint.empty() || a.writePartial > 0 || a.resumeFrom || !a.display.empty();
  if (longRender && a.time > 0) throw UsageError("--write-partial and --display need a fixed --spp, not --time");
  const uint64_t fingerprint = longRender ? sceneFingerprint(scene) : 0;
  if (group.size() > 1) s.share = group.share();
  if (a.resumeFrom) {
    if (a.resumeFrom->rank != group.rank() || a.resumeFrom->ranks != group.size())
      throw InputError({a.checkpoint, 0}, "checkpoint of rank " + std::to_string(a.resumeFrom->rank) + " of " +
                                              std::to_string(a.resumeFrom->ranks) + " processes; this is rank " +
                                              std::to_string(group.rank()) + " of " + std::to_string(group.size()));
    if (a.resumeFrom->sceneFingerprint != fingerprint)
      throw InputError({a.checkpoint, 0}, "checkpoint belongs to another scene ('" + a.scene +
                                              "' or a file it loads changed since the checkpoint was written)");
    s.resume = &a.resumeFrom->state;
  }
  Progress progress(!a.quiet && group.leader());
  s.progress = [&](double f) { progress.update(f); };
  const StopOnSignal stop;
  s.stop = stop.flag();
  const RenderSettings resolved = resolveSettings(scene, s);
  const int ranks = group.size(), ownSpp = (resolved.spp - group.rank() + ranks - 1) / ranks;  // this rank's passes
  PassWriter passWriter(a, fingerprint, resolved.width, resolved.height, ownSpp, s.share);
  if (passWriter.active())
    s.onPasses = [&](const RenderState& state, const std::function<RgbImage()>& image) { passWriter.onPasses(state, image); };
  RenderStats stats;
  RgbImage image = render(scene, s, stats);
  progress.end();
  passWriter.finish(stats.spp > 0 ? &image : nullptr);
  RenderSettings r = resolveSettings(scene, s);
  const std::string resumeCommand = (ranks > 1 ? "mpirun -n " + std::to_string(ranks) + " " : std::string()) +
                                    "erpt resume " + given.checkpoint;
  if (!group.leader()) return stats.partial ? stop.exitStatus() : 0;  // rank 0 writes the image
  if (stats.partial && stats.spp == 0 && !(stats.keptSpp > 0)) {
    std::fprintf(stderr, "%s: stopped before the first sample pass completed: no image written%s\n", s.integrator.c_str(),
                 a.checkpoint.empty() ? "" : ("; continue with: " + resumeCommand).c_str());
    return stop.exitStatus();
  }
  const std::string partialNote = partialRenderNote(r, stats) + " (stopped by signal " + std::to_string(stop.signal()) + ")";
  if (stats.partial) image.metadata.emplace_back("erpt:partial", partialNote);

  fs::path png = out;
  png.replace_extension(".png");
  // Extra images first: the main image appears last, once everything else is written.
  for (const auto& [name, extra] : stats.extraImages) {
    fs::path p = out;
    p.replace_filename(out.stem().string() + "-" + name + ".exr");
    writeImageAtomic(p.string(), extra);
    // Counts and per-pixel statistics: EXR only.
    if (name != "proposals" && name != "strategy" && name != "mutations") writePngAtomic(fs::path(p).replace_extension(".png").string(), extra);
  }
  writeImagePair(out.string(), image, a.threads);
  std::fprintf(stderr, "%s: %dx%d, %d spp%s, %llu samples in %.2f s, %.2f Mrays/s, %llu invalid samples dropped -> %s, %s\n",
               s.integrator.c_str(), r.width, r.height, stats.spp,
               stats.passes > 1 ? (" in " + std::to_string(stats.passes) + " passes").c_str() : "",
               (unsigned long long)stats.samples, stats.seconds,
               stats.seconds > 0 ? double(stats.rays) / stats.seconds * 1e-6 : 0.0,
               (unsigned long long)stats.invalidSamples, out.string().c_str(), png.string().c_str());
  if (stats.refusedRays > 0)
    std::fprintf(stderr, "%s: warning: %llu rays with a non-finite origin or direction were not traced (a bug: please report the scene)\n",
                 s.integrator.c_str(), (unsigned long long)stats.refusedRays);
  if (const auto print = integratorNamed(s.integrator).printSummary) print(stats);
  if (a.resumeFrom) std::fprintf(stderr, "%s: resumed after %d of %d samples per pixel%s\n", s.integrator.c_str(),
                                 a.resumeFrom->state.passesDone, ownSpp, ranks > 1 ? " (of rank 0)" : "");
  if (ranks > 1) std::fprintf(stderr, "%s: rendered by %d processes (samples per pixel, samples and rays are their total)\n",
                              s.integrator.c_str(), ranks);
  if (!stats.partial) return 0;
  std::fprintf(stderr, "%s: PARTIAL image: %s%s\n", s.integrator.c_str(), partialNote.c_str(),
               a.checkpoint.empty() ? "" : ("; continue with: " + resumeCommand).c_str());
  return stop.exitStatus();
}

}  // namespace erpt::cli
