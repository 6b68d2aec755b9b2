// FixedSum::AddAll: a block of terms summed exactly in two double sums, then added in 128 bits
// twice, instead of one 128-bit shift and add per term (on the distributed smoother's quality
// pass that per-term add cost as much as the triangles' qualities).
//
// Why it is exact. Take a block of n <= 2^L terms (L = 10), every term in [2^el, 2^(eh+1)) with
// el >= -68 and d = eh - el <= 52 - 2L. Each term x is then a multiple of 2^(el-52) >= 2^-120, so
// Add(x) truncates nothing and adds exactly x 2^120. Let G = 2^g, g = eh + L - 51, and
// C = 1.5 2^(g+52).
// - yh = (x + C) - C is a multiple of G: x < 2^(eh+1) = 2^(g+52-L), so x + C lies in
//   [2^(g+52), 2^(g+53)), where doubles are G apart, and the subtraction of two doubles of one
//   binade is exact (Sterbenz). |x - yh| < G in any rounding mode.
// - yl = x - yh is exact: both are multiples of 2^(el-52) (g > el - 52), and |yl| < G needs
//   g - el + 52 <= 53 bits, i.e. d <= 52 - L.
// - Any sum of some of the yl is a multiple of 2^(el-52) below n G <= 2^(L+g) <= 2^(el+1) (that
//   is d <= 52 - 2L): at most 53 bits, so every addition of them is exact, in any order. (Rounding
//   to nearest, |yl| <= G/2 and d = 53 - 2L would do; the check keeps that binade for the other
//   rounding modes.)
// - Any sum of some of the yh is a multiple of G below n (2^(eh+1) + G) < 2^(L+eh+2) = 2^(g+53):
//   exact too.
// So H = sum yh and Lo = sum yl are exact whatever the order (the vector lanes' order), H + Lo is
// the block's sum, and both are multiples of 2^-120: adding each in units of 2^-120 adds exactly
// what the per-term Adds would, modulo 2^128 as they do. A block that breaks a condition (a zero,
// a term below 2^-68 that Add would truncate, a NaN, a negative or too large term, binades more
// than 32 apart) goes term by term. The conditions are read from the terms' bits as signed
// integers: for doubles of either sign and NaNs their order is the order the checks need (every
// negative double and -0.0 is below 2^-68's bits, every NaN and infinity at or above 64's).
// Needs IEEE double arithmetic as written: no -ffast-math (which would fold (x + C) - C to x).
#include "core/fixed_sum.h"

#include <algorithm>

namespace meshreuse {
namespace {

constexpr int kLogBlock = 10;
constexpr int64_t kBlock = int64_t{1} << kLogBlock;
constexpr int64_t kLowBits = int64_t{1023 - 68} << 52;  // 2^-68
constexpr int64_t kHighBits = int64_t{1023 + 6} << 52;  // 64.0

// Sums x[0, n), 0 < n <= kBlock, exactly into *h + *lo; false where the block breaks a condition
// of the argument above (nothing is summed then).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
bool SplitSum(const double* x, int64_t n, double* h, double* lo) {
  int64_t min_bits = INT64_MAX, max_bits = INT64_MIN;
#pragma omp simd reduction(min : min_bits) reduction(max : max_bits)
  for (int64_t k = 0; k < n; ++k) {
    int64_t b;
    std::memcpy(&b, x + k, sizeof b);
    min_bits = b < min_bits ? b : min_bits;
    max_bits = b > max_bits ? b : max_bits;
  }
  if (min_bits < kLowBits || max_bits >= kHighBits) return false;
  const int eh = static_cast<int>(max_bits >> 52) - 1023;
  const int el = static_cast<int>(min_bits >> 52) - 1023;
  if (eh - el > 52 - 2 * kLogBlock) return false;
  const int g = eh + kLogBlock - 51;
  const uint64_t c_bits = (static_cast<uint64_t>(g + 52 + 1023) << 52) | (uint64_t{1} << 51);
  double c;
  std::memcpy(&c, &c_bits, sizeof c);
  double sh = 0.0, sl = 0.0;
#pragma omp simd reduction(+ : sh, sl)
  for (int64_t k = 0; k < n; ++k) {
    const double yh = (x[k] + c) - c;
    sh += yh;
    sl += x[k] - yh;
  }
  *h = sh;
  *lo = sl;
  return true;
}

}  // namespace

void FixedSum::AddAll(const double* x, int64_t n) {
  for (int64_t b = 0; b < n; b += kBlock) {
    const int64_t len = std::min(kBlock, n - b);
    double h, lo;
    if (SplitSum(x + b, len, &h, &lo)) {
      AddMultipleOfUnit(h);
      AddMultipleOfUnit(lo);
    } else {
      for (int64_t k = 0; k < len; ++k) Add(x[b + k]);
    }
  }
}

}  // namespace meshreuse
