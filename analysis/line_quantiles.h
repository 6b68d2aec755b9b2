// Quantiles of each thread stream's line reuse distances (ReuseHistogram::Quantile's definition:
// the smallest observed d with at least a fraction X of the finite distances <= d) in memory
// O(depth) a stream plus a mark per line, where they are small: the top lines of the LRU stack
// (depth rounded up to whole vectors) in slots that never move, each with its rank, its place in
// the stack (0 the line used last): the ranks are always a permutation of 0..slots-1, the empty
// slots the highest. A held line's distance is its rank (the distinct lines used since, every one
// of them held); using it adds one to every rank below it and makes its own 0, one compare and
// subtract over all the ranks with SIMD. A line not held (its mark says so) is cold or a reuse at
// distance >= the slots, and takes the slot of the highest rank (the oldest line, or an empty slot
// while one is left), the same update. Quantile X is exact whenever it lies below depth: the
// finite count is exact, and the distances at or beyond depth come after every one below it.
// Otherwise the answer is "at least depth", and a caller that needs it runs the whole analysis
// (ReuseAnalysis). Lines as ReuseAnalysis's: address / line_bytes, an access that straddles two
// lines touches both.
// Why: the other kernels' table (reports/kernel_runs.h) reads two quantiles of line distances per
// run, which on the paper's meshes and orderings lie below 32 lines; on lake 36-51% of a
// kernel's accesses repeat the line on top (nothing changes) and 54-66% are at distance 3 or
// less. The whole LRU stack (StackDistance) cost about a third of the kernels part's samples
// (perf), the bounded one (BoundedStackDistance: a hashed position, a Fenwick tree, popcounts) as
// much; an array of the top lines moved to the front as in a list cut the part's simulated share
// on lake from 14.3 s to 11.8; slots that never move with the stamp of their last use (a distance
// the count of newer stamps, a line not held the slot of the smallest stamp: two passes over 32
// 32-bit stamps) took 0.94 of that, and were still a quarter of the part's samples. Ranks of a
// byte (16-bit beyond 128 slots) are one pass over two vectors for 32 slots, with no count to
// reduce and no clock to renumber (reports/docs/kernels.md, "Cost"); with the report's 32 slots
// a count fixed at compile time, 0.88 of Consume's samples (perf, the nine `--quick` meshes'
// kernels without timing, ORI). A non-canonical stream's
// marks are a hash table, looked up at every access but a repeat (the report's streams are
// canonical).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "analysis/line_marks.h"
#include "core/aligned.h"
#include "tracer/access_stream.h"

namespace meshreuse {

class LineQuantiles : public AccessConsumer {
 public:
  // line_bytes a power of two, depth in 1..4096 (std::invalid_argument otherwise): an access
  // but a repeat costs O(depth) compares.
  LineQuantiles(uint32_t line_bytes, uint32_t depth);
  void Begin(const StreamInfo& info) override;
  void Consume(const Access* a, size_t n) override;

  // Quantile x (in [0, 1]) of stream t's finite line distances when it is below depth; nullopt
  // when it is not, or when the stream has no finite distance (where ReuseHistogram throws).
  std::optional<uint64_t> Quantile(int thread, double x) const;
  uint64_t accesses(int thread) const;  // line accesses of stream t (a straddle counts two)
  uint64_t cold(int thread) const;      // its distinct lines

 private:
  static constexpr uint64_t kNone = ~uint64_t{0};
  struct Stream {
    Stream(bool canonical, uint32_t line_bytes, uint32_t slots, size_t rank_bytes)
        : line(slots, kNone),
          rank(slots * rank_bytes),
          mark(canonical, line_bytes),
          below(slots, 0) {}
    // The stack's top lines, in slots that never move: slot j holds line[j] (kNone: empty), its
    // rank the j-th entry of `rank` (int8_t entries, int16_t where wide_; 0..slots-1 at first).
    std::vector<uint64_t> line;
    AlignedVector<uint8_t> rank;  // aligned: whole vectors are loaded and stored
    uint64_t front = kNone;       // the line used last (rank 0)
    // Per line: 0 never used, 1 used and not held, j + 2 held in slot j.
    LineMarks<uint16_t> mark;
    std::vector<uint64_t> below;  // accesses at each distance below the slots
    uint64_t accesses = 0, cold = 0;
  };
  template <class R, uint32_t K>  // K: slots_ fixed at compile time, or 0
  void Add(Stream& s, uint64_t line);
  template <class R, uint32_t K>
  void ConsumeAs(const Access* a, size_t n);
  Stream& At(size_t t);
  const Stream* Find(int t) const;  // nullptr: no access of stream t yet

  uint32_t line_bytes_, depth_;
  uint32_t slots_;  // depth rounded up to whole vectors of ranks
  bool wide_;       // ranks of 16 bits (more than 128 slots), else 8
  int shift_;
  bool canonical_ = false;
  std::vector<std::unique_ptr<Stream>> streams_;
};

}  // namespace meshreuse
