// Spreads, bootstrap intervals, verdicts and noise; see timing.h.
#include "reports/timing.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "core/table.h"

namespace meshreuse {

namespace {

struct SplitMix64 {
  uint64_t s;
  uint64_t Next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
};

double Percentile(std::vector<double>& sorted, double p) {  // linear interpolation, sorted input
  if (sorted.empty()) return NAN;
  const double x = p * static_cast<double>(sorted.size() - 1);
  const size_t i = static_cast<size_t>(x);
  const double f = x - static_cast<double>(i);
  if (i + 1 >= sorted.size()) return sorted[i];
  // a + f (b - a): exactly a when a == b, and never outside [a, b] by rounding.
  return std::min(sorted[i + 1], std::max(sorted[i], sorted[i] + f * (sorted[i + 1] - sorted[i])));
}

double MedianOf(const std::vector<double>& v, const std::vector<size_t>& idx) {
  std::vector<double> s;
  s.reserve(idx.size());
  for (size_t i : idx) s.push_back(v[i]);
  return Median(std::move(s));
}

}  // namespace

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double CoefficientOfVariation(const std::vector<double>& v) {
  if (v.size() < 2) return NAN;
  double m = 0;
  for (double x : v) m += x;
  m /= static_cast<double>(v.size());
  double ss = 0;
  for (double x : v) ss += (x - m) * (x - m);
  return std::sqrt(ss / static_cast<double>(v.size() - 1)) / m;
}

Spread Bootstrap(size_t n, const std::function<double(const std::vector<size_t>&)>& f,
                 uint64_t seed, int resamples) {
  Spread s;
  if (n == 0) return s;
  std::vector<size_t> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = i;
  s.median = f(all);
  SplitMix64 rng{seed ^ 0x5EED0F0B007ull};
  std::vector<double> values;
  values.reserve(resamples);
  std::vector<size_t> idx(n);
  for (int b = 0; b < resamples; ++b) {
    for (size_t& i : idx) i = rng.Next() % n;
    const double v = f(idx);
    if (std::isfinite(v)) values.push_back(v);
  }
  std::sort(values.begin(), values.end());
  if (values.empty()) return s;
  s.min = values.front(), s.max = values.back();
  s.lo = Percentile(values, 0.025);
  s.hi = Percentile(values, 0.975);
  return s;
}

Spread SpreadOf(const std::vector<double>& v, uint64_t seed) {
  Spread s = Bootstrap(
      v.size(), [&v](const std::vector<size_t>& idx) { return MedianOf(v, idx); }, seed);
  if (!v.empty()) {
    s.min = *std::min_element(v.begin(), v.end());
    s.max = *std::max_element(v.begin(), v.end());
  }
  return s;
}

Spread RatioOfMedians(const std::vector<double>& a, const std::vector<double>& b, uint64_t seed) {
  if (a.empty() || b.empty()) return Spread();
  if (a.size() == b.size())
    return Bootstrap(
        a.size(),
        [&](const std::vector<size_t>& idx) { return MedianOf(a, idx) / MedianOf(b, idx); }, seed);
  // Unpaired: each side resampled on its own, from one stream.
  SplitMix64 rng{seed ^ 0xB00757A9ull};
  Spread s;
  std::vector<size_t> all_a(a.size()), all_b(b.size());
  for (size_t i = 0; i < a.size(); ++i) all_a[i] = i;
  for (size_t i = 0; i < b.size(); ++i) all_b[i] = i;
  s.median = MedianOf(a, all_a) / MedianOf(b, all_b);
  std::vector<double> values;
  for (int r = 0; r < 2000; ++r) {
    for (size_t& i : all_a) i = rng.Next() % a.size();
    for (size_t& i : all_b) i = rng.Next() % b.size();
    values.push_back(MedianOf(a, all_a) / MedianOf(b, all_b));
  }
  std::sort(values.begin(), values.end());
  s.min = values.front(), s.max = values.back();
  s.lo = Percentile(values, 0.025), s.hi = Percentile(values, 0.975);
  return s;
}

Verdict SpeedupVerdict(const Spread& s) {
  if (s.median == 1 && s.lo == 1 && s.hi == 1 && s.min == 1 && s.max == 1)
    return Verdict::kReference;
  if (!(std::isfinite(s.lo) && std::isfinite(s.hi))) return Verdict::kNotDistinguishable;
  if (s.lo > 1) return Verdict::kFaster;
  if (s.hi < 1) return Verdict::kSlower;
  return Verdict::kNotDistinguishable;
}

Verdict GainVerdict(const Spread& s) {
  if (!(std::isfinite(s.lo) && std::isfinite(s.hi))) return Verdict::kNotDistinguishable;
  if (s.lo > 0) return Verdict::kFaster;
  if (s.hi < 0) return Verdict::kSlower;
  return Verdict::kNotDistinguishable;
}

const char* VerdictName(Verdict v) {
  switch (v) {
    case Verdict::kFaster:
      return "faster";
    case Verdict::kSlower:
      return "slower";
    case Verdict::kReference:
      return "reference";
    case Verdict::kNotDistinguishable:
      break;
  }
  return "not distinguishable";
}

std::vector<std::string> SpreadCells(const Spread& s, double k) {
  return {ExactNumber(k * s.median), ExactNumber(k * s.min), ExactNumber(k * s.max),
          ExactNumber(k * s.lo), ExactNumber(k * s.hi)};
}

std::vector<std::string> SpreadColumns(const std::string& n) {
  return {n, n + "_min", n + "_max", n + "_lo", n + "_hi"};
}

Json SpreadJson(const Spread& s, double k) {
  auto num = [k](double v) { return std::isfinite(v) ? Json(k * v) : Json(nullptr); };
  return Json{{"median", num(s.median)},
              {"min", num(s.min)},
              {"max", num(s.max)},
              {"ci95_low", num(s.lo)},
              {"ci95_high", num(s.hi)}};
}

double LoadAverage() {
  std::ifstream in("/proc/loadavg");
  double l = NAN;
  if (!(in >> l)) return NAN;
  return l;
}

int Cores() {
  const long n = ::sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

std::vector<std::string> Noise::Reasons() const {
  std::vector<std::string> r;
  char b[200];
  const double load = std::max(std::isfinite(load_before) ? load_before : 0.0,
                               std::isfinite(load_after) ? load_after : 0.0);
  if (load > cores) {
    std::snprintf(b, sizeof b, "load average %.1f before and %.1f after, above the %d cores",
                  load_before, load_after, cores);
    r.push_back(b);
  }
  if (cpu_per_wall < 0.9) {
    std::snprintf(b, sizeof b,
                  "the timed sweeps ran %.0f%% of their wall time on a core (below 90%%: the "
                  "threads waited for cores)",
                  100 * cpu_per_wall);
    r.push_back(b);
  }
  if (cv > 0.05) {
    std::snprintf(b, sizeof b,
                  "the rounds' times vary by up to %.1f%% (coefficient of variation "
                  "above 5%%)",
                  100 * cv);
    r.push_back(b);
  }
  return r;
}

Json Noise::ToJson() const {
  auto num = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  return Json{{"cores", cores},
              {"load_before", num(load_before)},
              {"load_after", num(load_after)},
              {"cpu_per_wall_lowest", num(cpu_per_wall)},
              {"cv_highest", num(cv)},
              {"busy", !Reasons().empty()},
              {"reasons", Reasons()}};
}

}  // namespace meshreuse
