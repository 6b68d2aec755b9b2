// assembly: the element loop of a FEM code assembling the P1 stiffness matrix (stiffness.h) by
// scatter-add, once per sweep from zero: values zeroed, then each triangle in storage order (the
// triangle order follows the vertex ordering, --triangle-order) computes its local 3x3 matrix from
// its corners and adds each entry at the position its element map gives. The measure is the
// matrix's trace (the same work every sweep: exactly max_iters sweeps run). Serial: two triangles
// sharing a vertex add to the same entries, so threads need a colouring or an owner-computes split,
// neither of which is built yet (--threads 1 only).
// Access sequence of one sweep: the values zeroed, val[0..nnz) 8 B stores in order; then per
// triangle t: the loop bound (smoother.h ForStatic), tri[3t..3t+2] 4 B each, x then y of each
// corner 8 B each (kCoordRead on the x), and for each of the nine (a, b) in row-major order
// map[9t+3a+b] 8 B, val[pos] 8 B load, val[pos] 8 B store: 37 per triangle; the bound once more at
// the end. So nnz + 37 T + 1 accesses, 3 T element touches.
#include "core/kernels/common.h"
#include "core/kernels/stiffness.h"

namespace meshreuse {

namespace {
using kernel_detail::Load;
using kernel_detail::Report;
}  // namespace

// One assembly sweep into a (the values zeroed first); returns the trace's sum.
template <class Sink>
double AssembleStiffness(const Mesh& m, StiffnessMatrix& a, Sink& sink) {
  double* val = a.val.data();
  for (int64_t i = 0; i < a.nnz(); ++i) {
    Report(sink, 0, val + i, 8, Array::kMatValues, true);
    val[i] = 0.0;
  }
  const double* xy = m.xy.data();
  const int32_t* tri = m.tri.data();
  const int64_t* map = a.map.data();
  return smoother_detail::ForStatic<3>(
      tri, m.NumTriangles(), 1, sink, nullptr, [xy, tri, map, val, &sink](const int32_t* c, int) {
        const int64_t t = (c - tri) / 3;
        double p[6];
        int32_t v[3];
        for (int j = 0; j < 3; ++j) v[j] = Load(sink, 0, Array::kTriangles, c + j);
        for (int j = 0; j < 3; ++j) {
          const double* q = xy + 2 * int64_t{v[j]};
          Report(sink, 0, q, 8, Array::kCoords, false, AccessKind::kCoordRead, v[j]);
          Report(sink, 0, q + 1, 8, Array::kCoords, false);
          p[2 * j] = q[0], p[2 * j + 1] = q[1];
        }
        double k[9];
        LocalStiffness(p[0], p[1], p[2], p[3], p[4], p[5], k);
        for (int e = 0; e < 9; ++e) {
          const int64_t pos = Load(sink, 0, Array::kElementMap, map + 9 * t + e);
          Report(sink, 0, val + pos, 8, Array::kMatValues, false);
          Report(sink, 0, val + pos, 8, Array::kMatValues, true);
          val[pos] += k[e];
        }
        return k[0] + k[4] + k[8];
      });
}
template double AssembleStiffness(const Mesh&, StiffnessMatrix&, NullSink&);

namespace {

struct AssemblySetup : KernelSetup {  // KernelSetup: the pattern and element map, values zero
  StiffnessMatrix a;
  uint64_t Bytes() const override { return a.Bytes(); }
};

}  // namespace

std::unique_ptr<KernelSetup> KernelAssemblySetup(const Mesh& m) {
  auto s = std::make_unique<AssemblySetup>();
  s->a = StiffnessPattern(m);
  return s;
}

template <class Sink>
SmoothResult KernelAssembly(Mesh& m, const SmoothOptions& o, Sink& sink) {
  SmoothResult r;
  const AssemblySetup* s = kernel_detail::SetupOf<AssemblySetup>(o, [&](const auto& x) {
    return x.a.off.size() == static_cast<size_t>(m.NumVertices()) + 1 &&
           x.a.map.size() == 9 * static_cast<size_t>(m.NumTriangles());
  });
  StiffnessMatrix a = s ? s->a : StiffnessPattern(m);
  kernel_detail::BindArrays(
      sink,
      {kernel_detail::Of(Array::kTriangles, m.tri), kernel_detail::Of(Array::kCoords, m.xy),
       kernel_detail::Of(Array::kMatValues, a.val), kernel_detail::Of(Array::kElementMap, a.map)});
  SmoothOptions fixed = o;
  fixed.tol = -INFINITY;
  // The whole sweep, the zeroing too, in the region (the thread CPU time compare reads).
  kernel_detail::DriveSweeps(
      fixed, 0.0, sink, &r,
      [&](int, SweepRegion* region) {
        if (region) region->Enter(0);
        const double trace = AssembleStiffness(m, a, sink);
        if (region) region->Exit(0);
        return trace;
      },
      [](double) { return false; });
  r.quality_before = 0.0;
  r.quality_after = r.sweeps.empty() ? 0.0 : r.sweeps.back().quality;
  return r;
}
MESHREUSE_KERNEL_ENTRIES_WITH_SETUP(KernelAssembly)

std::vector<uint64_t> KernelAssemblyRefs(const Mesh& m, const SmoothOptions&) {
  const uint64_t nnz = m.v2v.idx.size() + static_cast<uint64_t>(m.NumVertices());
  return {nnz + 37 * static_cast<uint64_t>(m.NumTriangles()) + 1};
}

}  // namespace meshreuse
