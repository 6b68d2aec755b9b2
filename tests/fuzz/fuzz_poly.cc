// libFuzzer harness: a .poly outline, checked as `mesh generate --poly` checks it before Triangle
// runs (core/triangle_runner.h CheckPoly): it must accept or refuse with an InputError, never
// crash, hang or allocate by a count. Triangle itself is not run (a process per input).
#include "core/triangle_runner.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  meshreuse::fuzz::MemFile f(data, size);
  try {
    const double area = meshreuse::CheckPoly(f.path());
    if (!(area > 0 && area < 1e30)) __builtin_trap();  // what it promises of an accepted file
  } catch (const meshreuse::InputError&) {
  }
  return 0;
}
