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
// What a tracing sink sees (core/access.h): every load and store of mesh data the compiled sweep
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
//                                    (element kCoordRead c on the x of corner c); its quality
//                                    8 B, its weight 8 B, its quality 8 B store (weight and
//                                    quality of t are interleaved: wq[2t], wq[2t+1])
// so 6 + 2 deg(v) + 13 tris(v) accesses, 2 + deg(v) + 3 tris(v) of them element touches; before
// each visit, and once after a thread's last, the loop reads its end bound (8 B, kLoopBound: a
// local on the stack, see ForStatic) -- the one access that is not mesh data.
// This is what GCC 12 -O3 (x86-64) emits for the NullSink sweep: the coordinate pair of a
// neighbour is one vector load and the moved vertex one vector store; the array pointers live in
// registers (the sweep copies them to locals, and -fno-math-errno removes the call to sqrt that
// would otherwise force reloads). scripts/validate_callgrind.sh checks the count against
// callgrind's data references for the sweep function. RefsPerSweep() sums it.
// Jacobi: the same move (reading xy, storing 16 B into the next buffer, kCoordsNext), then a
// quality pass over the triangles in order: tri[3t..3t+2], the six coordinates (element touches as
// above), the weight 8 B, the quality 8 B store; split among threads statically.
// Traced runs (Sink::kEnabled) execute serially and give thread t the iterations that the static
// schedule gives it, so each thread's stream is exact and in its own program order.
#pragma once

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/access.h"
#include "core/mesh.h"
#include "core/quality.h"
#include "core/schedule.h"

namespace meshreuse {

enum class UpdateMode { kGaussSeidel, kJacobi };
const char* UpdateModeName(UpdateMode m);
// When the global quality is computed: after every move from the moved vertex's triangles (the
// paper's Algorithm 1, the default), or once per sweep by one pass over the triangles (as
// Mesquite's termination criterion does: the lean sweep, moves only, then Q = sum w_t q_t).
enum class QualityMode { kPerMove, kPerSweep };
const char* QualityModeName(QualityMode m);
QualityMode ParseQualityMode(const std::string& s);  // per-move | per-sweep
// Accepts "gs", "gauss-seidel", "jacobi"; throws UsageError otherwise.
UpdateMode ParseUpdateMode(const std::string& s);

struct SweepRecord;
struct KernelSetup;
struct SmoothOptions {
  int max_iters = 100;
  double tol = 5e-6;
  UpdateMode mode = UpdateMode::kGaussSeidel;
  QualityMode quality = QualityMode::kPerMove;  // Gauss-Seidel only (Jacobi is always per sweep)
  int threads = 1;
  SweepRegion* region = nullptr;  // optional, not owned
  // Before the first sweep (after the setup, outside the timed region) write and read this many
  // bytes of a scratch buffer: the caches then hold nothing of the mesh, like a simulator's empty
  // caches (scripts/validate_callgrind.sh). 0: no flush.
  uint64_t flush_bytes = 0;
  // Traced runs only (a tracing sink; untraced runs are real threads): how the threads' streams
  // are interleaved into the one the sink receives. Each thread's own stream is the same whatever
  // the interleaving (it depends on the mesh and the static schedule alone).
  //   0 (kSerialShares): thread 0's whole share of a sweep, then thread 1's, ... (as before);
  //   k > 0: k vertex visits of each thread in turn (1: a visit each; 64: blocks of 64);
  //   kAccessGrain (-1): a visit of each thread in turn, their accesses dealt one at a time.
  int interleave = 0;
  // Whether the caller reads the mesh's adjacency after the run. false (a timed runner that
  // throws the mesh away): a kernel that changes the triangles (edge-swap) leaves v2v, v2t,
  // boundary and interior as they were instead of rebuilding them from its new triangles (untimed
  // either way: on lake, 375k vertices, 0.05 s of a run's 0.23, its five sweeps 0.08).
  bool adjacency_after = true;
  // Whether the caller reads SmoothResult::quality_before and quality_after, a pass over the
  // mesh each (the global quality; edge-swap's share of Delaunay edges, untangle's after). false
  // (a timed runner after its first round, a traced run for its stream): they are NaN (untangle's
  // before, which its sweeps start from, is kept); the sweeps and their qualities are the same.
  bool end_qualities = true;
  // Optional, not owned: called after each sweep by the kernels of core/kernels/ (progress while
  // they run; Smooth itself takes its callback as an argument).
  const std::function<void(const SweepRecord&)>* on_sweep = nullptr;
  // Optional, not owned: the kernel's untimed set-up made beforehand from this same mesh
  // (PrepareKernel, core/kernels/kernel.h), for runs repeated on one layout; nullptr: the kernel
  // makes its own. The Laplacian and the kernels without one ignore it.
  const KernelSetup* setup = nullptr;
};
inline constexpr int kSerialShares = 0;
inline constexpr int kAccessGrain = -1;

// Exactly `sweeps` sweeps, whatever the quality does (no tolerance stop): what traces, analyses
// and simulations of k sweeps run.
inline SmoothOptions ExactSweeps(int sweeps, int threads = 1,
                                 UpdateMode mode = UpdateMode::kGaussSeidel) {
  SmoothOptions o;
  o.max_iters = sweeps;
  o.tol = -std::numeric_limits<double>::infinity();
  o.threads = threads;
  o.mode = mode;
  return o;
}

// Writes and reads `bytes` of a scratch buffer, one access per 64 bytes (see flush_bytes).
void FlushCaches(uint64_t bytes);

struct SweepRecord {
  int sweep = 0;           // 1-based
  double quality = 0;      // global quality after the sweep (incremental value)
  double improvement = 0;  // quality - previous quality
  double seconds = 0;      // wall time of the sweep alone
  double cpu_seconds = 0;  // thread CPU time of the sweep, summed over its threads (untraced)
};

// The calling thread's CPU time (CLOCK_THREAD_CPUTIME_ID): what a thread spent running, not
// waiting for a core another process holds.
double ThreadCpuSeconds();

// Thread CPU time of a sweep's parallel sections, per thread, summed: read at each thread's Enter
// and Exit, so the swept loop itself is untouched (two clock reads per thread per section). It
// forwards to an inner region (hardware counters) around its own reads.
class CpuTimeRegion : public SweepRegion {
 public:
  CpuTimeRegion(SweepRegion* inner, int threads) : inner_(inner), slots_(threads) {}
  void Enter(int t) override {
    if (inner_) inner_->Enter(t);
    slots_[t].start = ThreadCpuSeconds();
  }
  void Exit(int t) override {
    slots_[t].total += ThreadCpuSeconds() - slots_[t].start;
    if (inner_) inner_->Exit(t);
  }
  double Take() {  // the sum over threads since the last Take
    double s = 0;
    for (Slot& x : slots_) s += x.total, x.total = 0;
    return s;
  }

 private:
  struct alignas(64) Slot {  // a line each: threads never share one
    double start = 0, total = 0;
  };
  SweepRegion* inner_;
  std::vector<Slot> slots_;
};

struct SmoothResult {
  std::vector<SweepRecord> sweeps;
  double quality_before = 0;  // GlobalQuality() of the input, recomputed directly
  double quality_after = 0;   // GlobalQuality() of the output, recomputed directly
  double seconds = 0;         // sum of sweep times
  double cpu_seconds = 0;     // sum of the sweeps' thread CPU times
  bool converged = false;     // false when max_iters stopped it
};

namespace smoother_detail {

// Sum over triangles t in [b, e) of wq[2t] * quality(t): the lean sweep's quality pass, with
// `omp simd` lanes (built for AVX-512, AVX2 and baseline x86-64, chosen at run time), so its
// rounding depends on the lane count: reproducible on one machine, not bit-equal across CPUs.
double WeightedQualitySum(const double* xy, const int32_t* tri, const double* wq, int64_t b,
                          int64_t e);

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

// Sums body(p, thread) over p = items + k * stride for k in [0, n), split as schedule(static) among
// `threads` threads: in parallel for NullSink (each thread calls region->Enter/Exit around its
// share), serially for a tracing sink (thread 0's share, then thread 1's, ...: each stream exact,
// in its own order). The loop's end pointer is a volatile local, read from memory at each test of
// the loop condition: the Gauss-Seidel visit needs every register, and GCC 12 keeps the bound on
// the stack anyway; making it explicit gives every compiler the same loads, which the trace
// reports (array kLoopBound), so the address stream is exact by construction: one bound read per
// iteration plus one per thread's share. (A cursor pointer, not an index: an index would need the
// base pointer in one more register. A body that takes the index, Visit below, gets an index loop
// whose bound is the same 8-byte volatile: the pointer would be a second induction variable.)
// A tracing sink's interleaving (SmoothOptions::interleave): its `interleave` member when it has
// one, else thread shares in turn. With kAccessGrain it must also have EndTurn(), which deals the
// turn's buffered accesses out one at a time.
template <class S>
auto InterleaveOf(const S& s, int) -> decltype(static_cast<int>(s.interleave)) {
  return s.interleave;
}
template <class S>
int InterleaveOf(const S&, long) {
  return kSerialShares;
}
template <class S>
auto EndTurnOf(S& s, int) -> decltype(s.EndTurn()) {
  return s.EndTurn();
}
template <class S>
void EndTurnOf(S&, long) {}

// A tracing sink that records from real threads (kParallelTrace, thread-safe per thread): the
// traced loop then runs in the OpenMP region like the untraced one (the tests compare its
// per-thread streams with the serial traced run's).
template <class S, class = void>
struct ParallelTraced : std::false_type {};
template <class S>
struct ParallelTraced<S, std::void_t<decltype(S::kParallelTrace)>>
    : std::bool_constant<S::kParallelTrace> {};

// A visit body takes (item, thread) and returns the visit's share of the sweep's sum, or takes
// (item, index, thread): the index lets a visit address a parallel array by the loop's own
// induction variable, not recover it from the item's pointer, and such a body may return nothing
// (a serial kernel that keeps its own count) so that no sum lives in the loop. Together 9% of
// edge-swap's sweep (343.7 M to 313.1 M instructions on a 30k lake, by callgrind).
template <class T, class Body>
inline void Visit(double& sum, const Body& body, T* p, int64_t i, int tid) {
  if constexpr (!std::is_invocable_v<const Body&, T*, int64_t, int>)
    sum += body(p, tid);
  else if constexpr (std::is_void_v<std::invoke_result_t<const Body&, T*, int64_t, int>>)
    body(p, i, tid);
  else
    sum += body(p, i, tid);
}

template <int64_t stride, class Sink, class T, class Body>
inline double ForStatic(T* items, int64_t n, int threads, Sink& sink, SweepRegion* region,
                        const Body& body) {
  double sum = 0.0;
  if constexpr (ParallelTraced<Sink>::value) {
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(+ : sum)
    {
      const int tid = omp_get_thread_num();
      int64_t b, e;
      StaticRange(n, omp_get_num_threads(), tid, &b, &e);
      T* volatile end = items + e * stride;
      int64_t i = b;
      for (T* p = items + b * stride;; p += stride, ++i) {
        Report(sink, tid, const_cast<T* const*>(&end), sizeof(T*), Array::kLoopBound, false);
        if (!(p < end)) break;
        Visit(sum, body, p, i, tid);
      }
    }
    return sum;
  } else if constexpr (Sink::kEnabled) {
    if (const int grain = InterleaveOf(sink, 0); grain != kSerialShares && threads > 1) {
      // The same per-thread streams as below, their visits taken `grain` at a time from each
      // thread in turn (one per turn for kAccessGrain, the sink dealing their accesses).
      const int per_turn = grain > 0 ? grain : 1;
      std::vector<T*> cursor(threads);
      std::vector<T*> end(threads);
      std::vector<uint8_t> done(threads, 0);
      for (int t = 0; t < threads; ++t) {
        int64_t b, e;
        StaticRange(n, threads, t, &b, &e);
        cursor[t] = items + b * stride;
        end[t] = items + e * stride;
      }
      for (int left = threads; left > 0;) {
        for (int t = 0; t < threads; ++t) {
          for (int k = 0; k < per_turn && !done[t]; ++k) {
            Report(sink, t, const_cast<T* const*>(&end[t]), sizeof(T*), Array::kLoopBound, false);
            if (!(cursor[t] < end[t])) {
              done[t] = 1;
              --left;
              break;
            }
            Visit(sum, body, cursor[t], (cursor[t] - items) / stride, t);
            cursor[t] += stride;
          }
        }
        EndTurnOf(sink, 0);
      }
      return sum;
    }
    for (int t = 0; t < threads; ++t) {
      int64_t b, e;
      StaticRange(n, threads, t, &b, &e);
      T* volatile end = items + e * stride;
      int64_t i = b;
      for (T* p = items + b * stride;; p += stride, ++i) {
        Report(sink, t, const_cast<T* const*>(&end), sizeof(T*), Array::kLoopBound, false);
        if (!(p < end)) break;
        Visit(sum, body, p, i, t);
      }
    }
    return sum;
  }
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(+ : sum)
  {
    const Body local = body;  // private: its captured pointers stay in registers
    const int tid = omp_get_thread_num();
    int64_t b, e;
    StaticRange(n, omp_get_num_threads(), tid, &b, &e);
    if (region) region->Enter(tid);
    if constexpr (std::is_invocable_v<const Body&, T*, int64_t, int>) {
      volatile int64_t end = e;  // one induction variable, the index the body asks for
      for (int64_t i = b; i < end; ++i) Visit(sum, local, items + i * stride, i, tid);
    } else {
      T* volatile end = items + e * stride;
      for (T* p = items + b * stride; p < end; p += stride) sum += local(p, tid);
    }
    if (region) region->Exit(tid);
  }
  return sum;
}

// Triangle t's stored quality replaced by q: its old quality and weight read, q stored; returns
// the change of the global quality (w_t (q - old)).
template <class Sink>
inline double StoreQuality(double* wq, int64_t t, double q, int tid, Sink& sink) {
  const double old = Load(sink, tid, Array::kTriQuality, wq + 2 * t + 1);
  const double wt = Load(sink, tid, Array::kWeights, wq + 2 * t);
  Report(sink, tid, wq + 2 * t + 1, 8, Array::kTriQuality, true);
  wq[2 * t + 1] = q;
  return wt * (q - old);
}

// The qualities of the triangles v2t.idx[b..e) anew from the coordinates, stored: the change of
// the global quality.
template <class Sink>
inline double RequalifyTriangles(const Arrays& a, int64_t b, int64_t e, double* wq, int tid,
                                 Sink& sink) {
  double dq = 0.0;
  for (int64_t i = b; i < e; ++i) {
    const int64_t t = Load(sink, tid, Array::kTriIndex, a.tris + i);
    const double q = TracedTriangleQuality(a.xy, a.tri, t, tid, sink);
    dq += StoreQuality(wq, t, q, tid, sink);
  }
  return dq;
}

template <class Sink>
inline double VisitGaussSeidel(const Arrays& a, const int32_t* item, double* wq, int tid,
                               Sink& sink) {
  const int32_t v = Load(sink, tid, Array::kInterior, item);
  MoveToAverage(a, a.xy, a.xy, Array::kCoords, v, tid, sink);
  const int64_t b = Load(sink, tid, Array::kTriOffsets, a.toff + v);
  const int64_t e = Load(sink, tid, Array::kTriOffsets, a.toff + v + 1);
  return RequalifyTriangles(a, b, e, wq, tid, sink);
}

template <class Sink>
double GaussSeidelSweep(const Arrays& a, const AlignedVector<int32_t>& interior, double* wq,
                        int threads, Sink& sink, SweepRegion* region) {
  return ForStatic<1>(interior.data(), static_cast<int64_t>(interior.size()), threads, sink, region,
                      [a, wq, &sink](const int32_t* item, int tid) {
                        return VisitGaussSeidel(a, item, wq, tid, sink);
                      });
}

// Q = sum over triangles of w_t q_t, in one pass (the lean sweep's quality; the per-triangle
// qualities are not stored).
template <class Sink>
double QualityPass(const Mesh& m, const double* wq, int threads, Sink& sink, SweepRegion* region) {
  const double* xy = m.xy.data();
  const int32_t* tri = m.tri.data();
  if constexpr (!Sink::kEnabled) {
    // Untraced: a vectorised loop (WeightedQualitySum), each thread its static share.
    const int64_t nt = m.NumTriangles();
    double sum = 0.0;
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(+ : sum)
    {
      const int tid = omp_get_thread_num();
      int64_t b, e;
      StaticRange(nt, omp_get_num_threads(), tid, &b, &e);
      if (region) region->Enter(tid);
      sum += WeightedQualitySum(xy, tri, wq, b, e);
      if (region) region->Exit(tid);
    }
    return sum;
  }
  return ForStatic<3>(tri, m.NumTriangles(), threads, sink, region,
                      [xy, tri, wq, &sink](const int32_t* c, int tid) {
                        const int64_t t = (c - tri) / 3;
                        const double q = TracedTriangleQuality(xy, tri, t, tid, sink);
                        return Load(sink, tid, Array::kWeights, wq + 2 * t) * q;
                      });
}

// The lean Gauss-Seidel sweep: moves only, in place; then QualityPass.
template <class Sink>
double LeanGaussSeidelSweep(Mesh& m, const double* wq, int threads, Sink& sink,
                            SweepRegion* region) {
  const Arrays a = ArraysOf(m);
  ForStatic<1>(m.interior.data(), static_cast<int64_t>(m.interior.size()), threads, sink, region,
               [a, &sink](const int32_t* item, int tid) {
                 const int32_t v = Load(sink, tid, Array::kInterior, item);
                 MoveToAverage(a, a.xy, a.xy, Array::kCoords, v, tid, sink);
                 return 0.0;
               });
  return QualityPass(m, wq, threads, sink, region);
}

// Jacobi: new positions from the old buffer into `next`, swap, then all triangle qualities anew.
template <class Sink>
double JacobiSweep(Mesh& m, AlignedVector<double>& next, double* wq, int threads, Sink& sink,
                   SweepRegion* region) {
  const Arrays a = ArraysOf(m);
  double* dst = next.data();
  ForStatic<1>(m.interior.data(), static_cast<int64_t>(m.interior.size()), threads, sink, region,
               [a, dst, &sink](const int32_t* item, int tid) {
                 const int32_t v = Load(sink, tid, Array::kInterior, item);
                 MoveToAverage(a, a.xy, dst, Array::kCoordsNext, v, tid, sink);
                 return 0.0;
               });
  m.xy.swap(next);  // boundary entries are equal in both buffers, interior ones are now new
  const double* xy = m.xy.data();
  const int32_t* tri = m.tri.data();
  return ForStatic<3>(tri, m.NumTriangles(), threads, sink, region,
                      [xy, tri, wq, &sink](const int32_t* c, int tid) {
                        const int64_t t = (c - tri) / 3;
                        const double q = TracedTriangleQuality(xy, tri, t, tid, sink);
                        const double wt = Load(sink, tid, Array::kWeights, wq + 2 * t);
                        Report(sink, tid, wq + 2 * t + 1, 8, Array::kTriQuality, true);
                        wq[2 * t + 1] = q;
                        return wt * q;
                      });
}

}  // namespace smoother_detail

// Smooths `mesh` in place. `on_sweep` (optional) is called after each sweep, outside the timed
// region; the kernel itself prints nothing.
template <class Sink = NullSink>
SmoothResult Smooth(Mesh& mesh, const SmoothOptions& opt, Sink& sink,
                    const std::function<void(const SweepRecord&)>& on_sweep = {}) {
  using Clock = std::chrono::steady_clock;
  SmoothResult r;
  r.quality_before = opt.end_qualities ? GlobalQuality(mesh) : NAN;
  // Per triangle its weight and its quality side by side (wq[2t], wq[2t+1]): one line holds both,
  // and the sweep needs one pointer less (without it GCC spills two to the stack). Aligned like the
  // mesh's arrays, so line-level results do not depend on malloc.
  AlignedVector<double> wq;
  double q = 0.0;
  {
    const int32_t nt = mesh.NumTriangles();
    wq.resize(2 * static_cast<size_t>(nt));
    for (int32_t t = 0; t < nt; ++t) {
      wq[2 * int64_t{t}] = GlobalQualityWeight(mesh, t);
      wq[2 * int64_t{t} + 1] = TriangleQuality(mesh.xy.data(), &mesh.tri[3 * int64_t{t}]);
      q += wq[2 * int64_t{t}] * wq[2 * int64_t{t} + 1];
    }
  }
  AlignedVector<double> next;
  if (opt.mode == UpdateMode::kJacobi) next = mesh.xy;
  const int threads = opt.threads < 1 ? 1 : opt.threads;

  if constexpr (Sink::kEnabled) {
    ArrayLayout l;
    auto put = [&](Array a, const auto& v) {
      l.base[static_cast<int>(a)] = reinterpret_cast<uintptr_t>(v.data());
      l.bytes[static_cast<int>(a)] = v.size() * sizeof(v[0]);
    };
    put(Array::kInterior, mesh.interior);
    put(Array::kAdjOffsets, mesh.v2v.off);
    put(Array::kAdjIndex, mesh.v2v.idx);
    put(Array::kTriOffsets, mesh.v2t.off);
    put(Array::kTriIndex, mesh.v2t.idx);
    put(Array::kTriangles, mesh.tri);
    put(Array::kTriQuality, wq);  // weights and qualities share one array (interleaved)
    put(Array::kWeights, wq);
    put(Array::kCoords, mesh.xy);
    put(Array::kCoordsNext, next);
    sink.Bind(l);
  }
  if (opt.flush_bytes) FlushCaches(opt.flush_bytes);
  // Untimed runs read each thread's CPU time around its share; traced runs are serial and slow,
  // their CPU time means nothing.
  CpuTimeRegion cpu(opt.region, threads);
  SweepRegion* region = Sink::kEnabled ? opt.region : &cpu;
  for (int it = 1; it <= opt.max_iters; ++it) {
    if constexpr (Sink::kEnabled) sink.BeginSweep(it);
    const auto t0 = Clock::now();
    double q_new;
    if (opt.mode == UpdateMode::kGaussSeidel && opt.quality == QualityMode::kPerSweep) {
      q_new = smoother_detail::LeanGaussSeidelSweep(mesh, wq.data(), threads, sink, region);
    } else if (opt.mode == UpdateMode::kGaussSeidel) {
      q_new = q + smoother_detail::GaussSeidelSweep(smoother_detail::ArraysOf(mesh), mesh.interior,
                                                    wq.data(), threads, sink, region);
    } else {
      q_new = smoother_detail::JacobiSweep(mesh, next, wq.data(), threads, sink, region);
    }
    const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
    SweepRecord rec{it, q_new, q_new - q, secs, Sink::kEnabled ? 0.0 : cpu.Take()};
    r.sweeps.push_back(rec);
    r.seconds += secs;
    r.cpu_seconds += rec.cpu_seconds;
    q = q_new;
    if (on_sweep) on_sweep(rec);
    if (rec.improvement < opt.tol) {
      r.converged = true;
      break;
    }
  }
  r.quality_after = opt.end_qualities ? GlobalQuality(mesh) : NAN;
  return r;
}

// Element touches per sweep, per thread of the static schedule (see the sequence above):
// Gauss-Seidel, sum over the thread's interior vertices of 2 + deg(v) + 3 * triangles(v); Jacobi,
// 2 + deg(v) per interior vertex and 3 per triangle of the thread's share of the quality pass.
std::vector<uint64_t> AccessesPerSweep(const Mesh& m, int threads = 1,
                                       UpdateMode mode = UpdateMode::kGaussSeidel);
// Loads and stores (the address stream) per sweep, per thread: Gauss-Seidel 7 + 2 deg(v) +
// 13 triangles(v) per interior vertex (the 7th: the loop bound) plus 1; Jacobi 5 + 2 deg(v) per
// interior vertex plus 12 per triangle of the thread's share of the quality pass, plus 2.
std::vector<uint64_t> RefsPerSweep(const Mesh& m, int threads = 1,
                                   UpdateMode mode = UpdateMode::kGaussSeidel);

// The timed, uninstrumented smoother.
inline SmoothResult Smooth(Mesh& mesh, const SmoothOptions& opt) {
  NullSink sink;
  return Smooth(mesh, opt, sink);
}

}  // namespace meshreuse
