// Cache-line-aligned vectors for the arrays the smoother traces (coordinates, adjacency offsets).
// Line-granularity reuse distances depend only on which accesses share a 64-byte line; with the
// arrays starting on a line boundary that pattern, and so every line-level number, is the same in
// every run, whatever address malloc would have chosen.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace meshreuse {

template <class T, size_t kAlign = 64>
struct AlignedAllocator {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = AlignedAllocator<U, kAlign>;
  };
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U, kAlign>&) {}
  T* allocate(size_t n) {
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{kAlign}));
  }
  void deallocate(T* p, size_t) { ::operator delete (p, std::align_val_t{kAlign}); }
  template <class U>
  bool operator==(const AlignedAllocator<U, kAlign>&) const {
    return true;
  }
  template <class U>
  bool operator!=(const AlignedAllocator<U, kAlign>&) const {
    return false;
  }
};

template <class T>
using AlignedVector = std::vector<T, AlignedAllocator<T>>;

}  // namespace meshreuse
