// libFuzzer harness: a Triangle .node/.ele pair. The input is the .node text, a line "@@@", then
// the .ele text (without the separator: all .node, an empty .ele).
#include <string_view>

#include "core/mesh_io.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  const size_t sep = all.find("\n@@@\n");
  const std::string_view node = sep == std::string_view::npos ? all : all.substr(0, sep + 1);
  const std::string_view ele = sep == std::string_view::npos ? "" : all.substr(sep + 5);
  meshreuse::fuzz::MemFile n(reinterpret_cast<const uint8_t*>(node.data()), node.size());
  meshreuse::fuzz::MemFile e(reinterpret_cast<const uint8_t*>(ele.data()), ele.size());
  meshreuse::RawMesh raw;
  try {
    raw = meshreuse::ReadTriangleFiles(n.path(), e.path());
  } catch (const meshreuse::InputError&) {
    return 0;
  }
  meshreuse::fuzz::Exercise(std::move(raw));
  return 0;
}
