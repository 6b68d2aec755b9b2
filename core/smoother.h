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
// What a tracing sink sees (tracer/sink.h): every load and store of mesh data the compiled sweep
// makes, in program order, with its array and size; the element touches (the paper's model) ride
// on the accesses that read or write a vertex record. One Gauss-Seidel visit of interior vertex v
// (the k-th entry of `interior`), with deg(v) neighbours and tris(v) triangles:
//   interior[k]                      4 B                 (v)
//   v2v.off[v], v2v.off[v+1]         8 B each            element kAdjacency v on the first
//   per neighbour u, increasing id:  v2v.idx[i] 4 B, then xy[2u..2u+1] as one 16 B load
//                                                        element kCoordRead u
//   xy[2v..2v+1]                     16 B store          element kCoordWrite v
//   v2t.off[v], v2t.off[v+1]         8 B each
//   per triangle t, increasing id:   v2t.idx[i] 4 B; tri[3t], tri[3t+1], tri[3t+2] 4 B each;
//                                    x then y of each corner in stored order, 8 B each
//                                    (element kCoordRead c on the x of corner c); tq[t] 8 B;
//                                    w[t] 8 B; tq[t] 8 B store
// so 6 + 2 deg(v) + 13 tris(v) accesses, 2 + deg(v) + 3 tris(v) of them element touches.
// This is what GCC 12 -O3 (x86-64) emits for the NullSink sweep: the coordinate pair of a
// neighbour is one vector load and the moved vertex one vector store; the array pointers live in
// registers (the sweep copies them to locals, and -fno-math-errno removes the call to sqrt that
// would otherwise force reloads). scripts/validate_callgrind.sh checks the count against
// callgrind's data references for the sweep function. RefsPerSweep() sums it.
// Jacobi: the same move (reading xy, storing 16 B into the next buffer, kCoordsNext), then a
// quality pass over the triangles in order: tri[3t..3t+2], the six coordinates (element touches as
// above), w[t] 8 B, tq[t] 8 B store; split among threads statically.
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

// Each thread of a sweep's parallel region calls Enter(thread) before its share of the sweep and
// Exit(thread) after it: where hardware counters are read (analysis/papi_counters.h). Untraced
// runs only; the cost is two virtual calls per thread per sweep.
struct SweepRegion {
  virtual ~SweepRegion() = default;
  virtual void Enter(int thread) = 0;
  virtual void Exit(int thread) = 0;
};

struct SmoothOptions {
  int max_iters = 100;
  double tol = 5e-6;
  UpdateMode mode = UpdateMode::kGaussSeidel;
  int threads = 1;
  SweepRegion* region = nullptr;  // optional, not owned
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

// Reports one access (compiled away for NullSink) and performs it.
template <class Sink>
inline void Report(Sink& sink, int tid, const void* p, uint32_t size, Array array, bool write,
                   AccessKind kind = AccessKind::kNone, int32_t vertex = -1) {
  if constexpr (Sink::kEnabled) sink.Access(tid, MemRef{p, size, array, write, kind, vertex});
}
template <class Sink, class T>
inline T Load(Sink& sink, int tid, Array array, const T* p, AccessKind kind = AccessKind::kNone,
              int32_t vertex = -1) {
  Report(sink, tid, p, sizeof(T), array, false, kind, vertex);
  return *p;
}

// Moves v to the average of its neighbours read from `src`, writing to `dst` (the same array for
// Gauss-Seidel, `dst_array` says which it is).
template <class Sink>
inline void MoveToAverage(const Arrays& a, const double* src, double* dst, Array dst_array,
                          int32_t v, int tid, Sink& sink) {
  const int64_t b = Load(sink, tid, Array::kAdjOffsets, a.off + v, AccessKind::kAdjacency, v);
  const int64_t e = Load(sink, tid, Array::kAdjOffsets, a.off + v + 1);
  double sx = 0.0, sy = 0.0;
  for (int64_t i = b; i < e; ++i) {
    const int64_t u = Load(sink, tid, Array::kAdjIndex, a.nbr + i);
    Report(sink, tid, src + 2 * u, 16, Array::kCoords, false, AccessKind::kCoordRead,
           static_cast<int32_t>(u));
    sx += src[2 * u];
    sy += src[2 * u + 1];
  }
  const double inv = 1.0 / static_cast<double>(e - b);
  Report(sink, tid, dst + 2 * int64_t{v}, 16, dst_array, true, AccessKind::kCoordWrite, v);
  dst[2 * int64_t{v}] = sx * inv;
  dst[2 * int64_t{v} + 1] = sy * inv;
}

// The quality of triangle t read through the sink: its corners, then x and y of each.
template <class Sink>
inline double TracedTriangleQuality(const double* xy, const int32_t* tri, int64_t t, int tid,
                                    Sink& sink) {
  const int32_t* c = tri + 3 * t;
  if constexpr (Sink::kEnabled) {
    for (int j = 0; j < 3; ++j) Report(sink, tid, c + j, 4, Array::kTriangles, false);
    for (int j = 0; j < 3; ++j) {
      const double* p = xy + 2 * int64_t{c[j]};
      Report(sink, tid, p, 8, Array::kCoords, false, AccessKind::kCoordRead, c[j]);
      Report(sink, tid, p + 1, 8, Array::kCoords, false);
    }
  }
  return TriangleQuality(xy, c);
}

// The thread that OpenMP's schedule(static) without a chunk size gives iteration k of n to: P
// contiguous blocks, the first n % P of them one longer (libgomp's split).
inline int StaticOwner(int64_t k, int64_t n, int threads) {
  const int64_t q = n / threads, r = n % threads;
  return static_cast<int>(k < r * (q + 1) ? k / (q + 1) : r + (k - r * (q + 1)) / (q > 0 ? q : 1));
}

template <class Sink>
inline double VisitGaussSeidel(const Arrays& a, const int32_t* order, int64_t k, double* tq,
                               const double* w, int tid, Sink& sink) {
  const int32_t v = Load(sink, tid, Array::kInterior, order + k);
  MoveToAverage(a, a.xy, a.xy, Array::kCoords, v, tid, sink);
  double dq = 0.0;
  const int64_t b = Load(sink, tid, Array::kTriOffsets, a.toff + v);
  const int64_t e = Load(sink, tid, Array::kTriOffsets, a.toff + v + 1);
  for (int64_t i = b; i < e; ++i) {
    const int64_t t = Load(sink, tid, Array::kTriIndex, a.tris + i);
    const double q = TracedTriangleQuality(a.xy, a.tri, t, tid, sink);
    const double old = Load(sink, tid, Array::kTriQuality, tq + t);
    const double wt = Load(sink, tid, Array::kWeights, w + t);
    dq += wt * (q - old);
    Report(sink, tid, tq + t, 8, Array::kTriQuality, true);
    tq[t] = q;
  }
  return dq;
}

template <class Sink>
double GaussSeidelSweep(const Arrays& arrays, const AlignedVector<int32_t>& interior, double* tq,
                        const double* w, int threads, Sink& sink, SweepRegion* region) {
  const int64_t ni = static_cast<int64_t>(interior.size());
  const int32_t* order = interior.data();
  double dq = 0.0;
  if constexpr (Sink::kEnabled) {  // serial replay of the static schedule, one stream per thread
    for (int64_t k = 0; k < ni; ++k)
      dq += VisitGaussSeidel(arrays, order, k, tq, w, StaticOwner(k, ni, threads), sink);
    return dq;
  }
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(+ : dq)
  {
    const Arrays a = arrays;  // a private copy keeps the pointers in registers
    const int tid = omp_get_thread_num();
    if (region) region->Enter(tid);
#pragma omp for schedule(static)
    for (int64_t k = 0; k < ni; ++k) dq += VisitGaussSeidel(a, order, k, tq, w, tid, sink);
    if (region) region->Exit(tid);
  }
  return dq;
}

// Jacobi: new positions from the old buffer into `next`, swap, then all triangle qualities anew.
template <class Sink>
double JacobiSweep(Mesh& m, AlignedVector<double>& next, double* tq, const double* w, int threads,
                   Sink& sink, SweepRegion* region) {
  const Arrays arrays = ArraysOf(m);
  const int64_t ni = static_cast<int64_t>(m.interior.size());
  const int32_t* order = m.interior.data();
  double* dst = next.data();
  const int64_t nt = m.NumTriangles();
  const int32_t* tri = m.tri.data();
  double q_new = 0.0;
  if constexpr (Sink::kEnabled) {  // serial replay of the static schedule, one stream per thread
    for (int64_t k = 0; k < ni; ++k) {
      const int tid = StaticOwner(k, ni, threads);
      const int32_t v = Load(sink, tid, Array::kInterior, order + k);
      MoveToAverage(arrays, arrays.xy, dst, Array::kCoordsNext, v, tid, sink);
    }
    m.xy.swap(next);
    const double* xy = m.xy.data();
    for (int64_t t = 0; t < nt; ++t) {
      const int tid = StaticOwner(t, nt, threads);
      const double q = TracedTriangleQuality(xy, tri, t, tid, sink);
      const double wt = Load(sink, tid, Array::kWeights, w + t);
      Report(sink, tid, tq + t, 8, Array::kTriQuality, true);
      tq[t] = q;
      q_new += wt * q;
    }
    return q_new;
  }
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    const Arrays a = arrays;
    const int tid = omp_get_thread_num();
    if (region) region->Enter(tid);
#pragma omp for schedule(static)
    for (int64_t k = 0; k < ni; ++k) MoveToAverage(a, a.xy, dst, Array::kCoordsNext, order[k], tid, sink);
    if (region) region->Exit(tid);
  }
  m.xy.swap(next);  // boundary entries are equal in both buffers, interior ones are now new
  const double* xy = m.xy.data();
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(+ : q_new)
  {
    const int tid = omp_get_thread_num();
    if (region) region->Enter(tid);
#pragma omp for schedule(static)
    for (int64_t t = 0; t < nt; ++t) {
      tq[t] = TriangleQuality(xy, tri + 3 * t);
      q_new += w[t] * tq[t];
    }
    if (region) region->Exit(tid);
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
  // Aligned like the mesh's arrays, so line-level results do not depend on malloc.
  AlignedVector<double> tq, w;
  {
    const std::vector<double> q0 = TriangleQualities(mesh), w0 = GlobalQualityWeights(mesh);
    tq.assign(q0.begin(), q0.end());
    w.assign(w0.begin(), w0.end());
  }
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
                                                    tq.data(), w.data(), threads, sink,
                                                    opt.region);
    } else {
      q_new =
          smoother_detail::JacobiSweep(mesh, next, tq.data(), w.data(), threads, sink, opt.region);
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

// Element touches per Gauss-Seidel sweep, per thread of the static schedule (see the sequence
// above): sum over the thread's interior vertices of 2 + deg(v) + 3 * triangles(v).
std::vector<uint64_t> AccessesPerSweep(const Mesh& m, int threads = 1);
// Loads and stores (the address stream) per sweep, per thread: Gauss-Seidel 6 + 2 deg(v) +
// 13 triangles(v) per interior vertex; Jacobi 4 + 2 deg(v) per interior vertex plus 11 per
// triangle of the thread's share of the quality pass.
std::vector<uint64_t> RefsPerSweep(const Mesh& m, int threads = 1,
                                   UpdateMode mode = UpdateMode::kGaussSeidel);

// The timed, uninstrumented smoother.
inline SmoothResult Smooth(Mesh& mesh, const SmoothOptions& opt) {
  NullSink sink;
  return Smooth(mesh, opt, sink);
}

}  // namespace meshreuse
