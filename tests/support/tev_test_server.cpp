#include "support/tev_test_server.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <stdexcept>

namespace erpt::test {

namespace {
// Reads one packet's fields in order; throws on reading past its end.
class Reader {
 public:
  explicit Reader(const std::string& p) : p_(p) {}
  template <class T>
  T get() {
    if (at_ + sizeof(T) > p_.size()) throw std::runtime_error("field past the packet's end");
    T v;
    std::memcpy(&v, p_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  std::string getString() {
    const size_t end = p_.find('\0', at_);
    if (end == std::string::npos) throw std::runtime_error("unterminated string");
    std::string s = p_.substr(at_, end - at_);
    at_ = end + 1;
    return s;
  }
  size_t left() const { return p_.size() - at_; }
  const char* here() const { return p_.data() + at_; }

 private:
  const std::string& p_;
  size_t at_ = 0;
};
}  // namespace

TevTestServer::TevTestServer() {
  listen_ = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  if (listen_ < 0 || bind(listen_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(listen_, 1) != 0)
    throw std::runtime_error("test server: cannot listen");
  socklen_t len = sizeof addr;
  getsockname(listen_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  thread_ = std::thread([this] { serve(); });
}

TevTestServer::~TevTestServer() {
  shutdown(listen_, SHUT_RDWR);
  close(listen_);
  if (thread_.joinable()) thread_.join();
}

bool TevTestServer::waitForClose(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!closed_ && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return closed_;
}

void TevTestServer::serve() {
  const int fd = accept(listen_, nullptr, nullptr);
  if (fd < 0) return;
  std::string buffer;
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = recv(fd, chunk, sizeof chunk, 0);
    if (n <= 0) break;
    buffer.append(chunk, size_t(n));
    while (buffer.size() >= 4) {  // whole packets: tev frames by the length prefix
      uint32_t length;
      std::memcpy(&length, buffer.data(), 4);
      if (length < 5) {
        errors.push_back("packet length " + std::to_string(length));
        buffer.clear();
        break;
      }
      if (buffer.size() < length) break;
      handle(buffer.substr(0, length));
      buffer.erase(0, length);
    }
  }
  if (!buffer.empty()) errors.push_back("connection closed inside a packet");
  close(fd);
  closed_ = true;
}

void TevTestServer::handle(const std::string& packet) {
  largestPacket = std::max(largestPacket, packet.size());
  try {
    Reader r(packet);
    r.get<uint32_t>();
    const uint8_t type = r.get<uint8_t>();
    const uint8_t focus = r.get<uint8_t>();
    if (focus > 1) errors.push_back("bool byte " + std::to_string(focus));
    const std::string imageName = r.getString();
    if (type == 4) {
      ++creates;
      name = imageName;
      image.width = r.get<int32_t>(), image.height = r.get<int32_t>();
      const int32_t n = r.get<int32_t>();
      channels.clear();
      for (int32_t c = 0; c < n; ++c) channels.push_back(r.getString());
      if (image.width <= 0 || image.height <= 0) throw std::runtime_error("empty image");
      image.pixels.assign(size_t(image.width) * size_t(image.height), Color(-1.0f));
      if (r.left() != 0) errors.push_back("CreateImage has trailing bytes");
      return;
    }
    if (type != 6) throw std::runtime_error("packet type " + std::to_string(type));
    ++updates;
    if (imageName != name || creates == 0) errors.push_back("update of an image never created: " + imageName);
    const int32_t n = r.get<int32_t>();
    if (n != 3) throw std::runtime_error("update with " + std::to_string(n) + " channels");
    std::vector<std::string> names;
    for (int32_t c = 0; c < n; ++c) names.push_back(r.getString());
    if (names != channels) errors.push_back("update channels differ from the created ones");
    const int32_t x = r.get<int32_t>(), y = r.get<int32_t>(), w = r.get<int32_t>(), h = r.get<int32_t>();
    if (x < 0 || y < 0 || w <= 0 || h <= 0 || x + w > image.width || y + h > image.height)
      throw std::runtime_error("update rectangle outside the image");
    int64_t offset[3], stride[3];
    for (auto& o : offset) o = r.get<int64_t>();
    for (auto& s : stride) s = r.get<int64_t>();
    const int64_t pixels = int64_t(w) * h;
    int64_t floats = 0;
    for (int c = 0; c < 3; ++c) floats = std::max(floats, offset[c] + (pixels - 1) * stride[c] + 1);
    if (r.left() != size_t(floats) * sizeof(float))
      throw std::runtime_error("update data is " + std::to_string(r.left()) + " bytes, its header says " +
                               std::to_string(floats * 4));
    const float* data = reinterpret_cast<const float*>(r.here());
    for (int64_t i = 0; i < pixels; ++i) {
      Color& px = image.pixels[size_t(y + i / w) * size_t(image.width) + size_t(x + i % w)];
      for (int c = 0; c < 3; ++c) std::memcpy(&px[c], data + offset[c] + i * stride[c], sizeof(float));
    }
  } catch (const std::exception& e) {
    errors.push_back(e.what());
  }
}

}  // namespace erpt::test
