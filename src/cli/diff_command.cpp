// `erpt diff IMAGE REFERENCE [--heatmap OUT.png]`: error metrics of an image against a
// reference, and a false-colour map of where the error is.
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "erpt/error.h"
#include "io/error_heatmap.h"
#include "erpt/image_metrics.h"

namespace erpt::cli {

void addDiffCommand(CLI::App& app, DiffArgs& a) {
  CLI::App* cmd = app.add_subcommand("diff", "Compare an image with a reference: MSE, relMSE, channel means");
  cmd->add_option("image", a.image, "Image (any format OpenImageIO reads)")->required();
  cmd->add_option("reference", a.reference, "Reference (the same size, or an integer multiple: box-downsampled)")
      ->required();
  cmd->add_option("--heatmap", a.heatmap, "Also write a false-colour PNG of the per-pixel relative squared error (log scale, 1e-5 to 1)");
}

int runDiff(const DiffArgs& a) {
  const RgbImage image = readImage(a.image), reference = readImage(a.reference);
  const ImageComparison c = compareImages(image, reference);
  // A reference of another size is never compared silently: the downsampling is printed.
  const std::string note = referenceSizeNote(reference, image.width, image.height);
  if (!note.empty()) std::printf("reference_downsampled %d (%s)\n", reference.width / image.width, note.c_str());
  if (!a.heatmap.empty()) {
    if (std::filesystem::path(a.heatmap).extension() != ".png") throw UsageError("--heatmap must name a .png file");
    errorHeatmap(image, matchReferenceSize(reference, image.width, image.height)).writePng(a.heatmap);
  }
  std::printf("mse %.6g\nrelmse %.6g\n", c.mse, c.relMse);
  std::printf("mean %.6g %.6g %.6g\nreference_mean %.6g %.6g %.6g\n", c.mean.x, c.mean.y, c.mean.z,
              c.referenceMean.x, c.referenceMean.y, c.referenceMean.z);
  auto ratio = [](float a, float b) { return b != 0 ? double(a) / double(b) : 0.0; };
  std::printf("mean_ratio %.6f %.6f %.6f\nnonfinite_pixels %zu\n", ratio(c.mean.x, c.referenceMean.x),
              ratio(c.mean.y, c.referenceMean.y), ratio(c.mean.z, c.referenceMean.z), c.nonFinite);
  const double pixels = double(image.pixels.size());
  std::printf("black_pixels %zu (%.2f%%), %zu where the reference is not black (%.2f%%)\n", c.black,
              100.0 * double(c.black) / pixels, c.blackWhereReferenceIsNot, 100.0 * double(c.blackWhereReferenceIsNot) / pixels);
  if (!a.heatmap.empty())
    std::printf("heatmap %s (per-pixel relative squared error, log scale %g dark to %g bright; cyan: non-finite)\n",
                a.heatmap.c_str(), kHeatmapLow, kHeatmapHigh);
  return 0;
}

}  // namespace erpt::cli
