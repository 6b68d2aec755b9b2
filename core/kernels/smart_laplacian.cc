// smart-laplacian: constrained Laplacian smoothing (Freitag, Jones and Plassmann 1995, "smart"
// Laplacian; Mesquite's smart Laplacian option): each interior vertex, in storage order and in
// place (Gauss-Seidel), is tried at the plain average of its distinct neighbours, and the move is
// kept only if the smallest quality (core/quality.h: shortest/longest edge) of its triangles does
// not drop. The global quality is kept incrementally as the smoother keeps it, and the stop rule
// is the smoother's. With threads: the static split of the interior list, moves racing at the
// chunks' borders as the paper's Laplacian does.
// Access sequence of one visit of interior vertex v (the k-th interior entry), as the Laplacian's
// in core/smoother.h where the same:
//   interior[k] 4 B; v2v.off[v], v2v.off[v+1] 8 B each (kAdjacency v on the first); per
//   neighbour u: v2v.idx[i] 4 B, xy[2u..2u+1] 16 B (kCoordRead u)  -- the candidate, in registers
//   v2t.off[v], v2t.off[v+1] 8 B each; per triangle t: v2t.idx[i] 4 B, tri[3t..3t+2] 4 B each,
//   x then y of the two corners other than v 8 B each (kCoordRead on the x; v's own position is
//   the candidate, not read), its stored quality wq[2t+1] 8 B  -- the trial: 2 + 9 tris(v)
//   kept only: xy[2v..2v+1] 16 B store (kCoordWrite v), then per triangle the Laplacian's quality
//   update: v2t.idx[i], tri[3t..3t+2], the six coordinates (kCoordRead on each x), wq[2t+1] 8 B,
//   wq[2t] 8 B, wq[2t+1] 8 B store: 1 + 13 tris(v)
// plus the loop bound before each visit and after a thread's last (smoother.h ForStatic). So a
// visit is 6 + 2 deg(v) + 2 + 9 tris(v) accesses, and 1 + 13 tris(v) more when the move is kept:
// the stream's length depends on the values (KernelInfo::refs is empty).
#include "core/kernels/common.h"

namespace meshreuse {

namespace {

using kernel_detail::Load;
using kernel_detail::Report;
using smoother_detail::Arrays;

template <class Sink>
inline double VisitSmart(const Arrays& a, const int32_t* item, double* wq, int tid, Sink& sink) {
  const int32_t v = Load(sink, tid, Array::kInterior, item);
  const int64_t nb = Load(sink, tid, Array::kAdjOffsets, a.off + v, AccessKind::kAdjacency, v);
  const int64_t ne = Load(sink, tid, Array::kAdjOffsets, a.off + v + 1);
  double sx = 0.0, sy = 0.0;
  for (int64_t i = nb; i < ne; ++i) {
    const int64_t u = Load(sink, tid, Array::kAdjIndex, a.nbr + i);
    Report(sink, tid, a.xy + 2 * u, 16, Array::kCoords, false, AccessKind::kCoordRead,
           static_cast<int32_t>(u));
    sx += a.xy[2 * u];
    sy += a.xy[2 * u + 1];
  }
  const double inv = 1.0 / static_cast<double>(ne - nb);
  const double x = sx * inv, y = sy * inv;
  const int64_t b = Load(sink, tid, Array::kTriOffsets, a.toff + v);
  const int64_t e = Load(sink, tid, Array::kTriOffsets, a.toff + v + 1);
  double old_min = 1.0, new_min = 1.0;
  for (int64_t i = b; i < e; ++i) {
    const int64_t t = Load(sink, tid, Array::kTriIndex, a.tris + i);
    double c[6];
    for (int j = 0; j < 3; ++j) {
      const int32_t u = Load(sink, tid, Array::kTriangles, a.tri + 3 * t + j);
      if (u == v) {
        c[2 * j] = x, c[2 * j + 1] = y;
        continue;
      }
      const double* p = a.xy + 2 * int64_t{u};
      Report(sink, tid, p, 8, Array::kCoords, false, AccessKind::kCoordRead, u);
      Report(sink, tid, p + 1, 8, Array::kCoords, false);
      c[2 * j] = p[0], c[2 * j + 1] = p[1];
    }
    old_min = std::min(old_min, Load(sink, tid, Array::kTriQuality, wq + 2 * t + 1));
    new_min = std::min(new_min, TriangleQuality(c[0], c[1], c[2], c[3], c[4], c[5]));
  }
  if (!(new_min >= old_min)) return 0.0;
  Report(sink, tid, a.xy + 2 * int64_t{v}, 16, Array::kCoords, true, AccessKind::kCoordWrite, v);
  a.xy[2 * int64_t{v}] = x;
  a.xy[2 * int64_t{v} + 1] = y;
  return smoother_detail::RequalifyTriangles(a, b, e, wq, tid, sink);
}

}  // namespace

template <class Sink>
SmoothResult KernelSmartLaplacian(Mesh& m, const SmoothOptions& o, Sink& sink) {
  return kernel_detail::RunSmoothingKernel(
      m, o, sink, [&sink](const Arrays& a, const int32_t* item, double* wq, int tid) {
        return VisitSmart(a, item, wq, tid, sink);
      });
}
MESHREUSE_KERNEL_ENTRIES(KernelSmartLaplacian)

std::vector<uint64_t> KernelSmartLaplacianRefs(const Mesh&, const SmoothOptions&) { return {}; }

}  // namespace meshreuse
