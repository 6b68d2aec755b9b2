// Cache-line-aligned vectors for the arrays the smoother traces (coordinates, adjacency offsets).
// Line-granularity reuse distances depend only on which accesses share a 64-byte line; with the
// arrays starting on a line boundary that pattern, and so every line-level number, is the same in
// every run, whatever address malloc would have chosen.
// resize(n) and vector(n) default-initialise (leave numbers unwritten, as `new T[n]` would): big
// arrays that are about to be filled are not first zeroed, which would cost a pass over memory.
// Ask for zeros by value: assign(n, 0), resize(n, 0).
#pragma once

#include <cstddef>
#include <new>
#include <utility>
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
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;  // default-initialisation: no zeroing
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
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
