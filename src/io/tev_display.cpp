#include "io/tev_display.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace erpt {

namespace {
constexpr uint8_t kCreateImage = 4, kUpdateImageV3 = 6;
constexpr size_t kPacketBytes = 1 << 20;
const char* const kChannels[3] = {"R", "G", "B"};

// One packet: the length is filled in by finish().
class Packet {
 public:
  explicit Packet(uint8_t type) {
    put(uint32_t(0));
    put(type);
  }
  template <class T>
  void put(T value) {
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void putString(const std::string& s) { bytes_.append(s.c_str(), s.size() + 1); }
  void putFloats(const float* p, size_t n) { bytes_.append(reinterpret_cast<const char*>(p), n * sizeof(float)); }
  const std::string& finish() {
    const uint32_t n = uint32_t(bytes_.size());
    std::memcpy(bytes_.data(), &n, sizeof n);
    return bytes_;
  }

 private:
  std::string bytes_;
};
}  // namespace

TevDisplay::TevDisplay(const std::string& address, const std::string& name, int width, int height)
    : name_(name), width_(width), height_(height) {
  const size_t colon = address.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == address.size())
    throw std::runtime_error("--display expects HOST:PORT, got '" + address + "'");
  const std::string host = address.substr(0, colon), port = address.substr(colon + 1);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (const int err = getaddrinfo(host.c_str(), port.c_str(), &hints, &found); err != 0)
    throw std::runtime_error("cannot resolve display '" + address + "': " + gai_strerror(err));
  std::string why = "no address";
  for (addrinfo* a = found; a && socket_ < 0; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype, a->ai_protocol);
    if (fd < 0) continue;
    if (::connect(fd, a->ai_addr, a->ai_addrlen) == 0) {
      socket_ = fd;
    } else {
      why = std::strerror(errno);
      ::close(fd);
    }
  }
  freeaddrinfo(found);
  if (socket_ < 0) throw std::runtime_error("cannot connect to the display at '" + address + "': " + why);
  Packet p(kCreateImage);
  p.put(uint8_t(1));  // grab focus
  p.putString(name_);
  p.put(int32_t(width)), p.put(int32_t(height)), p.put(int32_t(3));
  for (const char* c : kChannels) p.putString(c);
  send(p.finish());
}

TevDisplay::~TevDisplay() {
  if (socket_ >= 0) ::close(socket_);
}

bool TevDisplay::send(const std::string& packet) {
  size_t sent = 0;
  while (socket_ >= 0 && sent < packet.size()) {
    // MSG_NOSIGNAL: a viewer that went away is an error here, not a SIGPIPE.
    const ssize_t n = ::send(socket_, packet.data() + sent, packet.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) {
      if (n < 0 && errno == EINTR) continue;
      ::close(socket_);
      socket_ = -1;
    } else {
      sent += size_t(n);
    }
  }
  return socket_ >= 0;
}

bool TevDisplay::update(const RgbImage& image) {
  if (image.width != width_ || image.height != height_) return socket_ >= 0;
  const int rows = int(std::clamp<size_t>(kPacketBytes / (sizeof(Color) * size_t(width_)), 1, size_t(height_)));
  for (int y = 0; y < height_ && socket_ >= 0; y += rows) {
    const int h = std::min(rows, height_ - y);
    Packet p(kUpdateImageV3);
    p.put(uint8_t(0));
    p.putString(name_);
    p.put(int32_t(3));
    for (const char* c : kChannels) p.putString(c);
    p.put(int32_t(0)), p.put(int32_t(y)), p.put(int32_t(width_)), p.put(int32_t(h));
    for (int64_t c = 0; c < 3; ++c) p.put(c);          // interleaved RGB: channel c starts at float c
    for (int c = 0; c < 3; ++c) p.put(int64_t(3));     // and steps 3 floats per pixel
    static_assert(sizeof(Color) == 3 * sizeof(float));
    p.putFloats(&image.pixels[size_t(y) * size_t(width_)].x, size_t(h) * size_t(width_) * 3);
    send(p.finish());
  }
  return socket_ >= 0;
}

}  // namespace erpt
