// BoundedStackDistance; see bounded_stack.h.
#include "analysis/bounded_stack.h"

#include <algorithm>
#include <stdexcept>

namespace meshreuse {

BoundedStackDistance::BoundedStackDistance(uint32_t depth) : depth_(depth) {
  if (depth < 1 || depth > (1u << 26))
    throw std::invalid_argument("BoundedStackDistance: depth must be 1..2^26");
  window_ = 4 * depth + 64;  // room for 3 depth + 64 accesses between compactions
  tree_.assign(window_ + 1, 0);
  at_.assign(window_, 0);
  live_.assign(window_, 0);
  size_t slots = 16;
  while (slots < 2 * (static_cast<size_t>(depth) + 1)) slots *= 2;
  key_.assign(slots, 0);
  val_.assign(slots, 0);
  mask_ = slots - 1;
}

uint32_t* BoundedStackDistance::Find(uint64_t id) {
  for (size_t i = Slot(id);; i = (i + 1) & mask_) {
    if (key_[i] == id + 1) return &val_[i];
    if (key_[i] == 0) return nullptr;
  }
}

void BoundedStackDistance::Insert(uint64_t id, uint32_t p) {
  size_t i = Slot(id);
  while (key_[i] != 0) i = (i + 1) & mask_;
  key_[i] = id + 1, val_[i] = p;
  ++held_;
}

void BoundedStackDistance::Erase(uint64_t id) {
  size_t i = Slot(id);
  while (key_[i] != id + 1) i = (i + 1) & mask_;
  // Backward shift: move later members of the probe run into the hole where they may live.
  for (size_t j = (i + 1) & mask_; key_[j] != 0; j = (j + 1) & mask_) {
    const size_t home = Slot(key_[j] - 1);
    // j's entry may move to i when i lies cyclically in [home, j)
    if (((j - home) & mask_) >= ((j - i) & mask_)) {
      key_[i] = key_[j], val_[i] = val_[j];
      i = j;
    }
  }
  key_[i] = 0;
  --held_;
}

void BoundedStackDistance::Compact() {
  // Live markers to positions 0..n-1, in time order; the tree rebuilt in O(window).
  uint32_t n = 0;
  for (uint32_t p = oldest_; p < clock_; ++p)
    if (live_[p]) {
      const uint64_t id = at_[p];
      live_[p] = 0;
      at_[n] = id;
      live_[n] = 1;
      *Find(id) = n;
      ++n;
    }
  std::fill(live_.begin() + n, live_.end(), 0);
  std::fill(tree_.begin(), tree_.end(), 0);
  for (uint32_t i = 1; i <= window_; ++i) {  // linear Fenwick build
    if (i <= n) tree_[i] += 1;
    const uint32_t j = i + (i & (~i + 1));
    if (j <= window_) tree_[j] += tree_[i];
  }
  clock_ = n, oldest_ = 0;
}

uint64_t BoundedStackDistance::Access(uint64_t id) {
  if (clock_ == window_) Compact();
  uint64_t d = kFar;
  if (uint32_t* at = Find(id)) {
    const uint32_t p = *at;
    d = static_cast<uint64_t>(held_) - Prefix(p);  // live markers after p
    live_[p] = 0;
    Add(p, -1);
    *at = clock_;
  } else {
    if (held_ == depth_) {  // drop the least recent id first
      while (!live_[oldest_]) ++oldest_;
      Erase(at_[oldest_]);
      live_[oldest_] = 0;
      Add(oldest_, -1);
      ++oldest_;
    }
    Insert(id, clock_);
  }
  at_[clock_] = id;
  live_[clock_] = 1;
  Add(clock_, 1);
  ++clock_;
  return d;
}

}  // namespace meshreuse
