// libFuzzer harness: a Gmsh .msh file (2.2 or 4.1 ASCII, 4.1 binary: ReadGmsh picks the reader).
#include "core/mesh_io.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  meshreuse::fuzz::MemFile f(data, size);
  meshreuse::RawMesh raw;
  try {
    raw = meshreuse::ReadGmsh(f.path());
  } catch (const meshreuse::InputError&) {
    return 0;
  }
  meshreuse::fuzz::Exercise(std::move(raw));
  return 0;
}
