// edge-swap: quality-driven edge flips, the paper's "mesh swapping" (Lawson 1977: flipping every
// edge that is not locally Delaunay ends at the Delaunay triangulation, which maximises the least
// angle; Freitag and Ollivier-Gooch 1997 for swapping in mesh improvement). The kernel first
// perturbs its input (JitterMesh, below: outside the timed and traced sweeps; or takes the jittered
// coordinates and the triangles' neighbours from a shared set-up, KernelSetup), then each sweep
// visits the triangles in storage order (the order of the triangles follows the vertex ordering,
// --triangle-order), and each edge of triangle t, in corner-slot order, whose other triangle u has
// a higher id (each edge once, from its lower-numbered triangle): when the corner of u opposite the
// edge lies strictly inside t's circumcircle (the incircle determinant, signed by t's orientation,
// above 1e-12 of its magnitude: a near-cocircular quad is left, so round-off cannot flip an edge
// back and forth), the edge is flipped in place: t and u keep their slots, their corners and the
// triangles across their four outer edges are rewritten. The topology changes as it goes; the
// sweeps stop after one that flips nothing (every edge locally Delaunay), at most max_iters (tol
// does not apply). The measure: 1 - flips / interior edges in the sweep (1: none flipped). The
// mesh's vertex adjacency is rebuilt after the last sweep (untimed; not when the caller says it
// reads none, SmoothOptions::adjacency_after). Serial: two flips sharing a triangle would race
// (--threads 1 only).
// Access sequence of a visit of triangle t (besides the loop bound, smoother.h ForStatic):
// tri[3t..3t+2] 4 B each, x then y of each corner 8 B each (kCoordRead on the x); then per slot j:
// t2t[3t+j] 4 B; when u = t2t[3t+j] > t: tri[3u..3u+2] 4 B each and x then y of u's corner
// opposite the edge (kCoordRead on the x); when flipped: stores tri[3t..3t+2], tri[3u..3u+2],
// t2t[3t..3t+2], t2t[3u..3u+2] (4 B each), and for each of the two outer triangles whose
// neighbour changes, its t2t entries read up to the one that pointed back (4 B each) and that one
// stored. Its length depends on the flips (KernelInfo::refs is empty).
#include "core/kernels/edge_swap.h"

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "core/kernels/common.h"
#include "core/mix.h"

namespace meshreuse {

namespace {

using kernel_detail::Area2;
using kernel_detail::Load;
using kernel_detail::Report;

// Whether d lies strictly inside the circumcircle of (a, b, c), whatever its orientation, beyond
// round-off (1e-12 of the determinant's magnitude). Always inlined: GCC 12 left it a call from
// the sweep's OpenMP region (spilling the visit's registers around each of 2.4 M calls on a 30k
// lake, 3.6% of the sweep's instructions), where the hand-written sweep inlines it.
[[gnu::always_inline]] inline bool InCircle(const double* a, const double* b, const double* c,
                                            const double* d) {
  const double ax = a[0] - d[0], ay = a[1] - d[1], bx = b[0] - d[0], by = b[1] - d[1];
  const double cx = c[0] - d[0], cy = c[1] - d[1];
  const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double det = ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx);
  const double mag = std::fabs(ax) * (std::fabs(by * c2) + std::fabs(b2 * cy)) +
                     std::fabs(ay) * (std::fabs(bx * c2) + std::fabs(b2 * cx)) +
                     a2 * (std::fabs(bx * cy) + std::fabs(by * cx));
  const double orient = Area2(a[0], a[1], b[0], b[1], c[0], c[1]) >= 0.0 ? 1.0 : -1.0;
  return orient * det > 1e-12 * mag;
}

// Per triangle the triangle across the edge opposite each corner (-1 on the boundary). The
// set-up of a run, like JitterMesh and NotDelaunayEdges below, is untimed and runs on every core
// (each triangle's or vertex's result its own: the same values on any number of threads): on
// lake (375k vertices, 2 cores) a run then took 0.26 s instead of 0.43, its 5 sweeps 0.09 s.
AlignedVector<int32_t> TriangleNeighbours(const Mesh& m) {
  AlignedVector<int32_t> n(m.tri.size(), -1);
#pragma omp parallel for schedule(static, 8192)
  for (int32_t t = 0; t < m.NumTriangles(); ++t)
    for (int j = 0; j < 3; ++j) {
      const int32_t q = m.tri[3 * int64_t{t} + (j + 1) % 3],
                    r = m.tri[3 * int64_t{t} + (j + 2) % 3];
      for (const int32_t* u = m.v2t.RowBegin(q); u != m.v2t.RowEnd(q); ++u) {
        if (*u == t) continue;
        const int32_t* c = &m.tri[3 * int64_t{*u}];
        if (c[0] == r || c[1] == r || c[2] == r) n[3 * int64_t{t} + j] = *u;
      }
    }
  return n;
}

// In triangle x's neighbour slots, the one that holds `from`, now `to` (read until found).
template <class Sink>
void Repoint(int32_t* nbr, int32_t x, int32_t from, int32_t to, Sink& sink) {
  if (x < 0) return;
  for (int k = 0; k < 3; ++k)
    if (Load(sink, 0, Array::kTriNeighbours, nbr + 3 * int64_t{x} + k) == from) {
      Report(sink, 0, nbr + 3 * int64_t{x} + k, 4, Array::kTriNeighbours, true);
      nbr[3 * int64_t{x} + k] = to;
      return;
    }
}

// The flip of edge QR between t = (P, Q, R) (Q and R in t's slots jq and jr) and u (its first
// two corners w0, w1; its corners are R, Q and S): t becomes (P, Q, S) and u (P, S, R), with their
// neighbour slots and the two outer triangles' that change. Out of line: it runs for about 1% of
// the edges tested, and inlined it kept its addresses live across the test (GCC 12: 7% more
// instructions a sweep).
template <class Sink>
[[gnu::noinline]] void Flip(int32_t* tri, int32_t* nbr, int32_t t, int jq, int jr, int32_t u,
                            int32_t w0, int32_t w1, int32_t pv, int32_t qv, int32_t rv, int32_t s,
                            Sink& sink) {
  const int64_t t3 = 3 * int64_t{t};
  // u's outer neighbours: across (Q, S) and (S, R), by the slot opposite R and Q in u.
  const int ur = w0 == rv ? 0 : w1 == rv ? 1 : 2;
  const int uq = w0 == qv ? 0 : w1 == qv ? 1 : 2;
  const int32_t across_qs = Load(sink, 0, Array::kTriNeighbours, nbr + 3 * int64_t{u} + ur);
  const int32_t across_sr = Load(sink, 0, Array::kTriNeighbours, nbr + 3 * int64_t{u} + uq);
  const int32_t across_rp = Load(sink, 0, Array::kTriNeighbours, nbr + t3 + jq);
  const int32_t across_pq = Load(sink, 0, Array::kTriNeighbours, nbr + t3 + jr);
  // t' = (P, Q, S), u' = (P, S, R): the orientation kept (the quad is convex when S is inside).
  const int32_t nt[3] = {pv, qv, s}, nu[3] = {pv, s, rv};
  const int32_t bt[3] = {across_qs, u, across_pq}, bu[3] = {across_sr, across_rp, t};
  for (int k = 0; k < 3; ++k) {
    Report(sink, 0, tri + t3 + k, 4, Array::kTriangles, true);
    tri[t3 + k] = nt[k];
  }
  for (int k = 0; k < 3; ++k) {
    Report(sink, 0, tri + 3 * int64_t{u} + k, 4, Array::kTriangles, true);
    tri[3 * int64_t{u} + k] = nu[k];
  }
  for (int k = 0; k < 3; ++k) {
    Report(sink, 0, nbr + t3 + k, 4, Array::kTriNeighbours, true);
    nbr[t3 + k] = bt[k];
  }
  for (int k = 0; k < 3; ++k) {
    Report(sink, 0, nbr + 3 * int64_t{u} + k, 4, Array::kTriNeighbours, true);
    nbr[3 * int64_t{u} + k] = bu[k];
  }
  Repoint(nbr, across_qs, u, t, sink);  // (Q, S) now belongs to t
  Repoint(nbr, across_rp, t, u, sink);  // (R, P) now belongs to u
}

// Adds the visit's flips to *flips (in the flip path: no per-visit sum in the loop).
template <class Sink>
void VisitTriangle(const double* xy, int32_t* tri, int32_t* nbr, int64_t ti, double* flips,
                   Sink& sink) {
  const int32_t t = static_cast<int32_t>(ti);
  const int64_t t3 = 3 * ti;
  int32_t v[3];
  double p[3][2];
  for (int j = 0; j < 3; ++j) v[j] = Load(sink, 0, Array::kTriangles, tri + t3 + j);
  for (int j = 0; j < 3; ++j) {
    const double* q = xy + 2 * int64_t{v[j]};
    Report(sink, 0, q, 8, Array::kCoords, false, AccessKind::kCoordRead, v[j]);
    Report(sink, 0, q + 1, 8, Array::kCoords, false);
    p[j][0] = q[0], p[j][1] = q[1];
  }
#pragma GCC unroll 3
  for (int j = 0; j < 3; ++j) {
    const int32_t u = Load(sink, 0, Array::kTriNeighbours, nbr + t3 + j);
    if (u <= t) continue;
    // t = (P, Q, R) from slot j, the edge QR; u holds R, Q and S, S opposite the edge.
    const int jq = (j + 1) % 3, jr = (j + 2) % 3;
    int32_t w[3];
    for (int k = 0; k < 3; ++k) w[k] = Load(sink, 0, Array::kTriangles, tri + 3 * int64_t{u} + k);
    // u's corners are Q, R and S in some order: S without a search. The search's branches
    // mispredicted (with them the sweep took 29.8 ms on carabiner, without 24.2).
    const int32_t s = w[0] ^ w[1] ^ w[2] ^ v[jq] ^ v[jr];
    const double* ps = xy + 2 * int64_t{s};
    Report(sink, 0, ps, 8, Array::kCoords, false, AccessKind::kCoordRead, s);
    Report(sink, 0, ps + 1, 8, Array::kCoords, false);
    const double sp[2] = {ps[0], ps[1]};
    if (!InCircle(p[j], p[jq], p[jr], sp)) continue;
    const int32_t pv = v[j], qv = v[jq];
    Flip(tri, nbr, t, jq, jr, u, w[0], w[1], pv, qv, v[jr], s, sink);
    *flips += 1.0;
    // Go on with t as it now is: its corners in slot order are P, Q, S.
    v[0] = pv, v[1] = qv, v[2] = s;
    const double pp[2] = {p[j][0], p[j][1]}, pq[2] = {p[jq][0], p[jq][1]};
    p[0][0] = pp[0], p[0][1] = pp[1], p[1][0] = pq[0], p[1][1] = pq[1];
    p[2][0] = sp[0], p[2][1] = sp[1];
  }
}

}  // namespace

int64_t JitterMesh(Mesh& m, double amount, uint64_t seed) {
  // Each triangle's least altitude, then each vertex's least over its triangles (v2t), then the
  // moves: a vertex's reads only its own coordinates and least altitude, all taken before any
  // move, so the vertices move in place and in parallel.
  std::vector<double> h(static_cast<size_t>(m.NumTriangles()));
#pragma omp parallel for schedule(static, 8192)
  for (int32_t t = 0; t < m.NumTriangles(); ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    const double* a = &m.xy[2 * int64_t{c[0]}];
    const double* b = &m.xy[2 * int64_t{c[1]}];
    const double* d = &m.xy[2 * int64_t{c[2]}];
    const double a2 = std::fabs(Area2(a[0], a[1], b[0], b[1], d[0], d[1]));
    const double e =
        std::max({std::hypot(b[0] - a[0], b[1] - a[1]), std::hypot(d[0] - b[0], d[1] - b[1]),
                  std::hypot(a[0] - d[0], a[1] - d[1])});
    h[t] = e > 0 ? a2 / e : 0.0;  // the least altitude: over the longest edge
  }
  const int64_t n = static_cast<int64_t>(m.interior.size());
#pragma omp parallel for schedule(static, 4096)
  for (int64_t i = 0; i < n; ++i) {
    const int32_t v = m.interior[i];
    double least = INFINITY;
    for (const int32_t* t = m.v2t.RowBegin(v); t != m.v2t.RowEnd(v); ++t)
      least = std::min(least, h[*t]);
    uint64_t bx, by;
    std::memcpy(&bx, &m.xy[2 * int64_t{v}], 8);
    std::memcpy(&by, &m.xy[2 * int64_t{v} + 1], 8);
    const double angle =
        static_cast<double>(Mix64(seed ^ bx ^ Mix64(by)) >> 11) * 0x1p-53 * 2 * M_PI;
    const double r = amount * least;
    m.xy[2 * int64_t{v}] += r * std::cos(angle);
    m.xy[2 * int64_t{v} + 1] += r * std::sin(angle);
  }
  return n;
}

namespace {

// NotDelaunayEdges with the triangles' neighbours `n` at hand (the kernel's own, which its flips
// keep up to date): the kernel's measure before and after its sweeps without two more searches
// of TriangleNeighbours.
int64_t NotDelaunayEdges(const Mesh& m, const AlignedVector<int32_t>& n) {
  int64_t bad = 0;
#pragma omp parallel for schedule(static, 8192) reduction(+ : bad)
  for (int32_t t = 0; t < m.NumTriangles(); ++t)
    for (int j = 0; j < 3; ++j) {
      const int32_t u = n[3 * int64_t{t} + j];
      if (u < 0) continue;
      const int32_t* c = &m.tri[3 * int64_t{t}];
      const int32_t* w = &m.tri[3 * int64_t{u}];
      int32_t s = -1;
      for (int k = 0; k < 3; ++k)
        if (w[k] != c[(j + 1) % 3] && w[k] != c[(j + 2) % 3]) s = w[k];
      bad += InCircle(&m.xy[2 * int64_t{c[0]}], &m.xy[2 * int64_t{c[1]}], &m.xy[2 * int64_t{c[2]}],
                      &m.xy[2 * int64_t{s}]);
    }
  return bad;  // each edge seen from either side that finds the other's corner inside
}

}  // namespace

bool IsDelaunay(const Mesh& m) { return NotDelaunayEdges(m) == 0; }

int64_t NotDelaunayEdges(const Mesh& m) { return NotDelaunayEdges(m, TriangleNeighbours(m)); }

namespace {

// The untimed set-up (KernelSetup): the jittered coordinates and the triangles' neighbours of the
// mesh it was made from.
struct EdgeSwapSetup : KernelSetup {
  AlignedVector<double> xy;
  AlignedVector<int32_t> nbr;
  uint64_t Bytes() const override { return 8 * uint64_t{xy.size()} + 4 * uint64_t{nbr.size()}; }
};

}  // namespace

std::unique_ptr<KernelSetup> KernelEdgeSwapSetup(const Mesh& m) {
  auto s = std::make_unique<EdgeSwapSetup>();
  Mesh jittered = m.Clone();
  JitterMesh(jittered, kJitterAmount, kJitterSeed);
  s->xy = std::move(jittered.xy);
  s->nbr = TriangleNeighbours(m);  // of the triangles alone
  return s;
}

template <class Sink>
SmoothResult KernelEdgeSwap(Mesh& m, const SmoothOptions& o, Sink& sink) {
  SmoothResult r;
  AlignedVector<int32_t> nbr;
  if (const EdgeSwapSetup* s = kernel_detail::SetupOf<EdgeSwapSetup>(o, [&](const auto& x) {
        return x.xy.size() == m.xy.size() && x.nbr.size() == m.tri.size();
      })) {
    m.xy = s->xy;
    nbr = s->nbr;
  } else {
    JitterMesh(m, kJitterAmount, kJitterSeed);
    nbr = TriangleNeighbours(m);
  }
  int64_t edges = 0;  // interior edges, each counted from both sides
  for (int32_t x : nbr) edges += x >= 0;
  const double interior_edges = edges > 0 ? static_cast<double>(edges / 2) : 1.0;
  kernel_detail::BindArrays(
      sink, {kernel_detail::Of(Array::kTriangles, m.tri), kernel_detail::Of(Array::kCoords, m.xy),
             kernel_detail::Of(Array::kTriNeighbours, nbr)});
  SmoothOptions until = o;
  until.tol = -INFINITY;
  r.quality_before =
      o.end_qualities ? 1.0 - static_cast<double>(NotDelaunayEdges(m, nbr)) / (2 * interior_edges)
                      : NAN;
  const double* xy = m.xy.data();
  int32_t* tri = m.tri.data();
  int32_t* n = nbr.data();
  double flips = 0.0;
  kernel_detail::DriveSweeps(
      until, 1.0, sink, &r,
      [&](int, SweepRegion* region) {
        flips = 0.0;
        smoother_detail::ForStatic<3>(tri, m.NumTriangles(), 1, sink, region,
                                      [xy, tri, n, f = &flips, &sink](int32_t*, int64_t t, int) {
                                        VisitTriangle(xy, tri, n, t, f, sink);
                                      });
        return 1.0 - flips / interior_edges;
      },
      [&](double) { return flips == 0.0; });
  r.quality_after = o.end_qualities
                        ? 1.0 - static_cast<double>(NotDelaunayEdges(m, nbr)) / (2 * interior_edges)
                        : NAN;
  // The flips changed the triangles: the vertex adjacency anew (untimed), where the caller reads
  // it.
  if (!o.adjacency_after) return r;
  RawMesh raw;
  raw.xy = std::move(m.xy);
  raw.tri = std::move(m.tri);
  m = BuildMesh(std::move(raw));
  return r;
}
MESHREUSE_KERNEL_ENTRIES_WITH_SETUP(KernelEdgeSwap)

std::vector<uint64_t> KernelEdgeSwapRefs(const Mesh&, const SmoothOptions&) { return {}; }

}  // namespace meshreuse
