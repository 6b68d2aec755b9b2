// The kernel registry: list.h expanded twice, once to declare each kernel's entry points and once
// to build the table.
#include <string>

#include "core/error.h"
#include "core/kernels/kernel.h"

namespace meshreuse {

#define MESHREUSE_KERNEL(fn, ...)                                    \
  SmoothResult fn##Timed(Mesh&, const SmoothOptions&);               \
  SmoothResult fn##Traced(Mesh&, const SmoothOptions&, KernelSink&); \
  std::vector<uint64_t> fn##Refs(const Mesh&, const SmoothOptions&); \
  std::unique_ptr<KernelSetup> fn##Setup(const Mesh&);
#include "core/kernels/list.h"
#undef MESHREUSE_KERNEL

const std::vector<KernelInfo>& Kernels() {
  static const std::vector<KernelInfo> kTable = {
#define MESHREUSE_KERNEL(fn, name, unit, jacobi, threads, moves, fixed, measure, parallel, desc, \
                         ref)                                                                    \
  {name,  fn##Timed, fn##Traced, fn##Refs, unit, jacobi, threads,                                \
   moves, fixed,     measure,    parallel, desc, ref,    fn##Setup},
#include "core/kernels/list.h"
#undef MESHREUSE_KERNEL
  };
  return kTable;
}

const char* VisitUnitName(VisitUnit u) {
  switch (u) {
    case VisitUnit::kVertex:
      return "vertex";
    case VisitUnit::kEdge:
      return "edge";
    case VisitUnit::kTriangle:
      return "triangle";
    case VisitUnit::kRow:
      return "row";
  }
  return "?";
}

bool IsPaperSweep(const KernelInfo& k) { return std::string(k.name) == kPaperKernel; }

const KernelInfo* FindKernel(const std::string& name) {
  for (const KernelInfo& k : Kernels())
    if (name == k.name) return &k;
  return nullptr;
}

std::string KernelNames() {
  std::string s;
  for (const KernelInfo& k : Kernels()) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

const KernelInfo& ParseKernel(const std::string& name) {
  const KernelInfo* k = FindKernel(name);
  if (!k)
    throw UsageError("--kernel: unknown kernel '" + name + "' (known: " + KernelNames() + ")");
  return *k;
}

void CheckKernelOptions(const KernelInfo& k, const SmoothOptions& o) {
  if (o.mode == UpdateMode::kJacobi && !k.jacobi)
    throw UsageError("--kernel " + std::string(k.name) +
                     " has no Jacobi form (--mode gauss-seidel only)");
  if (o.threads > 1 && !k.threads)
    throw UsageError("--kernel " + std::string(k.name) + " runs on one thread only (" + k.parallel +
                     ")");
}

}  // namespace meshreuse
