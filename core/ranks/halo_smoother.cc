// The untraced instance of halo_smoother.h's sweep (the sweep itself is a template there, so a
// tracing sink can see it), its message arrays, the traced sweep's counts, and the exact quality.
#include "core/ranks/halo_smoother.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "core/error.h"
#include "core/quality.h"
#include "core/smoother.h"

namespace meshreuse {

HaloMode ParseHaloMode(const std::string& s) {
  if (s == "ordered") return HaloMode::kOrdered;
  if (s == "jacobi") return HaloMode::kJacobi;
  if (s == "hybrid") return HaloMode::kHybrid;
  throw UsageError("unknown distributed mode '" + s + "' (ordered, jacobi or hybrid)");
}

const char* HaloModeName(HaloMode m) {
  switch (m) {
    case HaloMode::kOrdered:
      return "ordered";
    case HaloMode::kJacobi:
      return "jacobi";
    case HaloMode::kHybrid:
      return "hybrid";
  }
  return "?";
}

namespace {

// w[t] q_t for t in [b, b + n), n <= kBlock, into out: TriangleQualityAt as `omp simd` lanes,
// built for AVX-512, AVX2 and baseline x86-64 (GCC 12 vectorises the AVX-512 one, as it does the
// serial pass). This file is compiled with -ffp-contract=off (core/CMakeLists.txt): GCC's AVX-512
// target enables FMA and would fuse the products and sums, changing the bits. Unfused, and with
// sqrt and division exact in any width, every build gives the scalar function's bits. Then
// summed exactly (AddAll).
constexpr int64_t kBlock = 1024;
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void WeightedTerms(const double* xy, const int32_t* tri, const double* w, int64_t b, int64_t n,
                   double* out) {
#pragma omp simd
  for (int64_t k = 0; k < n; ++k) out[k] = w[b + k] * TriangleQualityAt(xy, tri, b + k);
}

FixedSum WeightedSum(const double* xy, const int32_t* tri, const double* w, int64_t n) {
  FixedSum s;
  double buf[kBlock];
  for (int64_t b = 0; b < n; b += kBlock) {
    const int64_t len = std::min(kBlock, n - b);
    WeightedTerms(xy, tri, w, b, len, buf);
    s.AddAll(buf, len);
  }
  return s;
}

}  // namespace

FixedSum PartQuality(const RankPart& p) {
  return WeightedSum(p.xy.data(), p.tri.data(), p.weight.data(),
                     static_cast<int64_t>(p.weight.size()));
}

FixedSum FixedGlobalQuality(const Mesh& m) {
  const std::vector<double> w = GlobalQualityWeights(m);
  return WeightedSum(m.xy.data(), m.tri.data(), w.data(), m.NumTriangles());
}

HaloSweepCounts TracedPerSweep(const RankPart& p) {
  HaloSweepCounts c;
  for (int32_t k = 0; k < p.movable; ++k) {
    const uint64_t deg = static_cast<uint64_t>(p.v2v.RowSize(k));
    c.refs += 3 + 2 * deg;
    c.elements += 2 + deg;
  }
  uint64_t values = 0;
  for (const RankLink& l : p.links) values += l.send.size() + l.recv.size();
  c.refs += 3 * values;
  c.elements += values;
  c.refs += 10 * static_cast<uint64_t>(p.weight.size());
  c.elements += 3 * static_cast<uint64_t>(p.weight.size());
  return c;
}

namespace halo_detail {

Messages::Messages(const RankPart& p) {
  send_off.push_back(0);
  recv_off.push_back(0);
  for (const RankLink& l : p.links) {
    send.insert(send.end(), l.send.begin(), l.send.end());
    recv.insert(recv.end(), l.recv.begin(), l.recv.end());
    send_off.push_back(send.size());
    recv_off.push_back(recv.size());
  }
  out.assign(2 * send.size(), 0.0);
  in.assign(2 * recv.size(), 0.0);
}

}  // namespace halo_detail

HaloResult SmoothRankPart(RankPart& p, const HaloOptions& opt, Communicator& tx,
                          const std::function<void(const HaloSweep&)>& on_sweep) {
  NullSink none;
  return SmoothRankPart(p, opt, tx, none, on_sweep);
}

}  // namespace meshreuse
