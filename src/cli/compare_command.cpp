// `erpt compare SCENE --reference REF --time S [--integrators path,erpt,...]`: every integrator
// gets the same wall-clock budget; the report gives error, error per time (Eff = 1 / (T MSE),
// as in the PMC-ER paper's Table 1) and a log-log plot of error versus time from the images
// each render had after every pass.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "erpt/error.h"
#include "erpt/error_plots.h"
#include "erpt/image_metrics.h"

namespace erpt::cli {

namespace {

struct CompareRow {
  std::string integrator;
  double seconds = 0;
  int spp = 0, passes = 0;
  uint64_t mutations = 0;
  ImageComparison error;
  ErrorSeries series;
};

std::vector<std::string> splitList(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
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

std::string jsonReport(const CompareArgs& a, const RenderSettings& s, const std::vector<CompareRow>& rows) {
  std::ostringstream js;
  js << "{\n  \"command\": " << jsonString(a.commandLine) << ",\n  \"scene\": " << jsonString(a.render.scene)
     << ",\n  \"reference\": " << jsonString(a.reference) << ",\n  \"budget_seconds\": " << number(a.time)
     << ",\n  \"width\": " << s.width << ",\n  \"height\": " << s.height << ",\n  \"results\": [";
  for (size_t i = 0; i < rows.size(); ++i) {
    const CompareRow& r = rows[i];
    js << (i ? "," : "") << "\n    {\"integrator\": " << jsonString(r.integrator) << ", \"seconds\": " << number(r.seconds)
       << ", \"spp\": " << r.spp << ", \"passes\": " << r.passes << ", \"mutations\": " << r.mutations
       << ", \"mse\": " << number(r.error.mse) << ", \"rel_mse\": " << number(r.error.relMse)
       << ", \"eff\": " << number(efficiency(r.seconds, r.error.mse))
       << ", \"eff_rel\": " << number(efficiency(r.seconds, r.error.relMse)) << ", \"nonfinite_pixels\": " << r.error.nonFinite
       << ",\n     \"curve\": [";
    for (size_t k = 0; k < r.series.seconds.size(); ++k)
      js << (k ? ", " : "") << "{\"seconds\": " << number(r.series.seconds[k]) << ", \"mse\": " << number(r.series.mse[k])
         << ", \"rel_mse\": " << number(r.series.relMse[k]) << "}";
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
  cmd->add_option("--integrators", a.integrators, "Comma-separated integrators (default path,erpt)");
  cmd->add_option("--out", a.outDir, "Directory for the report (compare.md, compare.json, compare.png) and each integrator's image and error heat map (default compare-out)");
  addRenderOptions(cmd, a.render);
}

int runCompare(const CompareArgs& a) {
  namespace fs = std::filesystem;
  const std::vector<std::string> integrators = splitList(a.integrators);
  if (integrators.empty()) throw UsageError("--integrators names no integrator");
  for (const std::string& name : integrators)
    if (name != "path" && name != "erpt" && name != "direct")
      throw UsageError("unknown integrator '" + name + "' in --integrators (available: " + integratorNames() + ")");
  const RgbImage referenceFile = readImage(a.reference);
  const Scene scene = loadSceneFor(a.render);
  RenderSettings base = resolveSettings(scene, settingsFromArgs(a.render, scene));
  const RgbImage reference = matchReferenceSize(referenceFile, base.width, base.height);  // size errors before rendering
  std::error_code ec;
  fs::create_directories(a.outDir, ec);
  if (!fs::is_directory(a.outDir)) throw UsageError("cannot create output directory '" + a.outDir + "'");

  std::vector<CompareRow> rows;
  for (const std::string& name : integrators) {
    CompareRow row;
    row.integrator = row.series.name = name;
    RenderSettings s = base;
    s.integrator = name;
    s.timeBudget = a.time;
    s.onPass = [&](const RgbImage& img, double seconds, int) {
      const ImageComparison c = compareImages(img, reference);
      row.series.seconds.push_back(seconds);
      row.series.mse.push_back(c.mse);
      row.series.relMse.push_back(c.relMse);
    };
    if (!a.render.quiet) std::cerr << "compare: " << name << ", " << a.time << " s\n";
    RenderStats stats;
    const RgbImage image = render(scene, s, stats);
    row.seconds = row.series.seconds.empty() ? stats.seconds : row.series.seconds.back();
    row.spp = stats.spp;
    row.passes = stats.passes;
    row.mutations = stats.erpt.mutations;
    row.error = compareImages(image, reference);
    const fs::path out = fs::path(a.outDir) / name;
    writeImageAtomic(out.string() + ".exr", image);
    writePngAtomic(out.string() + ".png", image);
    errorHeatmap(image, reference).writePng(out.string() + "-error.png");
    rows.push_back(std::move(row));
  }

  const std::string table = markdownTable(rows);
  std::vector<ErrorSeries> series;
  for (const CompareRow& r : rows) series.push_back(r.series);
  const std::string title = fs::path(a.render.scene).parent_path().filename().string() + " " +
                            std::to_string(base.width) + "X" + std::to_string(base.height) + ", " + number(a.time) +
                            " S EACH";
  errorVsTimePlot(series, title).writePng((fs::path(a.outDir) / "compare.png").string());
  writeTextAtomic(fs::path(a.outDir) / "compare.json", jsonReport(a, base, rows));
  writeTextAtomic(fs::path(a.outDir) / "compare.md", "`" + a.commandLine + "`\n\n" + table);
  std::cout << table;
  std::cerr << "compare: wrote " << (fs::path(a.outDir) / "compare.{md,json,png}").string() << " and each integrator's image and error heat map\n";
  return 0;
}

}  // namespace erpt::cli
