// FixedSum::AddAll against the per-term Add it must equal bit for bit (the naive reference): blocks
// that take the split double sums and blocks that must not (zeros, terms Add truncates, ranges
// wider than 2^32, bad terms), every length around the block size, and the argument's bounds at
// their limits.
#include "core/fixed_sum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace meshreuse {
namespace {

FixedSum TermByTerm(const std::vector<double>& x) {
  FixedSum s;
  for (double v : x) s.Add(v);
  return s;
}

FixedSum AllAtOnce(const std::vector<double>& x) {
  FixedSum s;
  s.AddAll(x.data(), static_cast<int64_t>(x.size()));
  return s;
}

std::string Words(const FixedSum& s) {
  uint64_t w[2];
  s.ToWords(w);
  char b[40];
  std::snprintf(b, sizeof b, "%016llx%016llx", static_cast<unsigned long long>(w[1]),
                static_cast<unsigned long long>(w[0]));
  return b;
}

// n terms m 2^e, m uniform in [1, 2), e uniform in [lo, hi].
std::vector<double> Terms(std::mt19937_64& rng, int64_t n, int lo, int hi) {
  std::uniform_real_distribution<double> m(1.0, 2.0);
  std::uniform_int_distribution<int> e(lo, hi);
  std::vector<double> x(static_cast<size_t>(n));
  for (double& v : x) v = std::ldexp(m(rng), e(rng));
  return x;
}

TEST(FixedSum, AddAllEqualsAddTermByTerm) {
  std::mt19937_64 rng(11);
  // A mesh's weighted qualities (about 1 / V times a quality in (0, 1]), every length around the
  // block of 1024, and ranges from one binade to far beyond 2^32.
  for (int64_t n : {1, 2, 15, 16, 17, 1023, 1024, 1025, 2048, 5000}) {
    for (auto [lo, hi] : {std::pair{-20, -20},
                          {-30, -18},
                          {-50, -19},
                          {-52, -19},
                          {-68, -37},
                          {-68, 5},
                          {-80, -40},
                          {-130, -100},
                          {-3, 5}}) {
      const std::vector<double> x = Terms(rng, n, lo, hi);
      ASSERT_EQ(Words(AllAtOnce(x)), Words(TermByTerm(x))) << n << " " << lo << " " << hi;
    }
  }
}

// The argument's limits: ranges of 2^31, 2^32 (the widest taken), 2^33 and 2^34 (term by term),
// each block built so that its low parts all round the same way (every large term sits just below
// half a grid step above a grid point) and the smallest term's last bit is set, so the low sum
// needs every bit the bound allows: a check that took 2^34 rounds it and fails here (2^33 would
// still be exact when rounding to nearest, where a low part is at most half a step; the check
// keeps that binade for the other rounding modes). Then the largest terms below 64 with the
// smallest at 2^-68 and just below it (truncated by Add), every term at the top of its binade
// (the largest high sum the bounds allow), and past the contract's 2^6 (the two wrap modulo 2^128
// alike).
TEST(FixedSum, AddAllEqualsAddAtTheArgumentsLimits) {
  const double below64 = std::nextafter(64.0, 0.0);
  std::vector<std::vector<double>> cases;
  for (int d : {31, 32, 33, 34}) {
    // Terms in [2^-18, 2^-17): the grid is 2^-59, their last bit 2^-70; 1023 2^-70 is just
    // below half a step.
    std::vector<double> x(1024, std::ldexp(1.0, -18) + 1023 * std::ldexp(1.0, -70));
    x[7] = std::ldexp(1.0 + std::ldexp(1.0, -52), -18 - d);
    cases.push_back(x);
  }
  for (double small :
       {std::ldexp(1.0, -68), std::nextafter(std::ldexp(1.0, -68), 0.0), std::ldexp(1.0, -63)}) {
    std::vector<double> x(1024, std::ldexp(1.0, -37));
    x[3] = small;
    x[4] = std::nextafter(std::ldexp(1.0, -36), 0.0);
    cases.push_back(x);
  }
  cases.push_back(std::vector<double>(1024, below64));  // 2^16: past 2^6, both wrap
  std::vector<double> top(1024, std::nextafter(2.0, 0.0));
  top[0] = std::ldexp(1.0, -30);
  cases.push_back(top);
  std::vector<double> with_zero(1024, 1e-6);  // a zero and a subnormal: term by term
  with_zero[10] = 0.0, with_zero[11] = std::numeric_limits<double>::denorm_min();
  with_zero[12] = -0.0;
  cases.push_back(with_zero);
  for (size_t i = 0; i < cases.size(); ++i)
    EXPECT_EQ(Words(AllAtOnce(cases[i])), Words(TermByTerm(cases[i]))) << "case " << i;
}

// The values themselves, not only the agreement: sums a reader can check by hand.
TEST(FixedSum, AddAllGivesKnownSums) {
  std::vector<double> x(3000, 0.0078125);
  x.push_back(std::ldexp(1.0, -100));
  const FixedSum s = AllAtOnce(x);
  uint64_t w[2];
  s.ToWords(w);
  // 3000 2^-7 + 2^-100 in units of 2^-120: 3000 2^113 + 2^20.
  EXPECT_EQ(w[0], uint64_t{1} << 20);
  EXPECT_EQ(w[1], uint64_t{3000} << 49);
  EXPECT_EQ(s.ToDouble(), 23.4375);
}

TEST(FixedSum, AddAllRefusesWhatAddRefuses) {
  for (double bad :
       {-1e-300, -1.0, 64.0, std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::quiet_NaN()}) {
    std::vector<double> x(2000, 1e-6);
    x[1500] = bad;
    FixedSum s;
    EXPECT_THROW(s.AddAll(x.data(), static_cast<int64_t>(x.size())), std::logic_error) << bad;
  }
}

}  // namespace
}  // namespace meshreuse
