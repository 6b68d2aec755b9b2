// Exact LRU stack distance (reuse distance) of a stream of ids, streaming.
// The distance of an access is the number of distinct ids touched since the previous access to
// the same id (first touches are cold, kCold). Method (Bennett and Kruskal 1975; Almasi, Cascaval
// and Padua 2002): every id keeps one live marker at the time of its last access; the distance is
// the number of live markers after that time. Markers are bits in a bitmap over time positions.
// An access to the id whose marker is the newest (the top of the stack: the id just accessed) is
// distance 0 and leaves its marker where it is, since no marker lies between the two times.
// Counting them, two paths, both exact:
//   - short reuse (within kShortWords words, the common case under a good mesh ordering): popcounts
//     of the words in between, O(1);
//   - long reuse: live markers after p = live total - live markers up to p, the latter from a
//     Fenwick tree over groups of 512 positions (8 words) plus at most 8 popcounts: O(log window)
//     whatever the distance (the previous design summed block counts one after another and was
//     2.7-3.7x slower than a textbook Fenwick on a 1M-id cyclic scan).
// The Fenwick tree holds only closed groups: the group being filled is counted by popcount and
// enters the tree, in one update, when the clock leaves it, so an access costs one tree update (the
// removal of the old marker), not two. When the time axis fills, live markers are renumbered
// compactly (compaction) into a window 4x the live count, so memory follows the number of distinct
// ids, never the trace length: about 21 bytes per distinct id for dense ids (a
// direct array), plus a hash table entry for others. Counters are 64-bit; positions inside the
// window are 32-bit.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <new>
#include <utility>
#include <vector>

namespace meshreuse {

// A uint32_t array that grows and shrinks with realloc: glibc maps large blocks on their own and
// realloc moves their pages (mremap) instead of copying them, so resizing the analyzer's window
// never holds an old and a new copy at once (std::vector would: a third more memory at the peak).
// New elements are left unwritten. Move-only.
class U32Array {
 public:
  U32Array() = default;
  ~U32Array() { std::free(p_); }
  U32Array(U32Array&& o) noexcept : p_(std::exchange(o.p_, nullptr)), n_(std::exchange(o.n_, 0)) {}
  U32Array& operator=(U32Array&& o) noexcept {
    std::swap(p_, o.p_);
    std::swap(n_, o.n_);
    return *this;
  }
  U32Array(const U32Array&) = delete;
  U32Array& operator=(const U32Array&) = delete;
  void Resize(size_t n) {
    void* p = std::realloc(p_, n ? n * sizeof(uint32_t) : 1);
    if (!p) throw std::bad_alloc();
    p_ = static_cast<uint32_t*>(p);
    n_ = n;
  }
  uint32_t& operator[](size_t i) { return p_[i]; }
  uint32_t operator[](size_t i) const { return p_[i]; }
  size_t size() const { return n_; }

 private:
  uint32_t* p_ = nullptr;
  size_t n_ = 0;
};

class StackDistance {
 public:
  static constexpr uint64_t kCold = std::numeric_limits<uint64_t>::max();

  // Ids live in a direct array or a hash table. Ids below dense_ids (a known-dense range, e.g.
  // vertex ids) are always direct, entry i for id i. Otherwise the array is a strided window,
  // entry i for id base + i * 2^shift, chosen from the first 64 distinct ids (hashed until then):
  // 2^shift the largest power of two that three quarters of them share a residue modulo, base 32
  // Ki strides below the median of those (or the residue itself, near 0). So addresses at element
  // granularity -- multiples of their element size, clustered far from 0 -- are direct too, as
  // small ids are. The window grows up and down while it stays within 8 entries per distinct id
  // seen (plus 64 Ki), so no one far id costs gigabytes; ids off it (another residue, too far)
  // stay hashed; hashed ids move into the array when it grows over them.
  explicit StackDistance(uint64_t dense_ids = 0, uint32_t min_capacity = 1u << 16);
  StackDistance(StackDistance&&) = default;
  StackDistance& operator=(StackDistance&&) = default;
  StackDistance(const StackDistance&) = delete;
  StackDistance& operator=(const StackDistance&) = delete;

  uint64_t Access(uint64_t id) { return Visit<true>(id); }
  // Moves `id` to the top of the stack without computing its distance (cheaper: no count).
  void Touch(uint64_t id) { Visit<false>(id); }
  // Touch(ids[0]), ..., Touch(ids[n-1]) for distinct ids; when they are a sizeable part of the
  // stack, by one sequential renumbering (as a compaction) instead of n scattered moves.
  void TouchAll(const uint64_t* ids, size_t n);
  // Forgets `id` (its next access is cold again); false if it was not tracked. For samplers that
  // stop following an id (SHARDS fixed-size).
  bool Remove(uint64_t id);
  // The tracked ids from least to most recently used (the LRU stack, bottom first): a chunk's
  // summary for the parallel analyzer (analysis/parallel_stack_distance.h).
  std::vector<uint64_t> StackBottomUp() const;

  uint64_t accesses() const { return accesses_; }
  uint64_t distinct() const { return distinct_; }  // ids ever seen (not reduced by Remove)
  uint64_t live() const { return live_; }          // ids tracked now
  uint64_t compactions() const { return compactions_; }
  uint64_t hashed() const { return hash_used_; }  // ids in the hash table now (not direct)
  size_t MemoryBytes() const;

 private:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  static constexpr uint32_t kHashedBit = 1u << 31;
  static constexpr uint32_t kGroupShift = 9;  // 512 positions = 8 words per Fenwick leaf
  static constexpr uint32_t kShortWords = 16;

  uint32_t& LastOf(uint64_t id, uint32_t* key) {
    const uint64_t off = id - base_;  // wraps below base_: then far beyond the array
    if ((off & mask_) == 0 && (off >> shift_) < dense_last_.size()) {  // inline: the common case
      *key = static_cast<uint32_t>(off >> shift_);
      return dense_last_[off >> shift_];
    }
    return LastOfSlow(id, key);
  }
  // The array entry `id` would have in the window (kHashedBit when it has none).
  uint64_t WindowIndex(uint64_t id) const {
    const uint64_t off = id - base_;
    if (id < base_ || (off & mask_) != 0) return kHashedBit;
    return std::min<uint64_t>(off >> shift_, kHashedBit);
  }
  void SetWindow();  // from the hashed ids so far
  uint32_t& LastOfSlow(uint64_t id, uint32_t* key);
  template <bool kDistance>
  uint64_t Visit(uint64_t id);
  uint32_t* FindHashed(uint64_t id, size_t* slot_index);
  void GrowDense(uint64_t index);   // cover entry index, moving hashed ids it covers there
  void GrowDown(uint64_t entries);  // the window starts `entries` strides lower
  void MoveHashedIntoArray();       // hashed ids the array covers move there
  void EraseAt(size_t index);       // deletes a table entry (its slot freed), later ones moved back
  uint64_t LiveAfter(uint32_t p) const;  // live markers at positions > p (p < t_)
  void TreeAdd(uint32_t group, int32_t delta) {
    for (uint32_t i = group + 1; i < tree_.size(); i += i & (0u - i)) tree_[i] += delta;
  }
  void ClearMarker(uint32_t p) {
    bits_[p >> 6] &= ~(uint64_t{1} << (p & 63));
    if ((p >> kGroupShift) < closed_) TreeAdd(p >> kGroupShift, -1);
  }
  void CloseGroups();                // every group wholly before t_ into the tree
  void Compact(uint64_t extra = 0);  // renumber the live markers into a window for live + extra

  uint64_t dense_ids_;
  uint32_t min_capacity_;
  uint64_t base_ = 0, mask_ = 0;  // the window: entry i for id base_ + (i << shift_)
  uint32_t shift_ = 0;
  bool window_set_ = false;
  std::vector<uint32_t> dense_last_;   // by window entry
  std::vector<uint32_t> hashed_last_;  // by hash slot number
  std::vector<uint32_t> free_slots_;   // hashed_last_ entries freed by Remove
  std::vector<uint64_t> keys_;         // open addressing, kEmptyKey = free
  std::vector<uint32_t> slots_;
  uint64_t hash_used_ = 0;

  std::vector<uint64_t> bits_;  // live markers
  U32Array owner_;              // key (id or kHashedBit | slot) of the marker at each position
  std::vector<int32_t> tree_;   // Fenwick tree over closed groups' live counts, 1-based
  uint32_t capacity_ = 0;       // positions in the window (a multiple of 512)
  uint32_t t_ = 0;              // next position
  uint32_t closed_ = 0;         // groups [0, closed_) are in the tree
  uint64_t live_ = 0;
  uint64_t accesses_ = 0, distinct_ = 0, compactions_ = 0;
};

}  // namespace meshreuse
