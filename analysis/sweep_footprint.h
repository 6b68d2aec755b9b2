// The lines each sweep touches, and the miss floor they give every layout (issue 24).
//
// A sweep must bring every line it touches into the caches at least once. At its start, levels
// 1..i together hold at most C_1 + ... + C_i lines, and (without a prefetcher) a line enters a
// cache only when accessed, so at least D_s - (C_1 + ... + C_i) of the D_s distinct lines of sweep
// s miss level i, whatever the order of the vertices and whatever the replacement policy; in the
// first sweep (cold caches) all D_1 do. The sum over sweeps is a floor no ordering can go below;
// an ordering's misses above it are its excess. (LRU on a sweep larger than the cache loses every
// line between sweeps, D_s per sweep, so part of the gap at the last level is the policy's, not
// the layout's; see reports/docs/results.md.)
// As the simulator (analysis/cache_sim.h): each thread has a private hierarchy, so the floor is
// summed over the threads' own footprints; and since it counts an access that straddles two lines
// as one miss, a line counts here only where it is an access's first line (each such line's first
// touch is then a distinct access that needs it): the floor stays a floor.
#pragma once

#include <cstdint>
#include <vector>

#include "analysis/cache_model.h"
#include "analysis/line_marks.h"
#include "tracer/access_stream.h"

namespace meshreuse {

class SweepFootprint : public AccessConsumer {
 public:
  explicit SweepFootprint(uint32_t line_bytes) : line_bytes_(line_bytes) {}
  void Begin(const StreamInfo& info) override;
  void BeginSweep(int sweep) override;
  void Consume(const Access* a, size_t n) override;

  // Per thread, per sweep: the distinct lines its accesses start in; accesses before the first
  // BeginSweep count toward the first sweep.
  const std::vector<std::vector<uint64_t>>& lines() const { return lines_; }

 private:
  using Thread = LineMarks<uint32_t>;  // per line, the last sweep that touched it
  uint32_t line_bytes_;
  bool canonical_ = false;
  uint32_t sweep_ = 1;  // the current sweep (1-based), the mark of a line touched in it
  std::vector<Thread> threads_;
  std::vector<std::vector<uint64_t>> lines_;
  // Per thread, the line of its last access (kNoLine: none in this sweep): a repeat of it, about
  // half of a smoother's accesses, needs no lookup.
  static constexpr uint64_t kNoLine = ~uint64_t{0};
  std::vector<uint64_t> recent_;
};

// The floor on misses at each level of `cache` (one private hierarchy per thread), summed over
// the threads: per thread, lines[0] + sum over s >= 1 of max(0, lines[s] - (C_1 + ... + C_i) /
// line_bytes).
std::vector<uint64_t> MissFloor(const std::vector<std::vector<uint64_t>>& lines,
                                const CacheSpec& cache, uint32_t line_bytes);

}  // namespace meshreuse
