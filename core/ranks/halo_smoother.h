// Laplacian smoothing of one rank's part (rank_part.h) with the ghost exchanges of
// ../shared/scale-out.md 3b, over the one message layer (core/ranks/communicator.h: MPI or
// threads), so this library stays MPI-free. Three modes:
//   ordered (default): non-cut vertices in local order; then, once every neighbour of a lower
//     colour has sent its new cut values, the cut vertices in local order; the new cut values go
//     to every neighbour; the higher colours' values are received before the sweep ends. Same-
//     colour parts never touch and non-cut vertices read owned values only, so one sweep is bit for
//     bit the serial Gauss-Seidel sweep along pi = (every rank's non-cut vertices) ++ (cut vertices
//     of colour 0) ++ (colour 1) ++ ... (GatheredVisitOrder): each vertex reads the new value of
//     a neighbour before it in pi and the old value of one after it, summed in increasing global id
//     (the serial mesh's row order). `meshreuse smooth --visit-order` runs that serial sweep.
//     That is the default cut placement (rank_part.h, kLast). With kFirst a rank waits for the
//     lower colours, moves its cut vertices, sends them and moves its non-cut ones while they
//     travel: pi = (cut vertices of colour 0) ++ (colour 1) ++ ... ++ (every rank's non-cut
//     vertices), exact because a cut vertex reads its own non-cut neighbours' old values and a
//     non-cut vertex reads owned values only. With kInterleaved a rank waits for the lower colours,
//     then sweeps everything in its ordering: pi = (colour 0's parts whole) ++ (colour 1's) ++ ...
//     (a colour's sweep waits for the whole sweep of the ones below: the placement's cost).
//   jacobi: every movable vertex from the previous sweep's values, then one exchange: bit for bit
//     the serial Jacobi sweep.
//   hybrid: Gauss-Seidel inside the part reading ghosts from the previous sweep, one exchange per
//     sweep. Equal to no serial order: for timing studies only.
// A move is the serial smoother's (MoveToAverage, smoother.h) operation for operation. The global
// quality Q = sum_t w_t q_t is summed over owned triangles in exact fixed point (fixed_sum.h) and
// combined across ranks, so Q, each sweep's improvement and the stop decision are identical for
// every number of ranks (the serial smoother sums in floating point: its Q differs in the last
// bits, its moves do not). Stop rule as the serial one: a sweep improving Q by less than `tol` is
// the last; at most `max_iters` sweeps.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/fixed_sum.h"
#include "core/mesh.h"
#include "core/ranks/communicator.h"
#include "core/ranks/rank_part.h"
#include "core/smoother.h"

namespace meshreuse {

enum class HaloMode { kOrdered, kJacobi, kHybrid };
HaloMode ParseHaloMode(const std::string& s);  // ordered | jacobi | hybrid; UsageError
const char* HaloModeName(HaloMode m);

struct HaloOptions {
  int max_iters = 100;
  double tol = 5e-6;
  HaloMode mode = HaloMode::kOrdered;
};

struct HaloSweep {
  int sweep = 0;            // 1-based
  double quality = 0;       // Q after the sweep (exact sum, rounded once)
  double improvement = 0;   // Q - previous Q (exact difference, rounded once)
  double seconds = 0;       // wall time of the sweep on this rank, quality reduction included
  double cpu_seconds = 0;   // this rank's thread CPU time moving vertices and packing
  double wait_seconds = 0;  // wall time blocked in Recv
  double work_seconds = 0;  // wall time of the spans cpu_seconds measures (their ratio: how much
                            // of its work time the rank had a core)
};

struct HaloResult {
  std::vector<HaloSweep> sweeps;
  FixedSum quality_before, quality_after;
  bool converged = false;
  uint64_t messages = 0, values_sent = 0;  // doubles sent, all sweeps
};

// Q over the part's owned triangles (its share of the global quality).
FixedSum PartQuality(const RankPart& p);
// The same sum over the whole mesh, serially: what the ranks' shares add up to.
FixedSum FixedGlobalQuality(const Mesh& m);

// Loads and stores a traced sweep of the part makes (below), and element touches among them; the
// same in every mode: each movable vertex moved once, each link's values packed once and unpacked
// once, one quality pass.
struct HaloSweepCounts {
  uint64_t refs = 0, elements = 0;
};
HaloSweepCounts TracedPerSweep(const RankPart& p);

namespace halo_detail {

// Every link's lists and values in one array each (the ids sent, the values sent, the ids
// received, the values received; link i's from offset off[i], values at twice it): four arrays a
// trace can name (core/access.h) whatever the number of neighbours.
struct Messages {
  explicit Messages(const RankPart& p);
  std::vector<size_t> send_off, recv_off;  // per link, and the end
  AlignedVector<int32_t> send, recv;
  AlignedVector<double> out, in;
};

// Vertices [b, e) each to the average of its neighbours read from `src`, written to `dst`: the
// serial smoother's move (smoother.h MoveToAverage: sums in row order, one division, two
// products), so the same bits and, traced, the same accesses for each move.
template <class Sink>
void MoveRange(const Csr& v2v, const double* src, double* dst, Array dst_array, int32_t b,
               int32_t e, Sink& sink) {
  smoother_detail::Arrays a{};
  a.off = v2v.off.data();
  a.nbr = v2v.idx.data();
  for (int32_t k = b; k < e; ++k)
    smoother_detail::MoveToAverage(a, src, dst, dst_array, k, 0, sink);
}

// Q over the part's owned triangles, reporting what its pass loads: per triangle its corners
// (4 B each), the x and y of each (8 B each, element kCoordRead on the x) and its weight (8 B).
template <class Sink>
FixedSum TracedPartQuality(const RankPart& p, Sink& sink) {
  if constexpr (Sink::kEnabled) {
    const int64_t nt = static_cast<int64_t>(p.weight.size());
    for (int64_t t = 0; t < nt; ++t) {
      for (int j = 0; j < 3; ++j)
        smoother_detail::Report(sink, 0, &p.tri[3 * t + j], 4, Array::kTriangles, false);
      for (int j = 0; j < 3; ++j) {
        const int32_t c = p.tri[3 * t + j];
        const double* xy = p.xy.data() + 2 * int64_t{c};
        smoother_detail::Report(sink, 0, xy, 8, Array::kCoords, false, AccessKind::kCoordRead, c);
        smoother_detail::Report(sink, 0, xy + 1, 8, Array::kCoords, false);
      }
      smoother_detail::Report(sink, 0, &p.weight[t], 8, Array::kWeights, false);
    }
  }
  return PartQuality(p);
}

// The messages of one rank's sweep. A pack, per vertex sent: its id (4 B), its coordinates (one
// 16 B load, element kCoordRead), the buffer (one 16 B store); an unpack, per ghost received: its
// id, the buffer (16 B load), its coordinates (16 B store, element kCoordWrite). The communicator's
// own copies are not the rank's sweep (MPI's, or another thread's) and are not reported.
template <class Sink>
class SweepRunner {
 public:
  SweepRunner(RankPart& p, Communicator& tx, HaloResult* r, Sink& sink)
      : p_(p), tx_(tx), r_(r), m_(p), sink_(sink) {}
  const Messages& messages() const { return m_; }

  // Sends this rank's new values of the vertices link i's rank ghosts, read from `xy`.
  void SendTo(size_t i, const double* xy, Array xy_array) {
    const size_t b = m_.send_off[i], e = m_.send_off[i + 1];
    if (b == e) return;
    double* o = m_.out.data();
    for (size_t j = b; j < e; ++j) {
      const int64_t v = smoother_detail::Load(sink_, 0, Array::kSendIndex, m_.send.data() + j);
      smoother_detail::Report(sink_, 0, xy + 2 * v, 16, xy_array, false, AccessKind::kCoordRead,
                              static_cast<int32_t>(v));
      smoother_detail::Report(sink_, 0, o + 2 * j, 16, Array::kSendBuffer, true);
      o[2 * j] = xy[2 * v];
      o[2 * j + 1] = xy[2 * v + 1];
    }
    tx_.SendValues(p_.links[i].rank, o + 2 * b, 16 * (e - b));
    ++r_->messages;
    r_->values_sent += 2 * (e - b);
  }
  void ReceiveFrom(size_t i, double* xy, Array xy_array) {
    const size_t b = m_.recv_off[i], e = m_.recv_off[i + 1];
    if (b == e) return;
    double* in = m_.in.data();
    const auto t0 = std::chrono::steady_clock::now();
    tx_.RecvValues(p_.links[i].rank, in + 2 * b, 16 * (e - b));
    wait_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (size_t j = b; j < e; ++j) {
      const int64_t v = smoother_detail::Load(sink_, 0, Array::kRecvIndex, m_.recv.data() + j);
      smoother_detail::Report(sink_, 0, in + 2 * j, 16, Array::kRecvBuffer, false);
      smoother_detail::Report(sink_, 0, xy + 2 * v, 16, xy_array, true, AccessKind::kCoordWrite,
                              static_cast<int32_t>(v));
      xy[2 * v] = in[2 * j];
      xy[2 * v + 1] = in[2 * j + 1];
    }
  }
  double TakeWait() { return std::exchange(wait_, 0.0); }

 private:
  RankPart& p_;
  Communicator& tx_;
  HaloResult* r_;
  Messages m_;
  Sink& sink_;
  double wait_ = 0;
};

}  // namespace halo_detail

// Smooths the part in place; every rank of the communicator calls it with the same options.
// `on_sweep` runs after each sweep (after the reduction: the same values on every rank).
// Tracing is the template parameter, as for the serial smoother: `sink` sees, before each sweep
// k, BeginSweep(k), then every load and store of the rank's sweep in program order (thread 0):
// the moves as smoother.h lists them (without the interior list and loop bound: the rank's loop
// runs over local ids), the packs and unpacks of its messages (above) where the mode makes them,
// and the quality pass. TracedPerSweep counts them. The initial quality is not traced (the serial
// smoother's is not either).
template <class Sink>
HaloResult SmoothRankPart(RankPart& p, const HaloOptions& opt, Communicator& tx, Sink& sink,
                          const std::function<void(const HaloSweep&)>& on_sweep = {}) {
  using Clock = std::chrono::steady_clock;
  HaloResult r;
  halo_detail::SweepRunner<Sink> run(p, tx, &r, sink);
  AlignedVector<double> next;
  if (opt.mode == HaloMode::kJacobi) next = p.xy;
  if constexpr (Sink::kEnabled) {
    ArrayLayout l;
    auto put = [&](Array a, const auto& v) {
      l.base[static_cast<int>(a)] = reinterpret_cast<uintptr_t>(v.data());
      l.bytes[static_cast<int>(a)] = v.size() * sizeof(v[0]);
    };
    const halo_detail::Messages& m = run.messages();
    put(Array::kAdjOffsets, p.v2v.off);
    put(Array::kAdjIndex, p.v2v.idx);
    put(Array::kTriangles, p.tri);
    put(Array::kWeights, p.weight);
    put(Array::kCoords, p.xy);
    put(Array::kCoordsNext, next);
    put(Array::kSendIndex, m.send);
    put(Array::kSendBuffer, m.out);
    put(Array::kRecvIndex, m.recv);
    put(Array::kRecvBuffer, m.in);
    sink.Bind(l);
  }
  r.quality_before = tx.AllReduceSum(PartQuality(p));
  FixedSum q = r.quality_before;
  const size_t links = p.links.size();
  for (int it = 1; it <= opt.max_iters; ++it) {
    if constexpr (Sink::kEnabled) sink.BeginSweep(it);
    const auto t0 = Clock::now();
    double cpu = 0, work = 0;
    auto timed = [&cpu, &work](auto&& f) {
      const double c0 = ThreadCpuSeconds();
      const auto w0 = Clock::now();
      f();
      cpu += ThreadCpuSeconds() - c0;
      work += std::chrono::duration<double>(Clock::now() - w0).count();
    };
    double* xy = p.xy.data();
    constexpr Array kXy = Array::kCoords;
    switch (opt.mode) {
      case HaloMode::kOrdered: {
        // [0, before): moves that read no ghost, made before waiting for the lower colours;
        // [before, sent): moves sent when done; [sent, movable): moves made while they travel.
        const int32_t before = p.placement == CutPlacement::kLast ? p.noncut : 0;
        const int32_t sent = p.placement == CutPlacement::kFirst ? p.cut() : p.movable;
        timed([&] { halo_detail::MoveRange(p.v2v, xy, xy, kXy, 0, before, sink); });
        for (size_t i = 0; i < links; ++i)
          if (p.links[i].colour < p.colour) run.ReceiveFrom(i, xy, kXy);
        timed([&] {
          halo_detail::MoveRange(p.v2v, xy, xy, kXy, before, sent, sink);
          for (size_t i = 0; i < links; ++i) run.SendTo(i, xy, kXy);
          halo_detail::MoveRange(p.v2v, xy, xy, kXy, sent, p.movable, sink);
        });
        for (size_t i = 0; i < links; ++i)
          if (p.links[i].colour > p.colour) run.ReceiveFrom(i, xy, kXy);
        break;
      }
      case HaloMode::kHybrid:
        timed([&] {
          halo_detail::MoveRange(p.v2v, xy, xy, kXy, 0, p.movable, sink);
          for (size_t i = 0; i < links; ++i) run.SendTo(i, xy, kXy);
        });
        for (size_t i = 0; i < links; ++i) run.ReceiveFrom(i, xy, kXy);
        break;
      case HaloMode::kJacobi: {
        double* nx = next.data();
        constexpr Array kNext = Array::kCoordsNext;
        timed([&] {
          halo_detail::MoveRange(p.v2v, xy, nx, kNext, 0, p.movable, sink);
          for (size_t i = 0; i < links; ++i) run.SendTo(i, nx, kNext);
        });
        for (size_t i = 0; i < links; ++i) run.ReceiveFrom(i, nx, kNext);
        p.xy.swap(next);  // fixed and unchanged values are equal in both buffers
        break;
      }
    }
    tx.Flush();
    FixedSum part;
    timed([&] { part = halo_detail::TracedPartQuality(p, sink); });
    const FixedSum q_new = tx.AllReduceSum(part);
    HaloSweep s;
    s.sweep = it;
    s.quality = q_new.ToDouble();
    s.improvement = q_new.Minus(q);
    s.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    s.cpu_seconds = cpu;
    s.work_seconds = work;
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

// The timed, untraced sweep.
HaloResult SmoothRankPart(RankPart& p, const HaloOptions& opt, Communicator& tx,
                          const std::function<void(const HaloSweep&)>& on_sweep = {});

}  // namespace meshreuse
