// BoundedStackDistance; see bounded_stack.h.
#include "analysis/bounded_stack.h"

#include <algorithm>
#include <stdexcept>

namespace meshreuse {

BoundedStackDistance::BoundedStackDistance(uint32_t depth) : depth_(depth) {
  if (depth < 1 || depth > (1u << 26))
    throw std::invalid_argument("BoundedStackDistance: depth must be 1..2^26");
  // Room for at least 3 depth + 512 accesses between compactions, in whole groups.
  window_ = (4 * depth + kGroup + kGroup - 1) / kGroup * kGroup;
  groups_ = window_ / kGroup;
  bits_.assign(window_ / 64, 0);
  tree_.assign(groups_ + 1, 0);
  at_.assign(window_, 0);
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
  // Backward shift: a later member of the probe run moves into the hole when the hole lies
  // cyclically between its home slot and where it sits.
  for (size_t j = (i + 1) & mask_; key_[j] != 0; j = (j + 1) & mask_) {
    const size_t home = Slot(key_[j] - 1);
    if (((j - home) & mask_) >= ((j - i) & mask_)) {
      key_[i] = key_[j], val_[i] = val_[j];
      i = j;
    }
  }
  key_[i] = 0;
  --held_;
}

void BoundedStackDistance::Set(uint32_t p) {
  bits_[p >> 6] |= uint64_t{1} << (p & 63);
  GroupAdd(p / kGroup, 1);
}

void BoundedStackDistance::Clear(uint32_t p) {
  bits_[p >> 6] &= ~(uint64_t{1} << (p & 63));
  GroupAdd(p / kGroup, -1);
}

uint64_t BoundedStackDistance::After(uint32_t p) const {
  // No marker lies at or after clock_, so every set bit above p counts.
  const uint32_t w = p >> 6;
  const uint64_t above = (p & 63) == 63 ? 0 : bits_[w] >> ((p & 63) + 1);
  if (clock_ - p <= kGroup) {  // short reuse: the words up to the clock
    uint64_t n = static_cast<uint64_t>(__builtin_popcountll(above));
    for (uint32_t i = w + 1; i <= (clock_ - 1) >> 6; ++i) n += __builtin_popcountll(bits_[i]);
    return n;
  }
  // Long reuse: all live markers minus those at or before p (the groups before p's, and p's own
  // group up to p).
  const uint32_t g = p / kGroup;
  uint64_t upto = GroupsBefore(g);
  for (uint32_t i = g * (kGroup / 64); i < w; ++i) upto += __builtin_popcountll(bits_[i]);
  upto += __builtin_popcountll(bits_[w] << (63 - (p & 63)));  // bits 0..p&63 of word w
  return held_ - upto;
}

void BoundedStackDistance::Compact() {
  // Live markers to positions 0..n-1 in time order; bits and group counts rebuilt in O(window).
  uint32_t n = 0;
  for (uint32_t p = oldest_; p < clock_; ++p)
    if (bits_[p >> 6] >> (p & 63) & 1) {
      const uint64_t id = at_[p];
      at_[n] = id;
      *Find(id) = n;
      ++n;
    }
  std::fill(bits_.begin(), bits_.end(), 0);
  for (uint32_t p = 0; p < n; p += 64)
    bits_[p >> 6] = n - p >= 64 ? ~uint64_t{0} : (uint64_t{1} << (n - p)) - 1;
  std::fill(tree_.begin(), tree_.end(), 0);
  for (uint32_t i = 1; i <= groups_; ++i) {  // linear Fenwick build over the group counts
    const uint32_t first = (i - 1) * kGroup;
    tree_[i] += n > first ? std::min(n - first, kGroup) : 0;
    const uint32_t j = i + (i & (~i + 1));
    if (j <= groups_) tree_[j] += tree_[i];
  }
  clock_ = n, oldest_ = 0;
}

uint64_t BoundedStackDistance::Access(uint64_t id) {
  if (clock_ == window_) Compact();
  uint64_t d = kFar;
  if (uint32_t* at = Find(id)) {
    const uint32_t p = *at;
    d = After(p);
    Clear(p);
    *at = clock_;
  } else {
    if (held_ == depth_) {  // drop the least recent id first
      uint32_t w = oldest_ >> 6;
      uint64_t word = bits_[w] & (~uint64_t{0} << (oldest_ & 63));
      while (!word) word = bits_[++w];
      const uint32_t p = w * 64 + static_cast<uint32_t>(__builtin_ctzll(word));
      Erase(at_[p]);
      Clear(p);
      oldest_ = p + 1;
    }
    Insert(id, clock_);
  }
  at_[clock_] = id;
  Set(clock_);
  ++clock_;
  return d;
}

}  // namespace meshreuse
