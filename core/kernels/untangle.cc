// untangle: mesh untangling (Freitag and Plassmann 2000; Mesquite's untangle-beta objective,
// Knupp 2001). The kernel first tangles its input on purpose (TangleMesh, below: outside the timed
// and traced sweeps), then each interior vertex in storage order, in place, minimises
//   F(p) = sum over its triangles of max(0, beta - o Area2(p, b, c))^2
// where Area2 is a triangle's doubled signed area, o the mesh's orientation (the sign of the summed
// Area2 before tangling) and beta = 0.05 x the mean |Area2| before tangling: triangles turned over
// (o Area2 <= 0) or nearly flat pull the vertex. Area2 is linear in p, so F is piecewise quadratic;
// one Newton step on the triangles active at p (H = 2 sum a a^T, g = -2 sum (beta - o Area2) a,
// a = o dArea2/dp), halved up to kHalvings times until F decreases (a gradient step scaled by
// 1/trace H when H is singular). The measure is the share of triangles not turned over,
// 1 - inverted/T, kept incrementally; the sweeps stop once none is (converged), at most
// max_iters (tol does not apply: a sweep may lower F and turn no triangle back yet).
// Access sequence of a visit of interior vertex v (the k-th interior entry): interior[k] 4 B, the
// patch (common.h GatherPatch: 4 + 8 tris(v)), then xy[2v..2v+1] 16 B store (kCoordWrite v) when v
// moved; the loop bound before each visit and after a thread's last. Its length depends on whether
// v moved (KernelInfo::refs is empty).
#include "core/kernels/untangle.h"

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
using kernel_detail::Patch;

constexpr int kHalvings = 10;

double Objective(const Patch& p, double o, double beta, double x, double y) {
  double f = 0.0;
  for (int i = 0; i < p.n; ++i) {
    const double d = beta - o * Area2(x, y, p.bx[i], p.by[i], p.cx[i], p.cy[i]);
    if (d > 0.0) f += d * d;
  }
  return f;
}

int Inverted(const Patch& p, double o, double x, double y) {
  int n = 0;
  for (int i = 0; i < p.n; ++i) n += !(o * p.StoredArea2(i, x, y) > 0.0);
  return n;
}

// The move from the patch's position; false when F has nothing to gain.
bool UntangleStep(const Patch& p, double o, double beta, double* x, double* y) {
  double gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0;
  for (int i = 0; i < p.n; ++i) {
    const double d = beta - o * Area2(p.px, p.py, p.bx[i], p.by[i], p.cx[i], p.cy[i]);
    if (!(d > 0.0)) continue;
    const double ax = o * (p.by[i] - p.cy[i]), ay = o * (p.cx[i] - p.bx[i]);
    gx -= 2.0 * d * ax, gy -= 2.0 * d * ay;
    hxx += 2.0 * ax * ax, hxy += 2.0 * ax * ay, hyy += 2.0 * ay * ay;
  }
  const double tr = hxx + hyy;
  if (!(tr > 0.0)) return false;
  const double det = hxx * hyy - hxy * hxy;
  double dx, dy;
  if (det > 1e-12 * tr * tr) {
    dx = -(hyy * gx - hxy * gy) / det;
    dy = -(hxx * gy - hxy * gx) / det;
  } else {
    dx = -gx / tr, dy = -gy / tr;
  }
  const double f = Objective(p, o, beta, p.px, p.py);
  for (int h = 0; h <= kHalvings; ++h, dx *= 0.5, dy *= 0.5) {
    if (Objective(p, o, beta, p.px + dx, p.py + dy) < f) {
      *x = p.px + dx, *y = p.py + dy;
      return true;
    }
  }
  return false;
}

}  // namespace

TangleStats TangleMesh(Mesh& m, double share, uint64_t seed) {
  TangleStats s;
  const int32_t nt = m.NumTriangles();
  double sum = 0.0, abs_sum = 0.0;
  for (int32_t t = 0; t < nt; ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    const double* a = &m.xy[2 * int64_t{c[0]}];
    const double* b = &m.xy[2 * int64_t{c[1]}];
    const double* d = &m.xy[2 * int64_t{c[2]}];
    const double a2 = Area2(a[0], a[1], b[0], b[1], d[0], d[1]);
    sum += a2, abs_sum += std::fabs(a2);
  }
  s.orientation = sum >= 0.0 ? 1.0 : -1.0;
  s.beta = nt > 0 ? 0.05 * abs_sum / nt : 0.0;
  // Every move from the positions before any: which vertices move and where depends on the
  // geometry alone, never on the numbering.
  const uint64_t threshold = share >= 1.0   ? ~uint64_t{0}
                             : share <= 0.0 ? 0
                                            : static_cast<uint64_t>(share * 18446744073709551616.0);
  std::vector<std::pair<int32_t, std::pair<double, double>>> moves;
  for (int32_t v : m.interior) {
    uint64_t bx, by;
    std::memcpy(&bx, &m.xy[2 * int64_t{v}], 8);
    std::memcpy(&by, &m.xy[2 * int64_t{v} + 1], 8);
    if (Mix64(seed ^ bx ^ Mix64(by)) > threshold) continue;
    const int32_t* u = m.v2v.RowBegin(v);
    const int32_t* best = u;
    for (; u != m.v2v.RowEnd(v); ++u) {
      const double* p = &m.xy[2 * int64_t{*u}];
      const double* q = &m.xy[2 * int64_t{*best}];
      if (p[0] < q[0] || (p[0] == q[0] && p[1] < q[1])) best = u;
    }
    const double* p = &m.xy[2 * int64_t{v}];
    const double* q = &m.xy[2 * int64_t{*best}];
    moves.push_back({v, {p[0] + 1.5 * (q[0] - p[0]), p[1] + 1.5 * (q[1] - p[1])}});
  }
  for (const auto& [v, xy] : moves)
    m.xy[2 * int64_t{v}] = xy.first, m.xy[2 * int64_t{v} + 1] = xy.second;
  s.moved = static_cast<int64_t>(moves.size());
  s.inverted = CountInverted(m, s.orientation);
  return s;
}

int64_t CountInverted(const Mesh& m, double orientation) {
  int64_t n = 0;
  for (int32_t t = 0; t < m.NumTriangles(); ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    const double* a = &m.xy[2 * int64_t{c[0]}];
    const double* b = &m.xy[2 * int64_t{c[1]}];
    const double* d = &m.xy[2 * int64_t{c[2]}];
    n += !(orientation * Area2(a[0], a[1], b[0], b[1], d[0], d[1]) > 0.0);
  }
  return n;
}

template <class Sink>
SmoothResult KernelUntangle(Mesh& m, const SmoothOptions& o, Sink& sink) {
  SmoothResult r;
  const TangleStats tangle = TangleMesh(m, kTangleShare, kTangleSeed);
  const double nt = m.NumTriangles() > 0 ? m.NumTriangles() : 1;
  int64_t inverted = tangle.inverted;
  r.quality_before = 1.0 - static_cast<double>(inverted) / nt;
  kernel_detail::BindArrays(
      sink, {kernel_detail::Of(Array::kInterior, m.interior),
             kernel_detail::Of(Array::kTriOffsets, m.v2t.off),
             kernel_detail::Of(Array::kTriIndex, m.v2t.idx),
             kernel_detail::Of(Array::kTriangles, m.tri), kernel_detail::Of(Array::kCoords, m.xy)});
  const smoother_detail::Arrays a = smoother_detail::ArraysOf(m);
  const double orient = tangle.orientation, beta = tangle.beta;
  // A sweep may lower F without turning a triangle back (a tangled neighbour moves next sweep):
  // the sweeps go on until none is turned over, at most max_iters, whatever tol says.
  SmoothOptions until = o;
  until.tol = -INFINITY;
  kernel_detail::DriveSweeps(
      until, r.quality_before, sink, &r,
      [&](int threads, SweepRegion* region) {
        inverted -= static_cast<int64_t>(smoother_detail::ForStatic<1>(
            m.interior.data(), static_cast<int64_t>(m.interior.size()), threads, sink, region,
            [a, orient, beta, &sink](const int32_t* item, int tid) {
              const int32_t v = Load(sink, tid, Array::kInterior, item);
              Patch p;
              if (!kernel_detail::GatherPatch(a, v, tid, sink, &p)) return 0.0;
              double x, y;
              if (!UntangleStep(p, orient, beta, &x, &y)) return 0.0;
              const int before = Inverted(p, orient, p.px, p.py);
              const int after = Inverted(p, orient, x, y);
              kernel_detail::Report(sink, tid, a.xy + 2 * int64_t{v}, 16, Array::kCoords, true,
                                    AccessKind::kCoordWrite, v);
              a.xy[2 * int64_t{v}] = x;
              a.xy[2 * int64_t{v} + 1] = y;
              return static_cast<double>(before - after);
            }));
        return 1.0 - static_cast<double>(inverted) / nt;
      },
      [&](double) { return inverted == 0; });
  r.quality_after =
      o.end_qualities ? 1.0 - static_cast<double>(CountInverted(m, orient)) / nt : NAN;
  return r;
}
MESHREUSE_KERNEL_ENTRIES(KernelUntangle)

std::vector<uint64_t> KernelUntangleRefs(const Mesh&, const SmoothOptions&) { return {}; }

}  // namespace meshreuse
