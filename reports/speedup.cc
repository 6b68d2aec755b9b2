// Speedup and Gain; see speedup.h.
#include "reports/speedup.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace meshreuse {

namespace {

std::vector<double> Sweeps(const CompareRow& r, TimeClock c) {
  return r.Values(c == TimeClock::kWall ? &CompareRound::sweep_wall : &CompareRound::sweep_cpu);
}

// A seed per comparison, so two comparisons never share a resampling stream.
uint64_t SeedOf(uint64_t seed, const CompareRow& a, const CompareRow& b) {
  return seed ^
         std::hash<std::string>()(a.mesh + '|' + a.ordering + '|' + std::to_string(a.threads) +
                                  '|' + b.ordering + '|' + std::to_string(b.threads));
}

Spread ToGain(const Spread& s) {  // 1 - 1/speedup: monotone, so the interval maps end to end
  auto g = [](double x) { return 1 - 1 / x; };
  return {g(s.median), g(s.min), g(s.max), g(s.lo), g(s.hi)};
}

}  // namespace

Spread Speedup(const CompareRow* ref, const CompareRow* r, uint64_t seed, TimeClock clock) {
  if (!ref || !r) return Spread();
  if (ref == r) return {1, 1, 1, 1, 1};  // the reference itself
  return RatioOfMedians(Sweeps(*ref, clock), Sweeps(*r, clock), SeedOf(seed, *ref, *r));
}

Spread Gain(const CompareRow* ref, const CompareRow* r, uint64_t seed, TimeClock clock) {
  if (!ref || !r || ref == r || ref->ordering == r->ordering) return Spread();
  return ToGain(Speedup(ref, r, seed, clock));
}

Spread MeanRatio(const std::vector<std::pair<const CompareRow*, const CompareRow*>>& pairs,
                 uint64_t seed, bool gain, TimeClock clock) {
  std::vector<std::pair<std::vector<double>, std::vector<double>>> sides;
  for (const auto& [ref, r] : pairs) {
    if (!ref || !r || (gain && (ref == r || ref->ordering == r->ordering))) continue;
    sides.emplace_back(Sweeps(*ref, clock), Sweeps(*r, clock));
  }
  Spread out;
  if (sides.empty()) return out;
  auto ratio = [gain](double a, double b) { return gain ? 1 - b / a : a / b; };
  std::vector<double> point;
  for (const auto& [a, b] : sides) point.push_back(ratio(Median(a), Median(b)));
  double sum = 0;
  for (double v : point) sum += v;
  out.median = sum / static_cast<double>(point.size());
  out.min = *std::min_element(point.begin(), point.end());
  out.max = *std::max_element(point.begin(), point.end());
  // Each pair's rounds resampled (paired within a mesh: its rounds interleave), one stream.
  uint64_t x = seed ^ 0x3EA7ull;
  auto next = [&x] {
    uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  std::vector<double> means;
  for (int rep = 0; rep < 2000; ++rep) {
    double m = 0;
    for (const auto& [a, b] : sides) {
      std::vector<double> ra, rb;
      const bool paired = a.size() == b.size();
      for (size_t k = 0; k < a.size(); ++k) {
        const size_t i = next() % a.size();
        ra.push_back(a[i]);
        if (paired) rb.push_back(b[i]);
      }
      if (!paired)
        for (size_t k = 0; k < b.size(); ++k) rb.push_back(b[next() % b.size()]);
      m += ratio(Median(ra), Median(rb));
    }
    means.push_back(m / static_cast<double>(sides.size()));
  }
  std::sort(means.begin(), means.end());
  out.lo = means[static_cast<size_t>(0.025 * (means.size() - 1))];
  out.hi = means[static_cast<size_t>(0.975 * (means.size() - 1))];
  return out;
}

TimingIndex::TimingIndex(const std::vector<CompareRow>& rows) {
  for (const CompareRow& r : rows) rows_[{r.mesh, r.ordering, r.threads}] = &r;
}

const CompareRow* TimingIndex::Find(const std::string& mesh, const std::string& ordering,
                                    int threads) const {
  const auto it = rows_.find({mesh, ordering, threads});
  return it == rows_.end() ? nullptr : it->second;
}

}  // namespace meshreuse
