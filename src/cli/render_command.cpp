#include <algorithm>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "erpt/error.h"
#include "erpt/integrators.h"
#include "erpt/render.h"
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

static void addPmcOptions(CLI::App* cmd, RenderArgs& a);
static void addMltOptions(CLI::App* cmd, RenderArgs& a);

void addRenderOptions(CLI::App* cmd, RenderArgs& a) {
  cmd->add_option("--spp", a.spp, "Samples per pixel (default: the scene's sample_count)")->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--width", a.width, "Image width in pixels (default: the scene's film)")->check(CLI::Range(1, 65536));
  cmd->add_option("--height", a.height, "Image height in pixels (default: the scene's film)")->check(CLI::Range(1, 65536));
  cmd->add_option("--threads", a.threads, "Worker threads (default 0 = all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--seed", a.seed, "Random seed; the same seed gives the same image for any --threads");
  cmd->add_option("--max-depth", a.maxDepth, "Longest path in segments, Mitsuba's meaning (-1 = unbounded)")
      ->check(CLI::Range(-1, 100000));
  cmd->add_option("--filter", a.filter, "Pixel filter: box, tent or gaussian (default: the scene's rfilter)")
      ->check(CLI::IsMember({"box", "tent", "gaussian"}));
  cmd->add_option("--film", a.film, "Path tracer's film: fis (filter importance sampling: each sample counts in its own pixel), splat (samples uniform in the pixel, splatted over the filter, normalized by the weights: Mitsuba's and pbrt-v3's), splat-unbiased (normalized by the expected weights) or auto (default: per filter, see README)")
      ->check(CLI::IsMember({"auto", "fis", "splat", "splat-unbiased"}));
  cmd->add_option("-D,--define", a.defines, "Override a scene <default>: -D name=value (repeatable)");
  cmd->add_flag("-q,--quiet", a.quiet, "No progress output");
  cmd->add_flag("--tessellate-spheres", a.tessellateSpheres, "Load sphere shapes as 256 x 512 triangle meshes instead of exact spheres (for comparisons)");
  ErptSettings& e = a.erpt;
  cmd->add_option("--mutations-per-pixel", e.mutationsPerPixel, "ERPT: mutations per pixel M (sets e_d = spp * e_ave / M)")
      ->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--chain-length", e.chainLength, "ERPT: steps m of every chain (paper: 100-1000)")
      ->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--lens-radius", e.lensRadius, "ERPT: half-side in pixels of the square lens perturbations move in (4.5 = the paper's 9x9)")
      ->check(CLI::Range(0.01, 10000.0));
  cmd->add_option("--mutation-strategy", a.strategy, "ERPT: paper (caustic for L...SDE paths, lens otherwise), mixed (a coin when both apply), lens or caustic (one kind only)")
      ->check(CLI::IsMember({"paper", "mixed", "lens", "caustic"}));
  cmd->add_option("--lens-shape", a.lensShape, "ERPT: lens perturbations move the film position uniformly in a square of half-side --lens-radius (square, the paper's) or in a disk of that radius (disk, PMC-ER's)")
      ->check(CLI::IsMember({"square", "disk"}));
  cmd->add_option("--caustic-angle", a.causticAngle, "ERPT: caustic perturbation angle: erpt (density 1/theta on [1e-4, 0.1] rad) or veach (uniform in [0, theta_max], PMC-ER eq. 6, for an image move of --lens-radius pixels)")
      ->check(CLI::IsMember({"erpt", "veach"}));
  cmd->add_option("--pilot-spp", e.pilotSpp, "ERPT: samples per pixel of the pilot pass estimating e_ave")
      ->check(CLI::Range(1, 1 << 16));
  cmd->add_option("--deposit", a.deposit, "ERPT: paper (all of a step's energy at the chain's path) or expected ((1-q) at y, q at z)")
      ->check(CLI::IsMember({"paper", "expected"}));
  cmd->add_option("--flow", a.flow, "ERPT flow rule: equal-deposition (default, paper section 3.2) or detailed-balance (section 3.1: each seed is mutated --chain-length times and never moves)")
      ->check(CLI::IsMember({"equal-deposition", "detailed-balance"}));
  cmd->add_flag("--pm-filter", a.pmFilter, "ERPT: proposed-mutations noise filter (paper 4.4; biased); also writes OUT-raw.exr (unfiltered) and OUT-proposals.exr (the tally)");
  cmd->add_option("--pm-filter-radius", e.pmFilterRadius, "ERPT: box radius of the proposed-mutations filter (3 = the paper's 7x7); implies --pm-filter")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--max-consecutive", e.maxConsecutive, "ERPT: consecutive-sample noise filter (paper 4.4; biased): a chain's deposits are dropped after N in a row on one pixel (paper: 10-20; 0 = off)")
      ->check(CLI::Range(0, 1 << 30));
  cmd->add_option("--max-chains-per-seed", e.maxChainsPerSeed, "ERPT: at most this many chains per seed (default 4096); a seed that would start more starts this many, each depositing more per step (same total)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--direct-samples", e.directSamples, "ERPT: one-bounce paths by a direct-lighting pass with N samples per pixel (default 64); -1: ERPT renders them too, as in the paper")
      ->check(CLI::Range(-1, 1 << 16));
  addPmcOptions(cmd, a);
  addMltOptions(cmd, a);
}

static void addMltOptions(CLI::App* cmd, RenderArgs& a) {
  MltSettings& m = a.mlt;
  cmd->add_option("--large-step-prob", m.largeStepProbability, "MLT: probability that a chain step is a large step, a fresh path-tracer sample through a uniform pixel (default 0.3)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--bootstrap", m.bootstrapSpp, "MLT: path-tracer samples per pixel of the bootstrap that estimates the image's luminance b and seeds the chains (default 0: enough for 100,000 samples, at least 1 per pixel)")
      ->check(CLI::Range(0, 65536));
  cmd->add_option("--chains", m.chains, "MLT: Markov chains, started by resampling the bootstrap's paths by luminance (default 2048); each runs mutations-per-pixel x pixels / chains steps")
      ->check(CLI::Range(1, 100000000));
}

static void addPmcOptions(CLI::App* cmd, RenderArgs& a) {
  PmcSettings& p = a.pmc;
  cmd->add_option("--pmc-flow", a.pmcFlow, "PMC-ER: equal-deposition (default, paper figure 2: members are Metropolis chains depositing equally per step) or balance (figure 3: members stay, each proposal receives its share times q)")
      ->check(CLI::IsMember({"equal-deposition", "balance"}));
  cmd->add_option("--population", p.population, "PMC-ER: members in the population (default 5000)")->check(CLI::Range(1, 10000000));
  cmd->add_option("--mutations-per-member", p.mutationsPerMember, "PMC-ER: mutations of every member per iteration (default 16)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--radii", a.radii, "PMC-ER: perturbation radii of the mixture in pixels, comma separated (default 5,10,50)");
  cmd->add_option("--pmc-adapt", a.pmcAdapt, "PMC-ER: mixture weights per image region, learned by an independent training population and frozen (region, default: unbiased), per member from its own acceptances (member, the paper's: can bias), or uniform (off)")
      ->check(CLI::IsMember({"region", "member", "off"}));
  cmd->add_option("--resample-rate", p.resampleRate, "PMC-ER: share of the population regenerated from the pool per iteration, and of a member's energy deposited per iteration (default 0.4)")
      ->check(CLI::Range(1e-3, 1.0));
  cmd->add_option("--alpha-floor", p.alphaFloor, "PMC-ER: smallest mixture weight eps (default 0.05)")->check(CLI::Range(0.0, 0.5));
  cmd->add_option("--caustic-prob", p.causticProb, "PMC-ER: probability of the caustic perturbation where it applies (gamma_caustic, default 0.9)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--pmc-region", p.regionSize, "PMC-ER region adaptation: side of the square regions in pixels (default 16)")
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--pmc-train-iterations", p.trainIterations, "PMC-ER region adaptation: iterations of the training population (default 4)")
      ->check(CLI::Range(1, 100000));
}

void addRenderCommand(CLI::App& app, RenderArgs& a) {
  CLI::App* cmd = app.add_subcommand("render", "Render a Mitsuba XML scene to a linear EXR and a tone-mapped PNG");
  cmd->add_option("scene", a.scene, "Scene file (Mitsuba 0.6 or 3 XML)")->required();
  cmd->add_option("-o,--output", a.output, "Output EXR path; the PNG is written beside it")->required();
  std::string integrators;
  for (const IntegratorModule& m : integratorModules()) integrators += (integrators.empty() ? "" : "; ") + m.name + ": " + m.description;
  cmd->add_option("--integrator", a.integrator, "Integrator (default: the scene's, if it is one of these, else path). " + integrators);
  cmd->add_option("--time", a.time, "Render for this many seconds instead of --spp samples per pixel (passes of growing spp; the image then depends on the machine's speed)")
      ->check(CLI::Range(1e-3, 1e7));
  cmd->add_option("--checkpoint", a.checkpoint, "Write the render's state to FILE (atomically) every --checkpoint-every seconds and when it ends or is stopped; continue it with `erpt resume FILE` (path, direct, erpt, pmc-er)");
  cmd->add_option("--checkpoint-every", a.checkpointEvery, "Seconds between checkpoints (default 300; written at the end of a group of sample passes)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--display", a.display, "Stream the image as it converges to the tev viewer listening at HOST:PORT (tev's default: 127.0.0.1:14158)");
  cmd->add_option("--write-partial", a.writePartial, "Write the image of the sample passes completed so far to the output every this many seconds (path, direct, erpt, pmc-er)")
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

static std::vector<float> parseRadii(const std::string& text) {
  std::vector<float> radii;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    size_t used = 0;
    float r = 0;
    try {
      r = std::stof(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size()) throw UsageError("--radii expects comma-separated numbers, got '" + text + "'");
    radii.push_back(r);
    start = comma + 1;
  }
  return radii;
}

RenderSettings settingsFromArgs(const RenderArgs& a, const Scene& scene) {
  if (a.maxDepth == 0) throw UsageError("--max-depth must be -1 (unbounded) or at least 1");
  RenderSettings s;
  const bool sceneIntegratorKnown = findIntegrator(scene.integrator.type) != nullptr;
  s.integrator = !a.integrator.empty() ? a.integrator : sceneIntegratorKnown ? scene.integrator.type : "path";
  s.width = a.width;
  s.height = a.height;
  s.spp = a.spp;
  s.maxDepth = a.maxDepth;
  s.seed = a.seed;
  s.threads = a.threads;
  s.erpt = a.erpt;
  s.erpt.strategy = a.strategy == "mixed"  ? MutationStrategy::Mixed
                    : a.strategy == "lens" ? MutationStrategy::LensOnly
                    : a.strategy == "caustic" ? MutationStrategy::CausticOnly
                                              : MutationStrategy::Paper;
  s.erpt.expectedDeposit = a.deposit == "expected";
  s.erpt.lensShape = a.lensShape == "disk" ? LensShape::Disk : LensShape::Square;
  s.erpt.causticAngle = a.causticAngle == "veach" ? CausticAngle::Veach : CausticAngle::Erpt;
  s.erpt.flow = a.flow == "detailed-balance" ? FlowRule::DetailedBalance : FlowRule::EqualDeposition;
  if (a.pmFilter && s.erpt.pmFilterRadius < 0) s.erpt.pmFilterRadius = 3;
  s.pmc = a.pmc;
  s.mlt = a.mlt;
  s.pmc.flow = a.pmcFlow == "balance" ? PmcFlow::Balance : PmcFlow::EqualDeposition;
  s.pmc.adapt = a.pmcAdapt == "member" ? PmcAdapt::Member : a.pmcAdapt == "off" ? PmcAdapt::Off : PmcAdapt::Region;
  s.pmc.radii = parseRadii(a.radii);
  s.film = a.film == "fis" ? FilmMode::Fis : a.film == "splat" ? FilmMode::Splat
          : a.film == "splat-unbiased" ? FilmMode::SplatUnbiased : FilmMode::Auto;
  s.timeBudget = a.time;
  const auto given = [&](const char* option) { return std::find(a.given.begin(), a.given.end(), option) != a.given.end(); };
  if (s.integrator == "mlt" && given("--spp")) {
    // Mitsuba's MLT takes its sampler's sample count as the mutations per pixel.
    if (given("--mutations-per-pixel"))
      throw UsageError("for mlt --spp is the mutations per pixel (as Mitsuba's sample count): give --spp or --mutations-per-pixel, not both");
    s.erpt.mutationsPerPixel = a.spp;
  }
  for (const char* option : {"--pmc-region", "--pmc-train-iterations"})
    if (given(option) && s.pmc.adapt != PmcAdapt::Region)
      throw UsageError(std::string(option) + " applies to pmc-er with --pmc-adapt region only");
  if (given("--alpha-floor") && s.pmc.adapt == PmcAdapt::Off)
    throw UsageError("--alpha-floor has no effect on pmc-er with --pmc-adapt off (the weights stay uniform)");
  if (given("--checkpoint-every") && a.checkpoint.empty()) throw UsageError("--checkpoint-every needs --checkpoint FILE");
  if (!a.filter.empty()) {
    s.filterSet = true;
    s.filter = a.filter == "box" ? FilterKind::Box : a.filter == "tent" ? FilterKind::Tent : FilterKind::Gaussian;
  }
  if (a.integrator.empty() && !sceneIntegratorKnown && !a.quiet)
    std::cerr << "note: the scene asks for integrator '" << scene.integrator.type << "'; rendering with '"
              << s.integrator << "'\n";
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
  RenderSettings s = settingsFromArgs(a, scene);
  integratorNamed(s.integrator);  // an unknown name first, before its options are judged
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
  if (stats.partial && stats.spp == 0) {
    std::fprintf(stderr, "%s: stopped before the first sample pass completed: no image written%s\n", s.integrator.c_str(),
                 a.checkpoint.empty() ? "" : ("; continue with: " + resumeCommand).c_str());
    return stop.exitStatus();
  }
  const std::string partialNote =
      std::to_string(stats.spp) + " of " + std::to_string(r.spp) + " samples per pixel (stopped by signal " +
      std::to_string(stop.signal()) + ")";
  if (stats.partial) image.metadata.emplace_back("erpt:partial", partialNote);

  fs::path png = out;
  png.replace_extension(".png");
  // Extra images first: the main image appears last, once everything else is written.
  for (const auto& [name, extra] : stats.extraImages) {
    fs::path p = out;
    p.replace_filename(out.stem().string() + "-" + name + ".exr");
    writeImageAtomic(p.string(), extra);
    // Counts and per-pixel statistics: EXR only.
    if (name != "proposals" && name != "strategy") writePngAtomic(fs::path(p).replace_extension(".png").string(), extra);
  }
  writeImagePair(out.string(), image);
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
