// Exact LRU stack distances below a depth K, for every access, in memory O(K): the top K ids of
// the LRU stack and nothing else. An access whose id is among them gets its exact distance (all
// ids touched since its last access are above it, so in the top K too); any other access (a cold
// one, or a reuse at distance K or more) is reported as kFar. The sampled analyzer (shards.h)
// uses it to count the small distances exactly, where SHARDS' scaling by 1/R is coarsest.
// Method as StackDistance's (Bennett and Kruskal 1975): one live marker per id at its last access,
// distance = live markers after it. Markers are bits over a window of positions: a reuse within
// 512 positions is counted by popcounts of at most 9 words, a longer one from a Fenwick tree over
// groups of 512 positions plus at most 8 popcounts. The least recent id (the first live marker)
// is dropped when a (K+1)-th arrives; the window is compacted when the clock reaches its end.
// Ids map to positions through an open-addressing table of 2^k >= 2 K slots.
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
  static constexpr uint32_t kGroup = 512;  // positions per Fenwick entry (8 words)
  uint64_t After(uint32_t p) const;        // live markers at positions after p
  void Set(uint32_t p);
  void Clear(uint32_t p);
  void GroupAdd(uint32_t g, int v) {
    for (uint32_t i = g + 1; i <= groups_; i += i & (~i + 1)) tree_[i] += v;
  }
  uint32_t GroupsBefore(uint32_t g) const {  // live markers in groups [0, g)
    uint32_t s = 0;
    for (uint32_t i = g; i > 0; i -= i & (~i + 1)) s += tree_[i];
    return s;
  }
  void Compact();
  // The table: id + 1 in key_ (0: empty), the position in val_; linear probing, deletion by
  // backward shift (no tombstones).
  uint32_t* Find(uint64_t id);
  void Insert(uint64_t id, uint32_t p);
  void Erase(uint64_t id);
  size_t Slot(uint64_t id) const {
    const uint64_t x = id * 0x9E3779B97F4A7C15ull;
    return static_cast<size_t>((x ^ (x >> 29)) & mask_);
  }

  uint32_t depth_, window_, groups_;
  uint32_t clock_ = 0, oldest_ = 0;  // next free position; no live marker before oldest_
  std::vector<uint64_t> bits_;       // live markers, a bit per position
  std::vector<uint32_t> tree_;       // Fenwick over groups, 1-based
  std::vector<uint64_t> at_;         // position -> id, for the live markers
  std::vector<uint64_t> key_;
  std::vector<uint32_t> val_;
  size_t mask_ = 0, held_ = 0;
};

}  // namespace meshreuse
