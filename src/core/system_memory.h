// How much memory this machine can give a render, for refusing up front what would not fit
// (instead of std::bad_alloc, or swapping, hours later).
#pragma once

#include <cstddef>
#include <string>

namespace erpt {

// Bytes the kernel reports as available for new allocations (Linux: MemAvailable in
// /proc/meminfo; elsewhere free physical pages). 0 when unknown.
size_t availableMemoryBytes();

// "3.3 GB", for messages.
std::string humanBytes(double bytes);

}  // namespace erpt
