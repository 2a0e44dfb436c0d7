// Column memory (soa.h): aligned, and large columns offered to the kernel as huge pages.
#include "core/soa.h"

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace erpt {

namespace {
constexpr size_t kHugePage = size_t(2) << 20;
constexpr size_t kHugeFrom = 2 * kHugePage;  // smaller columns keep 4 KB pages (less slack)
}  // namespace

void* allocateColumn(size_t bytes) {
  if (bytes >= kHugeFrom) {
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE);  // advice only: a refusal leaves 4 KB pages
    return p;
  }
  const size_t rounded = bytes == 0 ? 64 : (bytes + 63) / 64 * 64;
  void* p = std::aligned_alloc(64, rounded);
  if (!p) throw std::bad_alloc();
  return p;
}

}  // namespace erpt
