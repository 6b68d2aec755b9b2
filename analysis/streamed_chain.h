// The streamed merge of chunk summaries (../shared/scale-out.md section 3a): the exact stack
// distances of a trace cut into consecutive chunks, with no serial merge. Each chunk is analysed on
// its own (AnalyzeChunk, parallel_stack_distance.h); then the LRU stack before the first chunk
// flows chunk to chunk, bottom-up, in blocks: chunk r notes where each of its own ids stands in the
// stack before it (S_<r), drops them, forwards the rest at once, and at the end appends its own
// stack L_r. What flows out of chunk r is (S_<r without D_r) ++ L_r = S_<=r, the LRU stack after
// the chunk (the stack after a chunk is the old stack without the chunk's ids, with the chunk's ids
// on top in last-access order). Off the critical path, chunk r then resolves its first touches from
// the noted positions: with L = |S_<r| and pos_k the place of first touch k's id (0 = bottom),
//   d_k = (L - 1 - pos_k) + k - #{ j < k : pos_j > pos_k }     (cold when the id was not there),
// the ids above it in S_<r plus the chunk's earlier first touches that were not already above it:
// exactly the depth MergeChunk finds by replay. The count is a Fenwick tree over the order in which
// positions were found, which is their order in the stack. Critical path: one pass of the stack
// through every chunk, pipelined, O(M + P blocks), against P*M for chunk-after-chunk replay.
// ChunkResolver is the pure per-chunk step (threads, summary files and message passing share it);
// StreamedChain runs it on P threads connected by bounded block queues.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "analysis/parallel_stack_distance.h"

namespace meshreuse {

// id -> its index in a list of distinct ids: a direct array over the ids' range, at the stride
// they all share from the least (2^s: addresses' alignment, a scan's step), when that range is
// within 4 entries per id (+ 64 Ki; vertex ids of one chunk under a good ordering, a chunk of
// addresses), else an open-addressing table at load <= 1/2 with each key and its index in one
// slot.
class IdIndex {
 public:
  static constexpr uint32_t kAbsent = ~uint32_t{0};
  IdIndex() = default;                                 // of no ids
  explicit IdIndex(const std::vector<uint64_t>& ids);  // std::length_error beyond 2^32-1 ids
  uint32_t Find(uint64_t id) const {
    if (direct_mode_) {
      const uint64_t x = id - lo_;  // ids below lo_ wrap to large values
      return (x & mask_) == 0 && (x >> shift_) < direct_.size() ? direct_[x >> shift_] : kAbsent;
    }
    return FindHashed(id);
  }
  size_t MemoryBytes() const { return direct_.capacity() * 4 + slots_.capacity() * sizeof(Slot); }

 private:
  struct Slot {
    uint64_t key;
    uint32_t index;
  };
  uint32_t FindHashed(uint64_t id) const;
  bool direct_mode_ = true;
  uint64_t lo_ = 0, mask_ = 0;
  uint32_t shift_ = 0;
  std::vector<uint32_t> direct_;
  std::vector<Slot> slots_;
};

class ChunkResolver {
 public:
  explicit ChunkResolver(const ChunkSummary& s);
  // The next n ids of the stack before the chunk (bottom first): the chunk's own are noted where
  // they stand, the others appended to *out, in order.
  void Filter(const uint64_t* ids, size_t n, std::vector<uint64_t>* out);
  // After the whole stack before the chunk went through Filter: the distance of each first touch
  // (StackDistance::kCold when its id was not in the stack), in first-touch order.
  std::vector<uint64_t> FirstTouchDistances() const;
  // The same, as f(k, distance of first touch k) in first-touch order, with no list of them (at
  // 10^6 first touches, 8 MB of fresh pages fewer).
  template <class F>
  void ForEachFirstTouchDistance(F f) const;
  uint64_t stack_seen() const { return seen_; }  // |S_<r| so far
  size_t MemoryBytes() const { return index_.MemoryBytes() + pos_.capacity() * 12; }

 private:
  static constexpr uint64_t kNotFound = ~uint64_t{0};
  static constexpr uint64_t kColdDistance = ~uint64_t{0};  // StackDistance::kCold
  const ChunkSummary& s_;
  IdIndex index_;
  std::vector<uint64_t> pos_;   // per first touch: place in the stack before, or kNotFound
  std::vector<uint32_t> rank_;  // per first touch found: how many were found before it
  uint64_t seen_ = 0;
  uint32_t found_ = 0;
  // The index and the lists are built when the first ids of the stack arrive: a chunk with an
  // empty stack before it (the first) finds every first touch cold without them (at 10^6 ids,
  // 16 MB and a pass over its ids saved on the rank that adds everything up).
  bool indexed_ = false;
};

template <class F>
void ChunkResolver::ForEachFirstTouchDistance(F f) const {
  if (!indexed_) {  // nothing came before the chunk
    for (size_t k = 0; k < s_.first_ids.size(); ++k) f(k, kColdDistance);
    return;
  }
  // Which ranks (places in the stack, in order) earlier first touches were found at: a bit per
  // rank, and a Fenwick tree over the bit words counting the bits set in each. Ranks are distinct,
  // so a bit is enough; the bits and the tree (1/64 as many entries as a tree over the ranks) stay
  // in the L2 cache up to millions of first touches, where a tree per rank missed it on every
  // level (72 ns a first touch at 10^6 uniform ids, measured).
  std::vector<uint64_t> bits((found_ + 63) / 64, 0);
  std::vector<uint32_t> tree(bits.size() + 1, 0);
  uint64_t inserted = 0;
  for (size_t k = 0; k < pos_.size(); ++k) {
    if (pos_[k] == kNotFound) {
      f(k, kColdDistance);
      continue;
    }
    const uint32_t r = rank_[k], w = r >> 6;
    uint64_t below =
        static_cast<uint64_t>(__builtin_popcountll(bits[w] & ((uint64_t{1} << (r & 63)) - 1)));
    for (uint32_t i = w; i > 0; i -= i & (0u - i)) below += tree[i];  // words 0..w-1
    const uint64_t above = inserted - below;  // earlier first touches higher in the stack
    f(k, (seen_ - 1 - pos_[k]) + k - above);
    bits[w] |= uint64_t{1} << (r & 63);
    for (uint32_t i = w + 1; i < tree.size(); i += i & (0u - i)) ++tree[i];
    ++inserted;
  }
}

// The whole step for one chunk, serially: `stack` (bottom-up) is the stack before the chunk and is
// left holding the stack after it; returns the first touches' distances. For summary files merged
// one after another (memory: the stack and one chunk).
std::vector<uint64_t> ResolveChunk(const ChunkSummary& s, std::vector<uint64_t>* stack);

// Chunks 0..p-1 on p threads: analyse(c) is chunk c's phase 1 (its summary); finish(c, summary,
// first-touch distances) runs on the same thread once chunk c has forwarded its stack. `stack`
// holds the stack before chunk 0 and is left holding the stack after chunk p-1. Blocks of
// `block` ids, at most a few in flight between two chunks. An exception on any thread stops the
// others and is rethrown here.
using ChunkAnalyse = std::function<ChunkSummary(int chunk)>;
using ChunkFinish =
    std::function<void(int chunk, const ChunkSummary&, const std::vector<uint64_t>& first)>;
void StreamedChain(int p, std::vector<uint64_t>* stack, const ChunkAnalyse& analyse,
                   const ChunkFinish& finish, size_t block = size_t{1} << 16);

}  // namespace meshreuse
