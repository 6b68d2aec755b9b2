// laplacian: the paper's Algorithm 1, core/smoother.h unchanged (Gauss-Seidel or Jacobi, per-move
// or per-sweep quality): the registry's entry calls Smooth itself, so `--kernel laplacian` (the
// default everywhere) is the smoother every earlier result measured, bit for bit.
#include "core/kernels/kernel.h"

namespace meshreuse {

template <class Sink>
SmoothResult KernelLaplacian(Mesh& m, const SmoothOptions& o, Sink& sink) {
  return Smooth(m, o, sink, o.on_sweep ? *o.on_sweep : std::function<void(const SweepRecord&)>());
}
MESHREUSE_KERNEL_ENTRIES(KernelLaplacian)

std::vector<uint64_t> KernelLaplacianRefs(const Mesh& m, const SmoothOptions& o) {
  if (o.mode == UpdateMode::kGaussSeidel && o.quality == QualityMode::kPerSweep) return {};
  return RefsPerSweep(m, o.threads, o.mode);
}

}  // namespace meshreuse
