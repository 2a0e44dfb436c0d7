// OpenEXR files: RGB float, ZIP-compressed (what OpenImageIO wrote before, read the same by
// every EXR viewer). Reads R, G, B (or Y) of the first part, any pixel type, any data window.
#include <algorithm>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include "image_formats.h"

namespace erpt::image_formats {

namespace {
constexpr const char* kRgb[3] = {"R", "G", "B"};
int writeThreads = 1;
}

void setExrThreads(int threads) {
  writeThreads = std::max(1, threads);
  // OpenEXR compresses line blocks on its global pool; the writing thread is not one of them.
  Imf::setGlobalThreadCount(writeThreads > 1 ? writeThreads : 0);
}

bool writeExr(const std::string& path, const RgbImage& image, std::string& error) {
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const char* c : kRgb) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    for (const auto& [name, value] : image.metadata) header.insert(name, Imf::StringAttribute(value));
    Imf::FrameBuffer frame;
    char* base = reinterpret_cast<char*>(const_cast<Color*>(image.pixels.data()));
    for (int c = 0; c < 3; ++c)
      frame.insert(kRgb[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(Color),
                                       sizeof(Color) * size_t(image.width)));
    Imf::OutputFile file(path.c_str(), header, writeThreads > 1 ? writeThreads : 0);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

bool readExr(const std::string& path, RgbImage& image, std::string& error) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const long width = long(window.max.x) - window.min.x + 1, height = long(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width * height > (1l << 30)) {
      error = "image has no pixels or an absurd data window";
      return false;
    }
    const Imf::ChannelList& channels = file.header().channels();
    const bool rgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    if (!rgb && !channels.findChannel("Y")) {
      error = "no R, G, B or Y channel";
      return false;
    }
    image.width = int(width);
    image.height = int(height);
    image.pixels.assign(size_t(width) * size_t(height), Color(0.0f));
    Imf::FrameBuffer frame;
    char* base = reinterpret_cast<char*>(image.pixels.data());
    for (int c = 0; c < 3; ++c)
      frame.insert(rgb ? kRgb[c] : "Y",
                   Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), window, sizeof(Color), sizeof(Color) * size_t(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
      if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        image.metadata.emplace_back(it.name(), text->value());
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

}  // namespace erpt::image_formats
