// What `erpt render` does at the end of every group of sample passes (RenderSettings::onPasses):
// writes the checkpoint every --checkpoint-every seconds and the image so far every
// --write-partial seconds, both atomically, sends the image so far to the tev viewer
// (--display, at most every half second), and keeps the last state for the checkpoint written
// when the render ends (complete or stopped).
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "commands.h"
#include "io/checkpoint.h"
#include "io/tev_display.h"

namespace erpt::cli {

class PassWriter {
 public:
  // Connects to --display (a warning, and no display, when it cannot).
  // `share`: the rank of a split render (only rank 0 writes images and talks to the display).
  PassWriter(const RenderArgs& args, uint64_t sceneFingerprint, int width, int height, int totalSpp,
             const RenderShare& share);
  bool active() const { return !args_.checkpoint.empty() || args_.writePartial > 0 || display_; }
  void onPasses(const RenderState& state, const std::function<RgbImage()>& image);
  // The checkpoint of the last state seen (when --checkpoint is given); the final image to
  // the display (when there is one).
  void finish(const RgbImage* finalImage);

 private:
  using Clock = std::chrono::steady_clock;
  void writeCheckpoint();
  void sendToDisplay(const RgbImage& image);
  const RenderArgs& args_;
  Checkpoint checkpoint_;
  int totalSpp_;
  bool seen_ = false, leader_;
  Clock::time_point lastCheckpoint_, lastPartial_, lastDisplay_;
  std::unique_ptr<TevDisplay> display_;
};

// The output EXR and its PNG; `image.metadata` goes into the EXR. With threads other than 1
// (0: all cores) the two are written at once.
void writeImagePair(const std::string& exrPath, const RgbImage& image, int threads);

}  // namespace erpt::cli
