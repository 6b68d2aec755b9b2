// What the kernels of core/kernels/ share: binding their arrays to a sink, the sweep driver (the
// smoother's loop: timed sweeps, thread CPU time, the stop rule), a vertex's patch gathered once
// per visit (local-opt, untangle), signed areas and the per-triangle weight/quality array of the
// global quality (core/quality.h) that the smoothing kernels keep incrementally.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <stdexcept>

#include "core/kernels/kernel.h"
#include "core/quality.h"

namespace meshreuse::kernel_detail {

using smoother_detail::Load;
using smoother_detail::Report;

struct Bound {
  Array array;
  const void* data;
  uint64_t bytes;
};
template <class Sink>
void BindArrays(Sink& sink, std::initializer_list<Bound> arrays) {
  if constexpr (Sink::kEnabled) {
    ArrayLayout l;
    for (const Bound& b : arrays) {
      l.base[static_cast<int>(b.array)] = reinterpret_cast<uintptr_t>(b.data);
      l.bytes[static_cast<int>(b.array)] = b.bytes;
    }
    sink.Bind(l);
  }
}
template <class V>
Bound Of(Array a, const V& v) {
  return {a, v.data(), static_cast<uint64_t>(v.size() * sizeof(v[0]))};
}

// The set-up of type S that `o` carries (SmoothOptions::setup; nullptr: none). One of another
// kernel, or one that `fits` says was made from a mesh of other sizes, is a caller's bug.
template <class S, class Fits>
const S* SetupOf(const SmoothOptions& o, Fits fits) {
  if (!o.setup) return nullptr;
  const S* s = dynamic_cast<const S*>(o.setup);
  if (!s || !fits(*s)) throw std::logic_error("a kernel set-up made for another kernel or mesh");
  return s;
}

// Runs sweep(threads, region) -> the measure after the sweep, from measure `q0`, under the
// smoother's rules (SmoothOptions: at most max_iters sweeps, stop after one improving by less than
// tol; `done(q)` true stops too, converged). Fills sweeps, seconds and cpu_seconds.
template <class Sink, class Sweep, class Done>
void DriveSweeps(const SmoothOptions& opt, double q0, Sink& sink, SmoothResult* r,
                 const Sweep& sweep, const Done& done) {
  using Clock = std::chrono::steady_clock;
  if (opt.flush_bytes) FlushCaches(opt.flush_bytes);
  const int threads = opt.threads < 1 ? 1 : opt.threads;
  CpuTimeRegion cpu(opt.region, threads);
  SweepRegion* region = Sink::kEnabled ? opt.region : &cpu;
  double q = q0;
  for (int it = 1; it <= opt.max_iters; ++it) {
    if constexpr (Sink::kEnabled) sink.BeginSweep(it);
    const auto t0 = Clock::now();
    const double q_new = sweep(threads, region);
    const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
    SweepRecord rec{it, q_new, q_new - q, secs, Sink::kEnabled ? 0.0 : cpu.Take()};
    r->sweeps.push_back(rec);
    r->seconds += secs;
    r->cpu_seconds += rec.cpu_seconds;
    if (opt.on_sweep && *opt.on_sweep) (*opt.on_sweep)(rec);
    q = q_new;
    if (done(q) || rec.improvement < opt.tol) {
      r->converged = true;
      break;
    }
  }
}

// Per triangle its weight in the global quality and its quality, interleaved (wq[2t], wq[2t+1]),
// as the smoother keeps them; *q = the global quality they sum to.
inline AlignedVector<double> WeightsAndQualities(const Mesh& m, double* q) {
  AlignedVector<double> wq(2 * static_cast<size_t>(m.NumTriangles()));
  *q = 0.0;
  for (int32_t t = 0; t < m.NumTriangles(); ++t) {
    wq[2 * int64_t{t}] = GlobalQualityWeight(m, t);
    wq[2 * int64_t{t} + 1] = TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{t}]);
    *q += wq[2 * int64_t{t}] * wq[2 * int64_t{t} + 1];
  }
  return wq;
}

// Twice the signed area of (p, b, c): positive counter-clockwise.
inline double Area2(double px, double py, double bx, double by, double cx, double cy) {
  return (bx - px) * (cy - py) - (by - py) * (cx - px);
}

// A vertex's patch: per incident triangle its id and the other two corners, in the triangle's
// cyclic order after the vertex (so Area2(p, b, c) has the triangle's orientation). Gathered once
// per visit through the sink; the optimisation then works on this copy (a local, like the
// registers of the Laplacian's move: not mesh data, not traced), as Mesquite's PatchData does.
// A vertex with more than kMaxPatch triangles is left where it is (none of the shipped meshes has
// one).
inline constexpr int kMaxPatch = 64;
struct Patch {
  int n = 0;
  double px = 0, py = 0;
  int64_t t[kMaxPatch];
  int8_t at[kMaxPatch];  // the vertex's place among the triangle's stored corners
  double bx[kMaxPatch], by[kMaxPatch], cx[kMaxPatch], cy[kMaxPatch];
  // Twice triangle k's signed area with the vertex at (x, y), its corners in stored order: the
  // one expression CountInverted uses too, so a near-flat triangle is judged the same by both.
  double StoredArea2(int k, double x, double y) const {
    double c[6];
    const int j = at[k];
    c[2 * j] = x, c[2 * j + 1] = y;
    c[2 * ((j + 1) % 3)] = bx[k], c[2 * ((j + 1) % 3) + 1] = by[k];
    c[2 * ((j + 2) % 3)] = cx[k], c[2 * ((j + 2) % 3) + 1] = cy[k];
    return Area2(c[0], c[1], c[2], c[3], c[4], c[5]);
  }
};

// interior[k] is read by the caller; then: xy[2v..2v+1] 16 B (kCoordRead v), v2t.off[v] and
// v2t.off[v+1] 8 B each, and per triangle t in increasing id: v2t.idx[i] 4 B, tri[3t..3t+2] 4 B
// each, x then y of the two other corners in cyclic order 8 B each (kCoordRead on the x): 4 + 8
// tris(v) accesses. False (patch not gathered past its cap) when tris(v) > kMaxPatch.
template <class Sink>
inline bool GatherPatch(const smoother_detail::Arrays& a, int32_t v, int tid, Sink& sink,
                        Patch* p) {
  Report(sink, tid, a.xy + 2 * int64_t{v}, 16, Array::kCoords, false, AccessKind::kCoordRead, v);
  p->px = a.xy[2 * int64_t{v}];
  p->py = a.xy[2 * int64_t{v} + 1];
  const int64_t b = Load(sink, tid, Array::kTriOffsets, a.toff + v);
  const int64_t e = Load(sink, tid, Array::kTriOffsets, a.toff + v + 1);
  if (e - b > kMaxPatch) return false;
  p->n = static_cast<int>(e - b);
  for (int64_t i = b; i < e; ++i) {
    const int64_t t = Load(sink, tid, Array::kTriIndex, a.tris + i);
    const int32_t* c = a.tri + 3 * t;
    int32_t cc[3];
    for (int j = 0; j < 3; ++j) cc[j] = Load(sink, tid, Array::kTriangles, c + j);
    const int j = cc[0] == v ? 0 : cc[1] == v ? 1 : 2;
    const int32_t u = cc[(j + 1) % 3], w = cc[(j + 2) % 3];
    const int k = static_cast<int>(i - b);
    p->t[k] = t;
    p->at[k] = static_cast<int8_t>(j);
    const double* pu = a.xy + 2 * int64_t{u};
    const double* pw = a.xy + 2 * int64_t{w};
    Report(sink, tid, pu, 8, Array::kCoords, false, AccessKind::kCoordRead, u);
    Report(sink, tid, pu + 1, 8, Array::kCoords, false);
    Report(sink, tid, pw, 8, Array::kCoords, false, AccessKind::kCoordRead, w);
    Report(sink, tid, pw + 1, 8, Array::kCoords, false);
    p->bx[k] = pu[0], p->by[k] = pu[1], p->cx[k] = pw[0], p->cy[k] = pw[1];
  }
  return true;
}

// After a patch's vertex moved to (x, y): stores it (16 B, kCoordWrite v), then per triangle its
// new quality from the patch, reading its stored quality and weight (8 B each) and storing the new
// one: 1 + 3 tris(v) accesses. Returns the change of the global quality.
template <class Sink>
inline double StoreMove(const smoother_detail::Arrays& a, const Patch& p, int32_t v, double x,
                        double y, double* wq, int tid, Sink& sink) {
  Report(sink, tid, a.xy + 2 * int64_t{v}, 16, Array::kCoords, true, AccessKind::kCoordWrite, v);
  a.xy[2 * int64_t{v}] = x;
  a.xy[2 * int64_t{v} + 1] = y;
  double dq = 0.0;
  for (int k = 0; k < p.n; ++k)
    dq += smoother_detail::StoreQuality(
        wq, p.t[k], TriangleQuality(x, y, p.bx[k], p.by[k], p.cx[k], p.cy[k]), tid, sink);
  return dq;
}

// The smoothing kernels' arrays: the smoother's, with the weight/quality array.
template <class Sink>
void BindSmoothingArrays(Sink& sink, const Mesh& m, const AlignedVector<double>& wq) {
  BindArrays(sink, {Of(Array::kInterior, m.interior), Of(Array::kAdjOffsets, m.v2v.off),
                    Of(Array::kAdjIndex, m.v2v.idx), Of(Array::kTriOffsets, m.v2t.off),
                    Of(Array::kTriIndex, m.v2t.idx), Of(Array::kTriangles, m.tri),
                    Of(Array::kTriQuality, wq), Of(Array::kWeights, wq), Of(Array::kCoords, m.xy)});
}

// The smoothing kernels' sweeps (smart-laplacian, local-opt): the global quality kept as the
// smoother keeps it, each sweep `visit(arrays, interior item, wq, thread)` -> its change over the
// interior list split as schedule(static), the smoother's stop rule.
template <class Sink, class Visit>
SmoothResult RunSmoothingKernel(Mesh& m, const SmoothOptions& o, Sink& sink, const Visit& visit) {
  SmoothResult r;
  r.quality_before = o.end_qualities ? GlobalQuality(m) : NAN;
  double q = 0.0;
  AlignedVector<double> wq = WeightsAndQualities(m, &q);
  BindSmoothingArrays(sink, m, wq);
  const smoother_detail::Arrays a = smoother_detail::ArraysOf(m);
  DriveSweeps(
      o, q, sink, &r,
      [&](int threads, SweepRegion* region) {
        double* w = wq.data();
        q += smoother_detail::ForStatic<1>(
            m.interior.data(), static_cast<int64_t>(m.interior.size()), threads, sink, region,
            [a, w, &visit](const int32_t* item, int tid) { return visit(a, item, w, tid); });
        return q;
      },
      [](double) { return false; });
  r.quality_after = o.end_qualities ? GlobalQuality(m) : NAN;
  return r;
}

}  // namespace meshreuse::kernel_detail
