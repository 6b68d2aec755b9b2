// local-opt: optimisation-based smoothing on a local patch, as Mesquite's local-patch solvers do
// (Knupp 2000; Freitag and Knupp 2002; the inverse mean-ratio metric): each interior vertex in
// storage order, in place, minimises F(p) = sum over its triangles of the inverse mean ratio
//   mu_t(p) = (|p-b|^2 + |b-c|^2 + |c-p|^2) / (2 sqrt(3) s_t Area2(p, b, c))
// (1 for an equilateral triangle, growing as it degrades; +inf once a triangle turns over: s_t is
// the sign of its doubled area Area2 at the start of the visit, so a valid triangle stays valid)
// by kSteps steepest-descent steps, each with Armijo backtracking: a step of alpha = l^2 (l^2:
// the mean squared edge length of the patch), halved up to kHalvings times until
// F(p - alpha g) <= F(p) - 1e-4 alpha |g|^2; a step that finds no such point ends the visit. The
// vertex is stored when it moved. The reported measure is the global quality (core/quality.h),
// kept incrementally; the stop rule the smoother's.
// Access sequence of a visit of interior vertex v (the k-th interior entry): interior[k] 4 B, the
// patch gathered once (common.h GatherPatch: 4 + 8 tris(v)), the descent on the copy (no access),
// then when v moved common.h StoreMove (1 + 3 tris(v)); the loop bound before each visit and after
// a thread's last. Its length depends on whether v moved (KernelInfo::refs is empty).
#include <cmath>

#include "core/kernels/common.h"

namespace meshreuse {

namespace {

using kernel_detail::Area2;
using kernel_detail::Load;
using kernel_detail::Patch;

constexpr int kSteps = 2;
constexpr int kHalvings = 10;

// F at (x, y), and with kGradient its gradient; +inf when a triangle is not of its sign s. The
// line search asks for F alone: a template, so no call computes a gradient it drops (a runtime
// "gx == nullptr" left the compiler to compute it anyway, a third of the kernel's time).
template <bool kGradient>
double InverseMeanRatio(const Patch& p, const double* s, double x, double y, double* gx,
                        double* gy) {
  static const double k = 2.0 * std::sqrt(3.0);
  double f = 0.0, ax = 0.0, ay = 0.0;
  for (int i = 0; i < p.n; ++i) {
    const double bx = p.bx[i], by = p.by[i], cx = p.cx[i], cy = p.cy[i];
    const double a2 = s[i] * Area2(x, y, bx, by, cx, cy);
    if (!(a2 > 0.0)) return INFINITY;
    const double sq = (x - bx) * (x - bx) + (y - by) * (y - by) + (bx - cx) * (bx - cx) +
                      (by - cy) * (by - cy) + (cx - x) * (cx - x) + (cy - y) * (cy - y);
    f += sq / (k * a2);
    if constexpr (kGradient) {
      // d(sq)/dp = 2 (p-b) + 2 (p-c); d(Area2)/dp = (by - cy, cx - bx), times s.
      const double dsx = 2.0 * (x - bx) + 2.0 * (x - cx), dsy = 2.0 * (y - by) + 2.0 * (y - cy);
      const double dax = s[i] * (by - cy), day = s[i] * (cx - bx);
      ax += (dsx * a2 - sq * dax) / (k * a2 * a2);
      ay += (dsy * a2 - sq * day) / (k * a2 * a2);
    }
  }
  if constexpr (kGradient) *gx = ax, *gy = ay;
  return f;
}

// The descent from the patch's position; false when it did not move.
bool Descend(const Patch& p, double* x, double* y) {
  double s[kernel_detail::kMaxPatch];
  double l2 = 0.0;
  for (int i = 0; i < p.n; ++i) {
    s[i] = Area2(p.px, p.py, p.bx[i], p.by[i], p.cx[i], p.cy[i]) >= 0.0 ? 1.0 : -1.0;
    l2 += (p.px - p.bx[i]) * (p.px - p.bx[i]) + (p.py - p.by[i]) * (p.py - p.by[i]);
  }
  if (p.n == 0) return false;
  l2 /= p.n;
  double px = p.px, py = p.py, gx = 0.0, gy = 0.0;
  double f = InverseMeanRatio<true>(p, s, px, py, &gx, &gy);
  if (!std::isfinite(f)) return false;  // a patch already turned over: left to untangle
  bool moved = false;
  for (int step = 0; step < kSteps; ++step) {
    const double g2 = gx * gx + gy * gy;
    if (!(g2 > 0.0)) break;
    double alpha = l2, fn = INFINITY, nx = px, ny = py;
    int h = 0;
    for (; h <= kHalvings; ++h, alpha *= 0.5) {
      nx = px - alpha * gx, ny = py - alpha * gy;
      fn = InverseMeanRatio<false>(p, s, nx, ny, nullptr, nullptr);
      if (fn <= f - 1e-4 * alpha * g2) break;
    }
    if (h > kHalvings) break;
    px = nx, py = ny, moved = true;
    f = InverseMeanRatio<true>(p, s, px, py, &gx, &gy);
  }
  *x = px, *y = py;
  return moved;
}

}  // namespace

template <class Sink>
SmoothResult KernelLocalOpt(Mesh& m, const SmoothOptions& o, Sink& sink) {
  return kernel_detail::RunSmoothingKernel(
      m, o, sink,
      [&sink](const smoother_detail::Arrays& a, const int32_t* item, double* wq, int tid) {
        const int32_t v = Load(sink, tid, Array::kInterior, item);
        Patch p;
        if (!kernel_detail::GatherPatch(a, v, tid, sink, &p)) return 0.0;
        double x, y;
        if (!Descend(p, &x, &y)) return 0.0;
        return kernel_detail::StoreMove(a, p, v, x, y, wq, tid, sink);
      });
}
MESHREUSE_KERNEL_ENTRIES(KernelLocalOpt)

std::vector<uint64_t> KernelLocalOptRefs(const Mesh&, const SmoothOptions&) { return {}; }

}  // namespace meshreuse
