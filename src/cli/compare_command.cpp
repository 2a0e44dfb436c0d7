// `erpt compare SCENE --reference REF --time S [--integrators path,erpt,...]`: every integrator
// gets the same wall-clock budget; the report gives error, error per time (Eff = 1 / (T MSE),
// as in the PMC-ER paper's Table 1) and a log-log plot of error versus time from the images
// each render had after every pass.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "erpt/erpt_settings.h"
#include "commands.h"
#include "option_scope.h"
#include "erpt/error.h"
#include "erpt/integrators.h"
#include "io/error_heatmap.h"
#include "python_plot.h"
#include "erpt/image_metrics.h"
#include "erpt/pssmlt_settings.h"

namespace erpt::cli {

namespace {

struct CompareRow {
  std::string integrator;
  double seconds = 0;
  int spp = 0, passes = 0;
  uint64_t mutations = 0;
  ImageComparison error;
  std::vector<double> curveSeconds, curveMse, curveRelMse;  // the error after every pass
};

// One entry of --integrators: `NAME` or `NAME[OPTIONS]`, OPTIONS being render options that
// apply to this entry only (e.g. `erpt[--pm-filter --max-consecutive 20]`).
struct IntegratorEntry {
  std::string label;  // the entry as written: the row's name
  RenderSettings settings;
};

std::vector<std::string> splitEntries(const std::string& list) {
  std::vector<std::string> out;
  std::string item;
  int depth = 0;
  for (char c : list) {
    depth += c == '[' ? 1 : c == ']' ? -1 : 0;
    if (c == ',' && depth == 0) {
      if (!item.empty()) out.push_back(item);
      item.clear();
    } else {
      item += c;
    }
  }
  if (depth != 0) throw UsageError("--integrators: unbalanced [ ] in '" + list + "'");
  if (!item.empty()) out.push_back(item);
  return out;
}

IntegratorEntry parseEntry(const std::string& entry, const RenderArgs& common, const Scene& scene) {
  IntegratorEntry out{entry, {}};
  RenderArgs args = common;
  const size_t open = entry.find('[');
  args.integrator = entry.substr(0, open);
  if (!findIntegrator(args.integrator))
    throw UsageError("unknown integrator '" + args.integrator + "' in --integrators (available: " + integratorNames() + ")");
  if (open != std::string::npos) {
    if (entry.back() != ']') throw UsageError("--integrators entry '" + entry + "' must end with ']'");
    CLI::App options{"options of one --integrators entry"};
    addRenderOptions(&options, args);
    try {
      options.parse(entry.substr(open + 1, entry.size() - open - 2), false);
    } catch (const CLI::ParseError& e) {
      throw UsageError("--integrators entry '" + entry + "': " + e.what());
    }
    const std::vector<std::string> own = givenOptions(options);
    checkOptionScope(own, {args.integrator});
    args.given.insert(args.given.end(), own.begin(), own.end());
  }
  out.settings = resolveSettings(scene, settingsFromArgs(args, scene));
  return out;
}

// A file name for a row label: letters, digits, '-' and '_' kept, the rest '-'.
std::string fileStem(const std::string& label) {
  std::string out;
  for (char c : label) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '-';
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out + "\"";
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", std::isfinite(v) ? v : 0.0);
  return buf;
}

double efficiency(double seconds, double error) { return seconds > 0 && error > 0 ? 1.0 / (seconds * error) : 0.0; }

std::string markdownTable(const std::vector<CompareRow>& rows) {
  std::ostringstream md;
  md << "| integrator | time (s) | spp | mutations | MSE | relMSE | Eff = 1/(T MSE) | Eff_rel = 1/(T relMSE) |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const CompareRow& r : rows) {
    std::snprintf(line, sizeof line, "| %s | %.2f | %d | %s | %.3g | %.3g | %.4g | %.4g |\n", r.integrator.c_str(), r.seconds,
                  r.spp, r.mutations ? std::to_string(r.mutations).c_str() : "-", r.error.mse, r.error.relMse,
                  efficiency(r.seconds, r.error.mse), efficiency(r.seconds, r.error.relMse));
    md << line;
  }
  return md.str();
}

// `downsampled`: the factor by which the reference was box-averaged (1: the render's size).
std::string jsonReport(const CompareArgs& a, const RenderSettings& s, const std::vector<CompareRow>& rows, int downsampled) {
  std::ostringstream js;
  js << "{\n  \"command\": " << jsonString(a.commandLine) << ",\n  \"scene\": " << jsonString(a.render.scene)
     << ",\n  \"reference\": " << jsonString(a.reference) << ",\n  \"reference_downsampled\": " << downsampled
     << ",\n  \"budget_seconds\": " << number(a.time)
     << ",\n  \"width\": " << s.width << ",\n  \"height\": " << s.height << ",\n  \"results\": [";
  for (size_t i = 0; i < rows.size(); ++i) {
    const CompareRow& r = rows[i];
    js << (i ? "," : "") << "\n    {\"integrator\": " << jsonString(r.integrator) << ", \"seconds\": " << number(r.seconds)
       << ", \"spp\": " << r.spp << ", \"passes\": " << r.passes << ", \"mutations\": " << r.mutations
       << ", \"mse\": " << number(r.error.mse) << ", \"rel_mse\": " << number(r.error.relMse)
       << ", \"eff\": " << number(efficiency(r.seconds, r.error.mse))
       << ", \"eff_rel\": " << number(efficiency(r.seconds, r.error.relMse)) << ", \"nonfinite_pixels\": " << r.error.nonFinite
       << ",\n     \"curve\": [";
    for (size_t k = 0; k < r.curveSeconds.size(); ++k)
      js << (k ? ", " : "") << "{\"seconds\": " << number(r.curveSeconds[k]) << ", \"mse\": " << number(r.curveMse[k])
         << ", \"rel_mse\": " << number(r.curveRelMse[k]) << "}";
    js << "]}";
  }
  js << "\n  ]\n}\n";
  return js.str();
}

void writeTextAtomic(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".partial";
  {
    std::ofstream out(tmp);
    out << text;
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

void addCompareCommand(CLI::App& app, CompareArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "compare", "Render a scene with several integrators for the same time and compare their error against a reference");
  cmd->add_option("scene", a.render.scene, "Scene file (Mitsuba 0.6 or 3 XML)")->required();
  cmd->add_option("--reference", a.reference, "Converged reference image (the render's size, or an integer multiple)")->required();
  cmd->add_option("--time", a.time, "Wall-clock budget of every integrator, in seconds")->required()->check(CLI::Range(1e-3, 1e6));
  cmd->add_option("--integrators", a.integrators, "Comma-separated integrators (default path,erpt); an entry may carry its own render options in brackets, e.g. 'path,erpt,erpt[--pm-filter --max-consecutive 20]'");
  cmd->add_option("--out", a.outDir, "Directory for the report (compare.md, compare.json, compare.png) and each integrator's image and error heat map (default compare-out)");
  cmd->add_flag("--json", a.json, "Print the JSON report on stdout instead of the Markdown table (both are written to --out)");
  addRenderOptions(cmd, a.render);
}

int runCompare(const CompareArgs& a) {
  namespace fs = std::filesystem;
  const RgbImage referenceFile = readImage(a.reference);
  const Scene scene = loadSceneFor(a.render);
  RenderArgs common = a.render;
  common.integrator = defaultIntegrator().name;  // the size and filter are all `base` is for
  const RenderSettings base = resolveSettings(scene, settingsFromArgs(common, scene));
  std::vector<IntegratorEntry> entries;
  for (const std::string& e : splitEntries(a.integrators)) {
    entries.push_back(parseEntry(e, a.render, scene));
    if (entries.back().settings.width != base.width || entries.back().settings.height != base.height)
      throw UsageError("--integrators entry '" + e + "' changes the image size; give --width/--height outside the brackets");
  }
  if (entries.empty()) throw UsageError("--integrators names no integrator");
  // An option outside the brackets applies to every entry that uses it; it must fit one.
  std::vector<std::string> raced;
  for (const std::string& e : splitEntries(a.integrators)) raced.push_back(e.substr(0, e.find('[')));
  checkOptionScope(a.render.given, raced);
  const RgbImage reference = matchReferenceSize(referenceFile, base.width, base.height);  // size errors before rendering
  const std::string sizeNote = referenceSizeNote(referenceFile, base.width, base.height);
  if (!sizeNote.empty()) std::cerr << "compare: " << sizeNote << "\n";
  std::error_code ec;
  fs::create_directories(a.outDir, ec);
  if (!fs::is_directory(a.outDir)) throw UsageError("cannot create output directory '" + a.outDir + "'");

  std::vector<CompareRow> rows;
  for (const IntegratorEntry& entry : entries) {
    const std::string& name = entry.label;
    CompareRow row;
    row.integrator = name;
    RenderSettings s = entry.settings;
    s.timeBudget = a.time;
    s.onPass = [&](const RgbImage& img, double seconds, int) {
      const ImageComparison c = compareImages(img, reference);
      row.curveSeconds.push_back(seconds);
      row.curveMse.push_back(c.mse);
      row.curveRelMse.push_back(c.relMse);
    };
    if (!a.render.quiet) std::cerr << "compare: " << name << ", " << a.time << " s\n";
    RenderStats stats;
    const RgbImage image = render(scene, s, stats);
    row.seconds = row.curveSeconds.empty() ? stats.seconds : row.curveSeconds.back();
    row.spp = stats.spp;
    row.passes = stats.passes;
    row.mutations = chainStatsOf(stats).mutations + pssmltStatsOf(stats).smallSteps + pssmltStatsOf(stats).largeSteps;
    row.error = compareImages(image, reference);
    const fs::path out = fs::path(a.outDir) / fileStem(name);
    writeImageAtomic(out.string() + ".exr", image);
    writePngAtomic(out.string() + ".png", image);
    errorHeatmap(image, reference).writePng(out.string() + "-error.png");
    rows.push_back(std::move(row));
  }

  const std::string table = markdownTable(rows);
  const std::string json = jsonReport(a, base, rows, referenceFile.width / base.width);
  const fs::path jsonPath = fs::path(a.outDir) / "compare.json", plotPath = fs::path(a.outDir) / "compare.png";
  writeTextAtomic(jsonPath, json);
  writeTextAtomic(fs::path(a.outDir) / "compare.md",
                  "`" + a.commandLine + "`\n\n" + (sizeNote.empty() ? "" : "Note: " + sizeNote + ".\n\n") + table);
  // The plot is drawn by the Python package (python/erpt/plot.py, matplotlib).
  const std::string plotted = plotComparison(jsonPath.string(), plotPath.string());
  if (!plotted.empty()) std::cerr << "compare: no compare.png: " << plotted << "\n";
  std::cout << (a.json ? json : table);
  std::cerr << "compare: wrote " << (fs::path(a.outDir) / (plotted.empty() ? "compare.{md,json,png}" : "compare.{md,json}")).string()
            << " and each integrator's image and error heat map\n";
  return 0;
}

}  // namespace erpt::cli
