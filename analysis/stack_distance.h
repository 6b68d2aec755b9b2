// Exact LRU stack distance (reuse distance) of a stream of ids, streaming.
// The distance of an access is the number of distinct ids touched since the previous access to
// the same id (first touches are cold, kCold). Method (Bennett and Kruskal 1975; Almasi, Cascaval
// and Padua 2002): every id keeps one live marker at the time of its last access; the distance is
// the number of live markers after that time. Markers are bits in a bitmap over time positions,
// with live counts per block of 64 words (4096 positions) and per superblock of 64 blocks: a
// reuse within a few thousand positions -- the common case under a good ordering -- is answered
// by popcounts alone, a longer one adds block and superblock counts, and moving a marker updates
// two counters (O(1); a Fenwick tree here costs ~15 dependent steps per access and was 1.3x
// slower end to end on carabiner). When the time axis fills, live markers are renumbered
// compactly (compaction) into a window 4x the live count, so memory follows the number of
// distinct ids, never the trace length: about 21 bytes per distinct id for dense ids (below
// `dense_limit`, a direct array), plus a hash table entry for others. Counters are 64-bit;
// positions inside the window are 32-bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace meshreuse {

class StackDistance {
 public:
  static constexpr uint64_t kCold = std::numeric_limits<uint64_t>::max();

  // Ids below dense_limit (at most 2^31) live in a direct array; larger ones in a hash table.
  explicit StackDistance(uint64_t dense_limit = uint64_t{1} << 26,
                         uint32_t min_capacity = 1u << 16);
  StackDistance(StackDistance&&) = default;
  StackDistance& operator=(StackDistance&&) = default;
  StackDistance(const StackDistance&) = delete;
  StackDistance& operator=(const StackDistance&) = delete;

  uint64_t Access(uint64_t id);

  uint64_t accesses() const { return accesses_; }
  uint64_t distinct() const { return distinct_; }
  uint64_t compactions() const { return compactions_; }
  size_t MemoryBytes() const;

 private:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  static constexpr uint32_t kHashedBit = 1u << 31;

  uint32_t& LastOf(uint64_t id, uint32_t* key) {
    if (id < dense_last_.size()) {  // the common case for vertex ids: inline
      *key = static_cast<uint32_t>(id);
      return dense_last_[id];
    }
    return LastOfSlow(id, key);
  }
  uint32_t& LastOfSlow(uint64_t id, uint32_t* key);
  uint64_t CountLive(uint32_t a, uint32_t b) const;     // live markers in [a, b)
  uint64_t CountWords(uint32_t w, uint32_t we) const;   // in whole words [w, we)
  uint64_t CountBlocks(uint32_t b, uint32_t be) const;  // in whole blocks [b, be)
  void Compact();

  uint64_t dense_limit_;
  uint32_t min_capacity_;
  std::vector<uint32_t> dense_last_;   // by id
  std::vector<uint32_t> hashed_last_;  // by hash slot number
  std::vector<uint64_t> keys_;         // open addressing, kEmptyKey = free
  std::vector<uint32_t> slots_;
  uint64_t hash_used_ = 0;

  std::vector<uint64_t> bits_;   // live markers
  std::vector<uint32_t> owner_;  // key (id or kHashedBit | slot) of the marker at each position
  std::vector<uint32_t> block_;  // live markers per 64 words
  std::vector<uint32_t> super_;  // live markers per 64 blocks
  uint32_t capacity_ = 0;        // positions in the window
  uint32_t t_ = 0;               // next position
  uint64_t accesses_ = 0, distinct_ = 0, compactions_ = 0;
};

}  // namespace meshreuse
