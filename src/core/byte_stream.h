// Little byte streams for render state (checkpoints, and the snapshot an interrupted render
// falls back to). Values are stored in the machine's own byte order: a checkpoint is resumed
// by the same build that wrote it (the header names the build, render_state.h).
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace erpt {

class ByteWriter {
 public:
  ByteWriter() = default;
  // Writes into `reuse` (emptied first), keeping its capacity: a snapshot taken again and
  // again (sample_passes.cpp) then costs a copy, not a fresh allocation and its page faults.
  explicit ByteWriter(std::vector<uint8_t> reuse) : bytes_(std::move(reuse)) { bytes_.clear(); }
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <class T>
  void putVector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(uint64_t(values.size()));
    const auto* p = reinterpret_cast<const uint8_t*>(values.data());
    bytes_.insert(bytes_.end(), p, p + values.size() * sizeof(T));
  }
  void putString(const std::string& s) { putVector(std::vector<char>(s.begin(), s.end())); }
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::vector<uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<uint8_t> bytes_;
};

// Reads what a ByteWriter wrote; throws std::runtime_error("truncated ...") past the end, so a
// cut-off file is refused instead of read as garbage.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  explicit ByteReader(const std::vector<uint8_t>& bytes) : ByteReader(bytes.data(), bytes.size()) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  template <class T>
  void get(T& value) { value = get<T>(); }
  // `expected`: the length the caller's layout requires (a film's pixel count), checked.
  template <class T>
  void getVector(std::vector<T>& values, size_t expected) {
    const uint64_t n = get<uint64_t>();
    if (n != expected) throw std::runtime_error("state holds " + std::to_string(n) + " values where " +
                                                std::to_string(expected) + " were expected");
    values.resize(n);
    if (n) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  std::string getString(size_t maxLength = 1 << 20) {
    const uint64_t n = get<uint64_t>();
    if (n > maxLength || n > size_ - pos_) throw std::runtime_error("truncated state (a string runs past the end)");
    const char* p = reinterpret_cast<const char*>(take(n));
    return std::string(p, p + n);
  }
  size_t remaining() const { return size_ - pos_; }
  void expectEnd() const {
    if (pos_ != size_) throw std::runtime_error("state has " + std::to_string(size_ - pos_) + " unread bytes");
  }

 private:
  const uint8_t* take(size_t n) {
    if (n > size_ - pos_) throw std::runtime_error("truncated state");
    const uint8_t* p = data_ + pos_;
    pos_ += n;
    return p;
  }
  const uint8_t* data_;
  size_t size_, pos_ = 0;
};

}  // namespace erpt
