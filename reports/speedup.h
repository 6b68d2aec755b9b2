// The paper's two timing ratios, computed here and only here (compare's rows and summary, the
// report's time, speedup and scaling tables), on per-sweep medians (time to convergence also
// depends on how many sweeps an ordering needs; the per-sweep time is what the layout changes):
//   Speedup(ord, p) = T_ori(1) / T_ord(p)        Gain(ord vs ref, p) = (T_ref(p) - T_ord(p)) /
//   T_ref(p)
// each with its 95% interval from resampling the rounds (timing.h); a ratio whose interval holds 1
// (a gain's, 0) is not distinguishable. On the wall clock by default; on the thread CPU clock
// (summed over threads) to rank orderings by the work they cost on a busy machine.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "reports/timed_runs.h"

namespace meshreuse {

// T_ref / T with its interval; all NaN when either is missing.
Spread Speedup(const CompareRow* ref, const CompareRow* r, uint64_t seed,
               TimeClock clock = TimeClock::kWall);
// (T_ref - T) / T_ref with its interval; NaN when either is missing or `r` is ref's own ordering.
Spread Gain(const CompareRow* ref, const CompareRow* r, uint64_t seed,
            TimeClock clock = TimeClock::kWall);
// The mean over the pairs (ref_i, r_i) of Speedup (or Gain), every pair's rounds resampled
// together; pairs with a missing side are left out. Its `min` and `max` are the pairs' extremes.
Spread MeanRatio(const std::vector<std::pair<const CompareRow*, const CompareRow*>>& pairs,
                 uint64_t seed, bool gain, TimeClock clock = TimeClock::kWall);

// The rows of a run by (mesh, ordering, threads).
class TimingIndex {
 public:
  explicit TimingIndex(const std::vector<CompareRow>& rows);
  const CompareRow* Find(const std::string& mesh, const std::string& ordering, int threads) const;

 private:
  std::map<std::tuple<std::string, std::string, int>, const CompareRow*> rows_;
};

}  // namespace meshreuse
