// Quantiles of each thread stream's line reuse distances (ReuseHistogram::Quantile's definition:
// the smallest observed d with at least a fraction X of the finite distances <= d) in memory
// O(depth) a stream plus a mark per line, where they are small: the top `depth` lines of the LRU
// stack as an array, most recent first (a line found at index d was reused at distance d: the d
// lines above it are the distinct ones touched since; found or not, it moves to the front), the
// cold accesses (each line's first) counted from the marks, and every other access known only to
// be a finite distance >= depth. Quantile X is exact whenever it lies below depth: the finite
// count is exact, and the distances at or beyond depth come after every one below it. Otherwise
// the answer is "at least depth", and a caller that needs it runs the whole analysis
// (ReuseAnalysis). Lines as ReuseAnalysis's: address / line_bytes, an access that straddles two
// lines touches both.
// Why: the other kernels' table (reports/kernel_runs.h) reads two quantiles of line distances per
// run, which on the paper's meshes and orderings lie below 32 lines; on lake 36-51% of a
// kernel's accesses repeat the line on top (nothing moves) and 54-66% are at distance 3 or
// less. The whole LRU stack (StackDistance) cost about a third of the kernels
// part's samples (perf), the bounded one (BoundedStackDistance: a hashed position, a Fenwick tree,
// popcounts) as much; with this array the part's simulated share on lake took 11.8 s against
// 14.3 (reports/docs/kernels.md, "Cost").
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "analysis/line_marks.h"
#include "tracer/access_stream.h"

namespace meshreuse {

class LineQuantiles : public AccessConsumer {
 public:
  // line_bytes a power of two, depth in 1..4096 (std::invalid_argument otherwise): an access
  // beyond the top costs O(depth).
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
    Stream(bool canonical, uint32_t line_bytes, uint32_t depth)
        : top(((depth + 7) / 8 + 1) * 8, kNone), seen(canonical, line_bytes), below(depth, 0) {}
    // The stack's top lines, most recent first; `held` of them, then kNone (no line's number:
    // lines are addresses / line_bytes) or the lines that fell off, in whole blocks of 8
    // entries and one block more.
    std::vector<uint64_t> top;
    uint32_t held = 0;
    LineMarks<uint8_t> seen;      // lines touched before
    std::vector<uint64_t> below;  // accesses at each distance below depth
    uint64_t accesses = 0, cold = 0;
  };
  void Add(Stream& s, uint64_t line);
  Stream& At(size_t t);
  const Stream* Find(int t) const;  // nullptr: no access of stream t yet

  uint32_t line_bytes_, depth_;
  int shift_;
  bool canonical_ = false;
  std::vector<std::unique_ptr<Stream>> streams_;
};

}  // namespace meshreuse
