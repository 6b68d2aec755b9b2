// libFuzzer harness: a permutation file (`--ordering file:PATH`) for a 20 x 15 synthetic mesh,
// applied to the mesh when accepted.
#include "core/synthetic.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  const Mesh& mesh = fuzz::SmallMesh();
  fuzz::MemFile f(data, size);
  try {
    const Permutation p = ComputeOrdering("file:" + f.path(), mesh, 1);
    ApplyPermutation(mesh, p, TriangleOrder::kFile);
  } catch (const InputError&) {
  }
  return 0;
}
