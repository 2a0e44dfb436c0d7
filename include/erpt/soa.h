// Structure-of-arrays storage. A queue's fields are listed once, as an X-macro in
// queue_fields.h; ERPT_SOA_STRUCT turns that list into a struct with one aligned column per
// field plus resize()/size(). Kernels take columns (or the whole struct) and an index range.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <vector>

namespace erpt {

// 64-byte aligned allocator so every column starts on a cache line (and SIMD loads align).
template <class T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U>&) {}
  T* allocate(size_t n) {
    size_t bytes = (n * sizeof(T) + 63) / 64 * 64;
    void* p = std::aligned_alloc(64, bytes == 0 ? 64 : bytes);
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t) { std::free(p); }
  template <class U>
  bool operator==(const AlignedAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const AlignedAllocator<U>&) const { return false; }
};

template <class T>
using Column = std::vector<T, AlignedAllocator<T>>;

struct IndexRange {
  size_t begin = 0, end = 0;
  size_t size() const { return end - begin; }
};

}  // namespace erpt

#define ERPT_SOA_COLUMN(type, name, doc) ::erpt::Column<type> name;
#define ERPT_SOA_RESIZE(type, name, doc) name.resize(n);
#define ERPT_SOA_COPY_ROW(type, name, doc) name[to] = from.name[at];
#define ERPT_SOA_STRUCT(Name, FIELDS)             \
  struct Name {                                   \
    FIELDS(ERPT_SOA_COLUMN)                       \
    size_t count = 0;                             \
    void resize(size_t n) {                       \
      FIELDS(ERPT_SOA_RESIZE)                     \
      count = n;                                  \
    }                                             \
    size_t size() const { return count; }         \
    /* row `to` of this = row `at` of `from` */   \
    void copyRow(size_t to, const Name& from, size_t at) { FIELDS(ERPT_SOA_COPY_ROW) } \
  };
