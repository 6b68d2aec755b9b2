// An exact sum of non-negative doubles below 2^6 in 128-bit fixed point (units of 2^-120): each
// term is truncated to the unit once, then the integer sum is exact, so the result does not depend
// on the order of the terms or on how they are split among ranks (../shared/scale-out.md 3b: the
// distributed smoother's global quality, identical for every P). Q = sum_t w_t q_t <= 1, so 2^6
// leaves room for any partial sum; a term of 2^-120 or less (none in a mesh of fewer than 10^30
// triangles) counts as zero. AddAll adds many terms at about the cost of two double sums, to the
// same value (fixed_sum.cc says why it is exact): issue 40's one rank beside the serial smoother.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace meshreuse {

class FixedSum {
 public:
  static constexpr int kFractionBits = 120;
  FixedSum() = default;
  // x in [0, 2^6); a negative or non-finite term is a caller's bug (std::logic_error).
  // Equal to adding (unsigned __int128)ldexp(x, 120) (exact scaling, then truncation), but
  // from the bits: mantissa shifted by the exponent, with no call into libgcc's conversion (a
  // sweep adds one term per triangle, so this is on the distributed smoother's hot path).
  void Add(double x) {
    if (__builtin_expect(!(x >= 0.0 && x < 64.0), 0))
      throw std::logic_error("FixedSum: term outside [0, 64)");
    v_ += Units(x);
  }
  // The same value as Add(x[k]) for k in [0, n), in any order: a block of 2^10 terms, all in
  // [2^-68, 64) and the largest one's binade at most 32 above the smallest one's, is summed
  // exactly in doubles (fixed_sum.cc); any other block term by term (a bad term throws as in Add).
  void AddAll(const double* x, int64_t n);
  void Add(const FixedSum& o) { v_ += o.v_; }
  double ToDouble() const { return std::ldexp(static_cast<double>(v_), -kFractionBits); }
  // (this - o) as a double: the improvement of a sweep, rounded once.
  double Minus(const FixedSum& o) const {
    const __int128 d = static_cast<__int128>(v_) - static_cast<__int128>(o.v_);
    return std::ldexp(static_cast<double>(d), -kFractionBits);
  }
  bool operator==(const FixedSum& o) const { return v_ == o.v_; }
  bool operator!=(const FixedSum& o) const { return v_ != o.v_; }
  // Two 64-bit words (low, high) for a transport that reduces them (MPI user-defined op).
  void ToWords(uint64_t w[2]) const {
    w[0] = static_cast<uint64_t>(v_);
    w[1] = static_cast<uint64_t>(v_ >> 64);
  }
  static FixedSum FromWords(const uint64_t w[2]) {
    FixedSum s;
    s.v_ = (static_cast<unsigned __int128>(w[1]) << 64) | w[0];
    return s;
  }

 private:
  // |x| 2^120 truncated to an integer, modulo 2^128, for |x| < 2^60 (a shift below 128); exact
  // where x is a multiple of 2^-120. The mantissa shifted by the exponent, the sign ignored (so
  // -0.0 is 0, as +0.0).
  static unsigned __int128 Units(double x) {
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const int e = static_cast<int>((bits >> 52) & 0x7ff);  // biased exponent, without the sign
    if (e == 0) return 0;                                  // zero or subnormal: far below the unit
    const uint64_t m = (bits & ((uint64_t{1} << 52) - 1)) | (uint64_t{1} << 52);
    const int shift = e - 1075 + kFractionBits;  // |x| = m 2^(e-1075); units of 2^-120
    if (shift >= 0) return static_cast<unsigned __int128>(m) << shift;
    return shift > -64 ? m >> -shift : 0;
  }
  // Adds y, a multiple of 2^-120 of either sign (AddAll's exact partial sums), modulo 2^128.
  void AddMultipleOfUnit(double y) {
    if (std::signbit(y))
      v_ -= Units(y);
    else
      v_ += Units(y);
  }
  unsigned __int128 v_ = 0;
};

}  // namespace meshreuse
