#include "erpt/image_io.h"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "erpt/error.h"
#include "io/file_util.h"
#include "image_formats.h"

namespace erpt {

namespace {

// The temporary files being written, for removePendingImageFiles(): plain buffers, so that a
// signal handler may read them; one slot per writer running at once (the CLI writes its EXR
// and PNG on two threads).
constexpr int kPendingSlots = 4;
char pendingPath[kPendingSlots][4096] = {};
std::atomic<bool> pendingClaimed[kPendingSlots] = {};

// A free slot for `tmp` (-1 when every slot is taken: the file is then not removed on a signal).
int claimPendingSlot(const std::string& tmp) {
  for (int i = 0; i < kPendingSlots; ++i) {
    bool expected = false;
    if (pendingClaimed[i].compare_exchange_strong(expected, true)) {
      std::snprintf(pendingPath[i], sizeof(pendingPath[i]), "%s", tmp.c_str());
      return i;
    }
  }
  return -1;
}

void releasePendingSlot(int slot) {
  if (slot < 0) return;
  pendingPath[slot][0] = 0;
  pendingClaimed[slot].store(false);
}

std::string temporaryPathFor(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  // Keep the extension last: OpenImageIO picks the format from it.
  return (dir / ("." + p.stem().string() + ".partial-" + std::to_string(getpid()) + p.extension().string())).string();
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Writes through `write(tmp, error)` to the temporary file, then renames it over `path`.
template <class Write>
void writeAtomic(const std::string& path, Write write) {
  std::string tmp = temporaryPathFor(path);
  const int slot = claimPendingSlot(tmp);
  auto fail = [&](const std::string& why) {
    std::remove(tmp.c_str());
    releasePendingSlot(slot);
    throw std::runtime_error("cannot write '" + path + "': " + why);
  };
  std::string error;
  if (!write(tmp, error)) fail(error);
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) fail(ec.message());
  releasePendingSlot(slot);
}

}  // namespace

void removePendingImageFiles() {
  for (const char* path : pendingPath)
    if (path[0]) unlink(path);
}

RgbImage readImage(const std::string& path, bool* isSrgbEncoded) {
  requireReadableFile(path, "image");
  RgbImage img;
  bool srgb = false;
  std::string error;
  const std::string ext = lowerExtension(path);
  const bool ok = ext == ".exr"   ? image_formats::readExr(path, img, error)
                  : ext == ".png" ? image_formats::readPng(path, img, srgb, error)
                                  : image_formats::readWithOiio(path, img, srgb, error);
  // The libraries' messages can run over several lines; the first says what went wrong.
  if (!ok) throw InputError({path, 0}, "cannot read image: " + error.substr(0, error.find_first_of("\r\n")));
  if (img.width <= 0 || img.height <= 0) throw InputError({path, 0}, "image has no pixels");
  if (isSrgbEncoded) *isSrgbEncoded = srgb;
  return img;
}

void writeImageAtomic(const std::string& path, const RgbImage& image) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") return writePngAtomic(path, image);
  writeAtomic(path, [&](const std::string& tmp, std::string& error) {
    return ext == ".exr" ? image_formats::writeExr(tmp, image, error)
                         : image_formats::writeWithOiio(tmp, image.width, image.height, true, image.pixels.data(), error);
  });
}

void setExrWriteThreads(int threads) { image_formats::setExrThreads(threads); }

void writeBytesAtomic(const std::string& path, const std::vector<uint8_t>& bytes) {
  writeAtomic(path, [&](const std::string& tmp, std::string& error) {
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) return error = std::strerror(errno), false;
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) return error = "write failed", false;
    return true;
  });
}

void writeRgb8Atomic(const std::string& path, int width, int height, const uint8_t* rgb) {
  const bool png = lowerExtension(path) == ".png";
  writeAtomic(path, [&](const std::string& tmp, std::string& error) {
    return png ? image_formats::writePng8(tmp, width, height, rgb, error)
               : image_formats::writeWithOiio(tmp, width, height, false, rgb, error);
  });
}

std::vector<uint8_t> toneMapped8(const RgbImage& image) {
  std::vector<uint8_t> bytes(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      float v = image.pixels[i][c];
      v = std::isfinite(v) ? std::min(1.0f, std::max(0.0f, v)) : 0.0f;
      v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
      bytes[i * 3 + c] = uint8_t(std::lround(v * 255.0f));
    }
  return bytes;
}

void writePngAtomic(const std::string& path, const RgbImage& image) {
  writeRgb8Atomic(path, image.width, image.height, toneMapped8(image).data());
}

}  // namespace erpt
