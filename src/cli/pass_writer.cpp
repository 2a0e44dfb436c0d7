#include "pass_writer.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <thread>

#include "erpt/image_io.h"

namespace erpt::cli {

PassWriter::PassWriter(const RenderArgs& args, uint64_t sceneFingerprint, int width, int height, int totalSpp,
                       const RenderShare& share)
    : args_(args), totalSpp_(totalSpp), leader_(share.rank == 0), lastCheckpoint_(Clock::now()),
      lastPartial_(Clock::now()), lastDisplay_(Clock::now()) {
  checkpoint_.sceneFingerprint = sceneFingerprint;
  checkpoint_.directory = std::filesystem::current_path().string();
  checkpoint_.args = args.commandArgs;
  checkpoint_.rank = share.rank;
  checkpoint_.ranks = share.ranks;
  if (!args.display.empty() && leader_) {
    try {
      display_ = std::make_unique<TevDisplay>(args.display, std::filesystem::path(args.output).filename().string(), width, height);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "warning: %s; rendering without a display\n", e.what());
    }
  }
}

void PassWriter::onPasses(const RenderState& state, const std::function<RgbImage()>& image) {
  const Clock::time_point now = Clock::now();
  auto due = [&](Clock::time_point last, double every) { return std::chrono::duration<double>(now - last).count() >= every; };
  if (!args_.checkpoint.empty()) {
    checkpoint_.state = state;
    seen_ = true;
    if (due(lastCheckpoint_, args_.checkpointEvery)) {
      writeCheckpoint();
      lastCheckpoint_ = Clock::now();
    }
  }
  if (state.passesDone == 0 || state.passesDone >= totalSpp_) return;  // no image yet; the final one comes after
  RgbImage img;  // resolved once, if someone wants it
  auto resolved = [&]() -> RgbImage& {
    if (img.pixels.empty()) img = image();
    return img;
  };
  if (args_.writePartial > 0 && leader_ && due(lastPartial_, args_.writePartial)) {
    RgbImage marked = resolved();
    marked.metadata.emplace_back("erpt:partial", std::to_string(state.passesDone) + " of " + std::to_string(totalSpp_) +
                                                     " samples per pixel (in progress)");
    writeImagePair(args_.output, marked, args_.threads);
    lastPartial_ = Clock::now();
  }
  if (display_ && due(lastDisplay_, 0.5)) {
    sendToDisplay(resolved());
    lastDisplay_ = Clock::now();
  }
}

void PassWriter::sendToDisplay(const RgbImage& image) {
  if (display_ && !display_->update(image)) {
    std::fprintf(stderr, "warning: the display at '%s' went away; rendering on without it\n", args_.display.c_str());
    display_.reset();
  }
}

void PassWriter::finish(const RgbImage* finalImage) {
  if (seen_) writeCheckpoint();
  if (finalImage) sendToDisplay(*finalImage);
}

void PassWriter::writeCheckpoint() { writeCheckpointAtomic(args_.checkpoint, checkpoint_); }

void writeImagePair(const std::string& exrPath, const RgbImage& image, int threads) {
  const std::string pngPath = std::filesystem::path(exrPath).replace_extension(".png").string();
  if (threads == 1) {
    writeImageAtomic(exrPath, image);
    writePngAtomic(pngPath, image);
    return;
  }
  // The PNG on a second thread while the EXR is compressed on OpenEXR's: at 1024x1024 the two
  // took 0.7 s one after the other (docs/performance.md).
  setExrWriteThreads(threads == 0 ? int(std::max(1u, std::thread::hardware_concurrency())) : threads);
  std::exception_ptr pngFailure;
  std::thread png([&] {
    try {
      writePngAtomic(pngPath, image);
    } catch (...) {
      pngFailure = std::current_exception();
    }
  });
  try {
    writeImageAtomic(exrPath, image);
  } catch (...) {
    png.join();
    throw;
  }
  png.join();
  if (pngFailure) std::rethrow_exception(pngFailure);
}

}  // namespace erpt::cli
