// A per-thread bump allocator for the short-lived objects of one path (the BSDF of each hit):
// allocate freely, reset() between samples, nothing is freed one by one (pbrt-v4 ScratchBuffer).
// Only trivially destructible types may live in it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace refracta {

class ScratchBuffer {
 public:
  explicit ScratchBuffer(size_t bytes = 1 << 14) : block_(new std::byte[bytes]), size_(bytes) {}

  template <class T, class... Args>
  T* make(Args&&... args) {
    static_assert(std::is_trivially_destructible<T>::value, "ScratchBuffer holds trivially destructible types only");
    return new (allocate(sizeof(T), alignof(T))) T(std::forward<Args>(args)...);
  }
  void reset() {
    offset_ = 0;
    retired_.clear();
  }

 private:
  void* allocate(size_t bytes, size_t align) {
    offset_ = (offset_ + align - 1) / align * align;
    if (offset_ + bytes > size_) {  // grow: keep the old block alive until reset
      retired_.push_back(std::move(block_));
      size_ = std::max(2 * size_, bytes + align);
      block_.reset(new std::byte[size_]);
      offset_ = 0;
    }
    void* p = block_.get() + offset_;
    offset_ += bytes;
    return p;
  }
  std::unique_ptr<std::byte[]> block_;
  std::vector<std::unique_ptr<std::byte[]>> retired_;
  size_t size_, offset_ = 0;
};

}  // namespace refracta
