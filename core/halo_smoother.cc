// The distributed sweep of halo_smoother.h: one rank's moves, packs, unpacks and reduction.
#include "core/halo_smoother.h"

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

// w[t] q_t for t in [b, b + n), n <= kBlock, into out: TriangleQuality's operations in a loop the
// compiler vectorises (no FMA in the base x86-64 build, and sqrt and division are exact in any
// width), so the same bits as the scalar function; then added one by one, exactly.
constexpr int64_t kBlock = 256;
void WeightedTerms(const double* xy, const int32_t* tri, const double* w, int64_t b, int64_t n,
                   double* out) {
  for (int64_t k = 0; k < n; ++k) {
    const int64_t t = b + k;
    const double* pa = xy + 2 * int64_t{tri[3 * t]};
    const double* pb = xy + 2 * int64_t{tri[3 * t + 1]};
    const double* pc = xy + 2 * int64_t{tri[3 * t + 2]};
    out[k] = w[t] * TriangleQuality(pa[0], pa[1], pb[0], pb[1], pc[0], pc[1]);
  }
}

FixedSum WeightedSum(const double* xy, const int32_t* tri, const double* w, int64_t n) {
  FixedSum s;
  double buf[kBlock];
  for (int64_t b = 0; b < n; b += kBlock) {
    const int64_t len = std::min(kBlock, n - b);
    WeightedTerms(xy, tri, w, b, len, buf);
    for (int64_t k = 0; k < len; ++k) s.Add(buf[k]);
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

namespace {

// Vertices [b, e) each to the average of its neighbours read from `src`, written to `dst`: the
// serial MoveToAverage's operations in the same order (sums in row order, one division, two
// products), so the same bits.
void MoveRange(const Csr& v2v, const double* src, double* dst, int32_t b, int32_t e) {
  const int64_t* off = v2v.off.data();
  const int32_t* nbr = v2v.idx.data();
  for (int32_t k = b; k < e; ++k) {
    double sx = 0.0, sy = 0.0;
    for (int64_t i = off[k]; i < off[k + 1]; ++i) {
      sx += src[2 * int64_t{nbr[i]}];
      sy += src[2 * int64_t{nbr[i]} + 1];
    }
    const double inv = 1.0 / static_cast<double>(off[k + 1] - off[k]);
    dst[2 * int64_t{k}] = sx * inv;
    dst[2 * int64_t{k} + 1] = sy * inv;
  }
}

class SweepRunner {
 public:
  SweepRunner(RankPart& p, HaloTransport& tx, HaloResult* r) : p_(p), tx_(tx), r_(r) {
    out_.resize(p.links.size());
    in_.resize(p.links.size());
    for (size_t i = 0; i < p.links.size(); ++i) {
      out_[i].resize(2 * p.links[i].send.size());
      in_[i].resize(2 * p.links[i].recv.size());
    }
  }

  // Sends this rank's new values of the vertices link i's rank ghosts, read from `xy`.
  void SendTo(size_t i, const double* xy) {
    const RankLink& l = p_.links[i];
    if (l.send.empty()) return;
    double* o = out_[i].data();
    for (size_t j = 0; j < l.send.size(); ++j) {
      o[2 * j] = xy[2 * int64_t{l.send[j]}];
      o[2 * j + 1] = xy[2 * int64_t{l.send[j]} + 1];
    }
    tx_.Send(l.rank, o, out_[i].size());
    ++r_->messages;
    r_->values_sent += out_[i].size();
  }
  void ReceiveFrom(size_t i, double* xy) {
    const RankLink& l = p_.links[i];
    if (l.recv.empty()) return;
    const auto t0 = std::chrono::steady_clock::now();
    tx_.Recv(l.rank, in_[i].data(), in_[i].size());
    wait_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double* in = in_[i].data();
    for (size_t j = 0; j < l.recv.size(); ++j) {
      xy[2 * int64_t{l.recv[j]}] = in[2 * j];
      xy[2 * int64_t{l.recv[j]} + 1] = in[2 * j + 1];
    }
  }
  double TakeWait() { return std::exchange(wait_, 0.0); }

 private:
  RankPart& p_;
  HaloTransport& tx_;
  HaloResult* r_;
  std::vector<AlignedVector<double>> out_, in_;
  double wait_ = 0;
};

}  // namespace

HaloResult SmoothRankPart(RankPart& p, const HaloOptions& opt, HaloTransport& tx,
                          const std::function<void(const HaloSweep&)>& on_sweep) {
  using Clock = std::chrono::steady_clock;
  HaloResult r;
  SweepRunner run(p, tx, &r);
  AlignedVector<double> next;
  if (opt.mode == HaloMode::kJacobi) next = p.xy;
  r.quality_before = tx.SumAll(PartQuality(p));
  FixedSum q = r.quality_before;
  const size_t links = p.links.size();
  for (int it = 1; it <= opt.max_iters; ++it) {
    const auto t0 = Clock::now();
    double cpu = 0;
    auto timed = [&cpu](auto&& f) {
      const double c0 = ThreadCpuSeconds();
      f();
      cpu += ThreadCpuSeconds() - c0;
    };
    double* xy = p.xy.data();
    switch (opt.mode) {
      case HaloMode::kOrdered: {
        // [0, before): moves that read no ghost, made before waiting for the lower colours;
        // [before, sent): moves sent when done; [sent, movable): moves made while they travel.
        const int32_t before = p.placement == CutPlacement::kLast ? p.noncut : 0;
        const int32_t sent = p.placement == CutPlacement::kFirst ? p.cut() : p.movable;
        timed([&] { MoveRange(p.v2v, xy, xy, 0, before); });
        for (size_t i = 0; i < links; ++i)
          if (p.links[i].colour < p.colour) run.ReceiveFrom(i, xy);
        timed([&] {
          MoveRange(p.v2v, xy, xy, before, sent);
          for (size_t i = 0; i < links; ++i) run.SendTo(i, xy);
          MoveRange(p.v2v, xy, xy, sent, p.movable);
        });
        for (size_t i = 0; i < links; ++i)
          if (p.links[i].colour > p.colour) run.ReceiveFrom(i, xy);
        break;
      }
      case HaloMode::kHybrid:
        timed([&] {
          MoveRange(p.v2v, xy, xy, 0, p.movable);
          for (size_t i = 0; i < links; ++i) run.SendTo(i, xy);
        });
        for (size_t i = 0; i < links; ++i) run.ReceiveFrom(i, xy);
        break;
      case HaloMode::kJacobi:
        timed([&] {
          MoveRange(p.v2v, xy, next.data(), 0, p.movable);
          for (size_t i = 0; i < links; ++i) run.SendTo(i, next.data());
        });
        for (size_t i = 0; i < links; ++i) run.ReceiveFrom(i, next.data());
        p.xy.swap(next);  // fixed and unchanged values are equal in both buffers
        break;
    }
    tx.Flush();
    FixedSum part;
    timed([&] { part = PartQuality(p); });
    const FixedSum q_new = tx.SumAll(part);
    HaloSweep s;
    s.sweep = it;
    s.quality = q_new.ToDouble();
    s.improvement = q_new.Minus(q);
    s.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    s.cpu_seconds = cpu;
    s.wait_seconds = run.TakeWait();
    r.sweeps.push_back(s);
    q = q_new;
    if (on_sweep) on_sweep(s);
    if (s.improvement < opt.tol) {
      r.converged = true;
      break;
    }
  }
  r.quality_after = q;
  return r;
}

}  // namespace meshreuse
