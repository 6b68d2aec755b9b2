// spmv: the row-centric FEM kernel, y = A x with A the P1 stiffness matrix (stiffness.h, assembled
// once before the sweeps, untimed) and x the vertices' x coordinates: each row i in storage order
// sums val * x[col] over its entries in increasing column id. The measure is x^T A x = sum_i x_i
// y_i (for x the coordinate function, the Dirichlet energy of f(x, y) = x: the mesh's area in exact
// arithmetic); the same work every sweep: exactly max_iters sweeps run. Threads: the rows split as
// schedule(static); each thread writes only its own rows of y, so there is no race.
// Access sequence of row i: the loop bound (smoother.h ForStatic), off[i] and off[i+1] 8 B each,
// per entry j: col[j] 4 B, val[j] 8 B, x[col[j]] 8 B (kCoordRead col[j]); y[i] 8 B store
// (kCoordWrite i); x[i] 8 B (the measure's term): 5 + 3 nnz(i) per row, nnz(i) = deg(i) + 1, and
// the bound once more at the end of each thread's share.
#include "core/kernels/common.h"
#include "core/kernels/stiffness.h"

namespace meshreuse {

namespace {
using kernel_detail::Load;
using kernel_detail::Report;

struct SpmvSetup : KernelSetup {  // KernelSetup: the assembled matrix (no element map)
  StiffnessMatrix a;
  uint64_t Bytes() const override { return a.Bytes(); }
};

StiffnessMatrix Assembled(const Mesh& m) {
  StiffnessMatrix a = StiffnessPattern(m);
  NullSink none;
  AssembleStiffness(m, a, none);
  return a;
}

}  // namespace

std::unique_ptr<KernelSetup> KernelSpmvSetup(const Mesh& m) {
  auto s = std::make_unique<SpmvSetup>();
  s->a = Assembled(m);
  s->a.map = {};
  return s;
}

template <class Sink>
SmoothResult KernelSpmv(Mesh& m, const SmoothOptions& o, Sink& sink) {
  SmoothResult r;
  const SpmvSetup* s = kernel_detail::SetupOf<SpmvSetup>(
      o, [&](const auto& x) { return x.a.off.size() == static_cast<size_t>(m.NumVertices()) + 1; });
  StiffnessMatrix a = s ? s->a : Assembled(m);
  const int32_t nv = m.NumVertices();
  AlignedVector<double> x(static_cast<size_t>(nv)), y(static_cast<size_t>(nv), 0.0);
  for (int32_t i = 0; i < nv; ++i) x[i] = m.xy[2 * int64_t{i}];
  kernel_detail::BindArrays(
      sink,
      {kernel_detail::Of(Array::kMatOffsets, a.off), kernel_detail::Of(Array::kMatColumns, a.col),
       kernel_detail::Of(Array::kMatValues, a.val), kernel_detail::Of(Array::kVectorIn, x),
       kernel_detail::Of(Array::kVectorOut, y)});
  SmoothOptions fixed = o;
  fixed.tol = -INFINITY;
  const int64_t* off = a.off.data();
  const int32_t* col = a.col.data();
  const double* val = a.val.data();
  const double* xs = x.data();
  double* ys = y.data();
  kernel_detail::DriveSweeps(
      fixed, 0.0, sink, &r,
      [&](int threads, SweepRegion* region) {
        return smoother_detail::ForStatic<1>(
            off, nv, threads, sink, region,
            [off, col, val, xs, ys, &sink](const int64_t* row, int tid) {
              const int32_t i = static_cast<int32_t>(row - off);
              const int64_t b = Load(sink, tid, Array::kMatOffsets, row);
              const int64_t e = Load(sink, tid, Array::kMatOffsets, row + 1);
              double s = 0.0;
              for (int64_t j = b; j < e; ++j) {
                const int32_t c = Load(sink, tid, Array::kMatColumns, col + j);
                const double v = Load(sink, tid, Array::kMatValues, val + j);
                s += v * Load(sink, tid, Array::kVectorIn, xs + c, AccessKind::kCoordRead, c);
              }
              Report(sink, tid, ys + i, 8, Array::kVectorOut, true, AccessKind::kCoordWrite, i);
              ys[i] = s;
              return s * Load(sink, tid, Array::kVectorIn, xs + i);
            });
      },
      [](double) { return false; });
  r.quality_after = r.sweeps.empty() ? 0.0 : r.sweeps.back().quality;
  return r;
}
MESHREUSE_KERNEL_ENTRIES_WITH_SETUP(KernelSpmv)

std::vector<uint64_t> KernelSpmvRefs(const Mesh& m, const SmoothOptions& o) {
  const int threads = o.threads < 1 ? 1 : o.threads;
  std::vector<uint64_t> n(threads, 1);  // each share's last bound test
  const int32_t nv = m.NumVertices();
  for (int32_t i = 0; i < nv; ++i)
    n[StaticOwner(i, nv, threads)] += 5 + 3 * static_cast<uint64_t>(m.v2v.RowSize(i) + 1);
  return n;
}

}  // namespace meshreuse
