// Exact stack distances on several cores: the chunk-and-merge method of PARDA (Niu, Dinan, Lu and
// Sadayappan, IPDPS 2012). The trace is cut into P consecutive chunks, analysed independently:
// an access whose previous access lies in the same chunk gets its exact distance there (the
// distinct ids between two accesses of one chunk are all in that chunk). What a chunk cannot
// decide is its first touches, and what it must pass on is the order in which it left its ids; its
// ChunkSummary holds exactly these two lists. The merge is then a pure function of the stack
// before the chunk and the chunk's summary:
//   - first touch k of the chunk (the k-th distinct id it meets) has distance = its depth in the
//     stack before the chunk, counting only ids the chunk has not met yet, plus k: exactly the
//     distance it gets when the stack before the chunk is replayed bottom-up and then the chunk's
//     first touches are accessed in order;
//   - the stack after the chunk is the stack before with the chunk's ids moved to the top in the
//     order of their last access: replaying the chunk's own stack bottom-up on top does that.
// MergeChunk realises both on one StackDistance holding the running stack, chunk after chunk: the
// reference. The analyzers use the streamed merge of streamed_chain.h, which computes the same
// without replaying chunks one after another. Since a summary is lists of ids, it can be written
// to a file or sent between machines unchanged (reports/chunks/summary_file.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "analysis/stack_distance.h"

namespace meshreuse {

struct ChunkSummary {
  std::vector<uint64_t> first_ids;        // the chunk's distinct ids in order of first access
  std::vector<uint64_t> first_positions;  // where each first access stands in the chunk
  std::vector<uint64_t> stack;            // the chunk's distinct ids, least recently used first
};

// Phase 1: distances decided inside ids[0, n): add(i, d) for each such access i (in order).
template <class Add>
ChunkSummary AnalyzeChunk(const uint64_t* ids, size_t n, uint64_t dense_limit, Add&& add) {
  StackDistance sd(dense_limit);
  ChunkSummary s;
  for (size_t i = 0; i < n; ++i) {
    const uint64_t d = sd.Access(ids[i]);
    if (d == StackDistance::kCold) {
      s.first_ids.push_back(ids[i]);
      s.first_positions.push_back(i);
    } else {
      add(i, d);
    }
  }
  s.stack = sd.StackBottomUp();
  return s;
}

// Phase 2: `stack` holds the stack before the chunk and is left holding the stack after it;
// add(first_positions[k], d) for each first touch (d = kCold when the id was never seen before).
template <class Add>
void MergeChunk(StackDistance* stack, const ChunkSummary& s, Add&& add) {
  for (size_t k = 0; k < s.first_ids.size(); ++k)
    add(s.first_positions[k], stack->Access(s.first_ids[k]));
  stack->TouchAll(s.stack.data(), s.stack.size());
}

// The stack distance of every access of ids, on `threads` threads (the streamed merge,
// streamed_chain.h), continuing from the LRU stack in `stack` (bottom-up; empty for a whole trace)
// and leaving the stack after the last access there; equal to the serial analyzer's access for
// access. Memory: the output, each chunk's distinct ids and two copies of the stack.
std::vector<uint64_t> ParallelStackDistances(const std::vector<uint64_t>& ids, int threads,
                                             uint64_t dense_limit, std::vector<uint64_t>* stack);

}  // namespace meshreuse
