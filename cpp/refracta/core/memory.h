// This machine's memory, and byte counts as messages print them (refusals of work too large to
// allocate: images, turbulence grids, sampled paths).
#pragma once

#include <cstdio>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <unistd.h>

namespace refracta {

// This machine's physical memory [bytes] (0 if unknown).
inline double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
}

// A byte count as a whole number, printed from the double: past 2^63 an int64_t conversion wraps
// negative (a 1e9 x 1e9 render's refusal said -9223372036854775808 bytes).
inline std::string whole_bytes(double size) {
  char text[64];
  std::snprintf(text, sizeof text, "%.0f", size);
  return text;
}

// A byte count in the largest unit that keeps it >= 1 (kB, MB, GB: powers of 1000).
inline std::string readable_bytes(double size) {
  char text[64];
  if (size >= 1e9) std::snprintf(text, sizeof text, "%.1f GB", size / 1e9);
  else if (size >= 1e6) std::snprintf(text, sizeof text, "%.1f MB", size / 1e6);
  else if (size >= 1e3) std::snprintf(text, sizeof text, "%.1f kB", size / 1e3);
  else std::snprintf(text, sizeof text, "%.0f bytes", size);
  return text;
}

// Whether `bytes` would not fit in this machine's memory (read into `memory`; unknown: fits).
inline bool beyond_memory(double bytes, double* memory) {
  *memory = physical_memory_bytes();
  return *memory > 0.0 && bytes > *memory;
}

// Refuses, before anything is allocated, work of `count` items (rays, samples) of bytes_per_item
// each at its peak that would not fit in physical memory: std::invalid_argument (ValueError)
// naming `what`. trace_rays of 1e8 rays traced for 12 s, then failed allocating its results.
inline void check_work_memory(double count, double bytes_per_item, const char* what, const char* items) {
  const double bytes = count * bytes_per_item;
  if (double memory; beyond_memory(bytes, &memory)) {
    throw std::invalid_argument(std::string(what) + ": " + whole_bytes(count) + " " + items + " need at least " +
                                readable_bytes(bytes) + ", more than this machine's " + readable_bytes(memory) +
                                " of memory: split them into batches");
  }
}

// std::allocator, except that a vector's new elements are default-initialised: resize(n) of a
// trivial type leaves them as they are instead of zeroing them. For buffers whose every element
// is written next by parallel work that polls Ctrl-C: zeroing an 8192^2 moment map first (1 GiB
// in fp32, 2 GiB in fp64, one thread) took seconds on a busy machine, and could not be interrupted.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  explicit UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A vector whose resize(n) does not initialise trivial elements (UninitializedAllocator).
template <class T>
using UninitializedVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace refracta
