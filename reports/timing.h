// The timing discipline every timed table follows (compare, the report's time, speedup, scaling
// and reordering-cost tables): untimed warm-up, at least three interleaved rounds, and for every
// timed quantity its spread over the rounds -- min, median, max and a 95% interval of the median
// from a seeded bootstrap over the rounds (Efron's percentile interval, 2,000 resamples). A ratio
// (Speedup, Gain) gets its interval the same way, resampling the rounds of both sides together
// (rounds interleave, so a round's drift hits both); a ratio whose interval holds 1 (a gain's, 0)
// is "not distinguishable", never ranked. Noise: the machine's load against its cores before and
// after, the timed sweeps' CPU/wall ratio, the rounds' coefficient of variation; any over its
// bound makes the run "busy", said on stderr, in run.json and at the top of a results README.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "reports/run_info.h"

namespace meshreuse {

struct Spread {
  double median = NAN, min = NAN, max = NAN;
  double lo = NAN, hi = NAN;  // 95% interval of the median (or of the statistic)
  // Half the interval's width relative to the median (0.02: +-2%); NaN when unknown.
  double RelativeHalfWidth() const { return (hi - lo) / 2 / std::fabs(median); }
};

// Wall seconds from t0 to now, on the steady clock.
inline double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median, min, max of `v` and the bootstrap interval of the median.
Spread SpreadOf(const std::vector<double>& v, uint64_t seed);
// A statistic f of the rounds, f(indices) on resampled round indices: its value on all rounds and
// the 95% percentile interval over `resamples` seeded resamples (n rounds drawn with replacement).
// min and max are those of the resampled values.
Spread Bootstrap(size_t n, const std::function<double(const std::vector<size_t>&)>& f,
                 uint64_t seed, int resamples = 2000);
// median(a[i]) / median(b[i]) over the same resampled rounds i (a and b of equal length: paired;
// otherwise each resampled on its own).
Spread RatioOfMedians(const std::vector<double>& a, const std::vector<double>& b, uint64_t seed);

double Median(std::vector<double> v);
double CoefficientOfVariation(const std::vector<double>& v);  // sample stddev / mean

enum class Verdict { kFaster, kSlower, kNotDistinguishable, kReference };
// For a speedup (time of the reference over time of the ordering): faster when the interval lies
// above 1, slower below, otherwise not distinguishable (also when the interval is unknown); the
// reference against itself (exactly 1) is the reference.
Verdict SpeedupVerdict(const Spread& speedup);
// For a gain ((T_ref - T) / T_ref): faster above 0, slower below.
Verdict GainVerdict(const Spread& gain);
const char* VerdictName(Verdict v);

// The five cells of a spread, `scale` applied (1e3: seconds to ms), at full precision; empty
// when unknown. ColumnNames: NAME, NAME_min, NAME_max, NAME_lo, NAME_hi.
std::vector<std::string> SpreadCells(const Spread& s, double scale = 1);
std::vector<std::string> SpreadColumns(const std::string& name);
Json SpreadJson(const Spread& s, double scale = 1);

// The machine's state around a timed run.
struct Noise {
  int cores = 0;
  double load_before = NAN, load_after = NAN;  // 1-minute load average
  double cpu_per_wall = NAN;  // lowest over the timed cells: thread CPU / (wall x threads)
  double cv = NAN;            // highest over the timed cells: the rounds' CV of the sweep time
  // Why the timings cannot be trusted as they are (empty: a quiet machine): load above the
  // cores, CPU/wall below 0.9, CV above 5%.
  std::vector<std::string> Reasons() const;
  Json ToJson() const;
};
double LoadAverage();  // /proc/loadavg's 1-minute figure; NaN where there is none
int Cores();           // online processors

}  // namespace meshreuse
