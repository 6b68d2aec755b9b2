// Exact LRU stack distances below a depth K, for every access, in memory O(K): the top K ids of
// the LRU stack and nothing else. An access whose id is among them gets its exact distance (all
// ids touched since its last access are above it, so in the top K too); any other access (a cold
// one, or a reuse at distance K or more) is reported as kFar. The sampled analyzer (shards.h)
// uses it to count the small distances exactly, where SHARDS' scaling by 1/R is coarsest.
// Method as StackDistance's (Bennett and Kruskal 1975): one live marker per id at its last access,
// distance = live markers after it; markers in a window of positions with a Fenwick tree over
// them; the least recent id (the first live marker) is dropped when a (K+1)-th arrives; the window
// is compacted when the clock reaches its end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace meshreuse {

class BoundedStackDistance {
 public:
  static constexpr uint64_t kFar = std::numeric_limits<uint64_t>::max();
  explicit BoundedStackDistance(uint32_t depth);  // depth in 1..2^26 (std::invalid_argument)
  uint64_t Access(uint64_t id);                   // the distance if below depth, else kFar
  uint32_t depth() const { return depth_; }
  size_t size() const { return held_; }  // ids held, at most depth

 private:
  void Compact();
  void Add(uint32_t p, int v) {
    for (uint32_t i = p + 1; i <= window_; i += i & (~i + 1)) tree_[i] += v;
  }
  uint32_t Prefix(uint32_t p) const {  // live markers at positions [0, p]
    uint32_t s = 0;
    for (uint32_t i = p + 1; i > 0; i -= i & (~i + 1)) s += tree_[i];
    return s;
  }

  // id -> position of its live marker: open addressing with linear probing over 2^k >= 2 depth
  // slots (deletion by backward shift, so no tombstones), small enough to stay in cache.
  uint32_t* Find(uint64_t id);
  void Insert(uint64_t id, uint32_t p);
  void Erase(uint64_t id);
  size_t Slot(uint64_t id) const {
    uint64_t x = id * 0x9E3779B97F4A7C15ull;
    return static_cast<size_t>((x ^ (x >> 29)) & mask_);
  }

  uint32_t depth_, window_;
  uint32_t clock_ = 0, oldest_ = 0;  // next free position; no live marker before oldest_
  std::vector<uint32_t> tree_;       // Fenwick, 1-based, window_ + 1 entries
  std::vector<uint64_t> at_;         // position -> id, for the live markers
  std::vector<uint8_t> live_;        // position -> 1 when its marker is live
  std::vector<uint64_t> key_;        // the table: id + 1 (0: empty)
  std::vector<uint32_t> val_;
  size_t mask_ = 0, held_ = 0;
};

}  // namespace meshreuse
