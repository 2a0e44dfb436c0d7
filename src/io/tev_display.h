// Streams an image to the tev viewer (https://github.com/Tom94/tev) over its TCP protocol, as
// pbrt-v4's and Mitsuba 3's `--display` do: `tev` listens on 127.0.0.1:14158 by default.
//
// Packets (little-endian): uint32 length of the whole packet, uint8 type, then the payload;
// strings end with a 0 byte, bools are one byte. CreateImage (type 4): grabFocus, name, int32
// width, height, channel count, channel names. UpdateImage v3 (type 6): grabFocus, name, int32
// channel count, channel names, int32 x, y, width, height, int64 offset and stride per
// channel, then the floats. Updates go in strips of rows, each packet about 1 MB.
#pragma once

#include <string>

#include "erpt/image_io.h"

namespace erpt {

class TevDisplay {
 public:
  // Connects to "HOST:PORT" and creates an image named `name` with channels R, G, B. Throws
  // std::runtime_error (naming the address) when it cannot connect.
  TevDisplay(const std::string& address, const std::string& name, int width, int height);
  ~TevDisplay();
  TevDisplay(const TevDisplay&) = delete;
  TevDisplay& operator=(const TevDisplay&) = delete;
  // Sends the whole image. Returns false once the viewer is gone (later calls do nothing).
  bool update(const RgbImage& image);

 private:
  bool send(const std::string& packet);
  int socket_ = -1;
  std::string name_;
  int width_, height_;
};

}  // namespace erpt
