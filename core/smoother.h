// Laplacian smoothing, the paper's Algorithm 1 as implemented in Mesquite (DESIGN.md "Smoothing
// sweep"): each sweep visits the interior vertices in storage order and moves each to the plain
// average of its distinct neighbours. Gauss-Seidel (default) updates in place, so later vertices
// see earlier moves; with several threads the OpenMP static schedule splits the interior list into
// contiguous chunks and reads of a neighbour being moved by another thread race, as in the paper.
// Jacobi reads the previous sweep's positions from a second buffer, so its result depends on
// neither the ordering nor the thread count (beyond the rounding of each neighbour sum).
// The global quality is kept incrementally: Q = sum_t w_t q_t (quality.h), so moving v changes Q by
// sum over v's triangles of w_t (q_t' - q_t). Stop rule: a sweep that improves Q by less than `tol`
// is the last one, and there are at most `max_iters` sweeps.
// Tracing is the template parameter: Smooth<NullSink> is the timed, uninstrumented kernel.
//
// The access sequence of one Gauss-Seidel visit of interior vertex v (what a tracing sink sees):
//   1. kAdjacency  v          (&v2v.off[v]: v's adjacency row is read)
//   2. kCoordRead  u          for each neighbour u of v, in increasing id (&xy[2u])
//   3. kCoordWrite v          (&xy[2v]: v moves)
//   4. kCoordRead  a, b, c    for each triangle t of v, in increasing id, its corners in stored
//                             order (the triangle's quality is recomputed; v is one of them)
// so 2 + deg(v) + 3 * triangles(v) touches; AccessesPerSweep() sums them. Jacobi visits touch
// 1-3 (reading the old buffer, writing the new one); then its quality pass touches the three
// corners of every triangle in triangle order (kCoordRead), split among threads statically.
// Traced runs (Sink::kEnabled) execute serially and give thread t the iterations that the static
// schedule gives it, so each thread's stream is exact and in its own program order.
#pragma once

#include <omp.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh.h"
#include "core/quality.h"
#include "tracer/sink.h"

namespace meshreuse {

enum class UpdateMode { kGaussSeidel, kJacobi };
const char* UpdateModeName(UpdateMode m);
// Accepts "gs", "gauss-seidel", "jacobi"; throws std::invalid_argument otherwise.
UpdateMode ParseUpdateMode(const std::string& s);

struct SmoothOptions {
  int max_iters = 100;
  double tol = 5e-6;
  UpdateMode mode = UpdateMode::kGaussSeidel;
  int threads = 1;
};

struct SweepRecord {
  int sweep = 0;           // 1-based
  double quality = 0;      // global quality after the sweep (incremental value)
  double improvement = 0;  // quality - previous quality
  double seconds = 0;      // wall time of the sweep alone
};

struct SmoothResult {
  std::vector<SweepRecord> sweeps;
  double quality_before = 0;  // GlobalQuality() of the input, recomputed directly
  double quality_after = 0;   // GlobalQuality() of the output, recomputed directly
  double seconds = 0;         // sum of sweep times
  bool converged = false;     // false when max_iters stopped it
};

namespace smoother_detail {

struct Arrays {
  double* xy;
  const int64_t* off;
  const int32_t* nbr;
  const int64_t* toff;
  const int32_t* tris;
  const int32_t* tri;
};

inline Arrays ArraysOf(Mesh& m) {
  return {m.xy.data(),      m.v2v.off.data(), m.v2v.idx.data(),
          m.v2t.off.data(), m.v2t.idx.data(), m.tri.data()};
}

// Moves v to the average of its neighbours read from `src`, writing to `dst` (the same array for
// Gauss-Seidel). Returns nothing; the caller updates qualities.
template <class Sink>
inline void MoveToAverage(const Arrays& a, const double* src, double* dst, int32_t v, int tid,
                          Sink& sink) {
  if constexpr (Sink::kEnabled) sink.Touch(tid, AccessKind::kAdjacency, v, a.off + v);
  const int64_t b = a.off[v], e = a.off[v + 1];
  double sx = 0.0, sy = 0.0;
  for (int64_t i = b; i < e; ++i) {
    const int64_t u = a.nbr[i];
    if constexpr (Sink::kEnabled)
      sink.Touch(tid, AccessKind::kCoordRead, static_cast<int32_t>(u), src + 2 * u);
    sx += src[2 * u];
    sy += src[2 * u + 1];
  }
  const double inv = 1.0 / static_cast<double>(e - b);
  dst[2 * int64_t{v}] = sx * inv;
  dst[2 * int64_t{v} + 1] = sy * inv;
  if constexpr (Sink::kEnabled) sink.Touch(tid, AccessKind::kCoordWrite, v, dst + 2 * int64_t{v});
}

// The thread that OpenMP's schedule(static) without a chunk size gives iteration k of n to: P
// contiguous blocks, the first n % P of them one longer (libgomp's split).
inline int StaticOwner(int64_t k, int64_t n, int threads) {
  const int64_t q = n / threads, r = n % threads;
  return static_cast<int>(k < r * (q + 1) ? k / (q + 1) : r + (k - r * (q + 1)) / (q > 0 ? q : 1));
}

template <class Sink>
inline double VisitGaussSeidel(const Arrays& a, int32_t v, double* tq, const double* w, int tid,
                               Sink& sink) {
  MoveToAverage(a, a.xy, a.xy, v, tid, sink);
  double dq = 0.0;
  for (int64_t i = a.toff[v]; i < a.toff[v + 1]; ++i) {
    const int64_t t = a.tris[i];
    const int32_t* c = a.tri + 3 * t;
    if constexpr (Sink::kEnabled)
      for (int j = 0; j < 3; ++j)
        sink.Touch(tid, AccessKind::kCoordRead, c[j], a.xy + 2 * int64_t{c[j]});
    const double q = TriangleQuality(a.xy, c);
    dq += w[t] * (q - tq[t]);
    tq[t] = q;
  }
  return dq;
}

template <class Sink>
double GaussSeidelSweep(const Arrays& a, const std::vector<int32_t>& interior, double* tq,
                        const double* w, int threads, Sink& sink) {
  const int64_t ni = static_cast<int64_t>(interior.size());
  const int32_t* order = interior.data();
  double dq = 0.0;
  if constexpr (Sink::kEnabled) {  // serial replay of the static schedule, one stream per thread
    for (int64_t k = 0; k < ni; ++k)
      dq += VisitGaussSeidel(a, order[k], tq, w, StaticOwner(k, ni, threads), sink);
    return dq;
  }
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(+ : dq)
  {
    const int tid = omp_get_thread_num();
#pragma omp for schedule(static)
    for (int64_t k = 0; k < ni; ++k) dq += VisitGaussSeidel(a, order[k], tq, w, tid, sink);
  }
  return dq;
}

// Jacobi: new positions from the old buffer into `next`, swap, then all triangle qualities anew.
template <class Sink>
double JacobiSweep(Mesh& m, AlignedVector<double>& next, double* tq, const double* w, int threads,
                   Sink& sink) {
  const Arrays a = ArraysOf(m);
  const int64_t ni = static_cast<int64_t>(m.interior.size());
  const int32_t* order = m.interior.data();
  double* dst = next.data();
  const int64_t nt = m.NumTriangles();
  const int32_t* tri = m.tri.data();
  double q_new = 0.0;
  if constexpr (Sink::kEnabled) {  // serial replay of the static schedule, one stream per thread
    for (int64_t k = 0; k < ni; ++k)
      MoveToAverage(a, a.xy, dst, order[k], StaticOwner(k, ni, threads), sink);
    m.xy.swap(next);
    const double* xy = m.xy.data();
    for (int64_t t = 0; t < nt; ++t) {
      const int tid = StaticOwner(t, nt, threads);
      for (int j = 0; j < 3; ++j)
        sink.Touch(tid, AccessKind::kCoordRead, tri[3 * t + j], xy + 2 * int64_t{tri[3 * t + j]});
      tq[t] = TriangleQuality(xy, tri + 3 * t);
      q_new += w[t] * tq[t];
    }
    return q_new;
  }
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static)
  for (int64_t k = 0; k < ni; ++k)
    MoveToAverage(a, a.xy, dst, order[k], omp_get_thread_num(), sink);
  m.xy.swap(next);  // boundary entries are equal in both buffers, interior ones are now new
  const double* xy = m.xy.data();
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static) reduction(+ : q_new)
  for (int64_t t = 0; t < nt; ++t) {
    tq[t] = TriangleQuality(xy, tri + 3 * t);
    q_new += w[t] * tq[t];
  }
  return q_new;
}

}  // namespace smoother_detail

// Smooths `mesh` in place. `on_sweep` (optional) is called after each sweep, outside the timed
// region; the kernel itself prints nothing.
template <class Sink = NullSink>
SmoothResult Smooth(Mesh& mesh, const SmoothOptions& opt, Sink& sink,
                    const std::function<void(const SweepRecord&)>& on_sweep = {}) {
  using Clock = std::chrono::steady_clock;
  SmoothResult r;
  r.quality_before = GlobalQuality(mesh);
  std::vector<double> tq = TriangleQualities(mesh);
  const std::vector<double> w = GlobalQualityWeights(mesh);
  double q = 0.0;
  for (size_t t = 0; t < tq.size(); ++t) q += w[t] * tq[t];
  AlignedVector<double> next;
  if (opt.mode == UpdateMode::kJacobi) next = mesh.xy;
  const int threads = opt.threads < 1 ? 1 : opt.threads;

  for (int it = 1; it <= opt.max_iters; ++it) {
    if constexpr (Sink::kEnabled) sink.BeginSweep(it);
    const auto t0 = Clock::now();
    double q_new;
    if (opt.mode == UpdateMode::kGaussSeidel) {
      q_new = q + smoother_detail::GaussSeidelSweep(smoother_detail::ArraysOf(mesh), mesh.interior,
                                                    tq.data(), w.data(), threads, sink);
    } else {
      q_new = smoother_detail::JacobiSweep(mesh, next, tq.data(), w.data(), threads, sink);
    }
    const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
    SweepRecord rec{it, q_new, q_new - q, secs};
    r.sweeps.push_back(rec);
    r.seconds += secs;
    q = q_new;
    if (on_sweep) on_sweep(rec);
    if (rec.improvement < opt.tol) {
      r.converged = true;
      break;
    }
  }
  r.quality_after = GlobalQuality(mesh);
  return r;
}

// Touches per Gauss-Seidel sweep, per thread of the static schedule (see the sequence above):
// sum over the thread's interior vertices of 2 + deg(v) + 3 * triangles(v).
std::vector<uint64_t> AccessesPerSweep(const Mesh& m, int threads = 1);

// The timed, uninstrumented smoother.
inline SmoothResult Smooth(Mesh& mesh, const SmoothOptions& opt) {
  NullSink sink;
  return Smooth(mesh, opt, sink);
}

}  // namespace meshreuse
