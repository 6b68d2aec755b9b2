// libFuzzer harness: a serial visit order file (`smooth --visit-order FILE`, the pi a distributed
// run writes) for a 20 x 15 synthetic mesh; when accepted it must list every interior vertex once,
// which the harness checks (a reader that accepted less would let the smoother skip or repeat
// vertices).
#include <cstdlib>
#include <vector>

#include "core/synthetic.h"
#include "core/visit_order.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  const Mesh& mesh = fuzz::SmallMesh();
  fuzz::MemFile f(data, size);
  try {
    const AlignedVector<int32_t> order = ReadVisitOrder(f.path(), mesh);
    if (order.size() != mesh.interior.size()) std::abort();
    std::vector<char> seen(mesh.NumVertices(), 0);
    for (int32_t v : order) {
      if (v < 0 || v >= mesh.NumVertices() || seen[v]) std::abort();
      seen[v] = 1;
    }
    for (int32_t v : mesh.interior)
      if (!seen[v]) std::abort();
  } catch (const InputError&) {
  }
  return 0;
}
