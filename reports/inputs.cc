// Mesh inputs of the runners; see inputs.h.
#include "reports/inputs.h"

#include <filesystem>
#include <vector>

#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/table.h"

namespace meshreuse {

Mesh LoadMesh(const std::string& path, const Log& log) {
  log.Say("reading " + path);
  std::vector<std::string> warnings;
  Mesh m = ReadMesh(path, &warnings);
  for (const std::string& w : warnings) log.Warn(w);  // each names its file
  log.Say("read " + Grouped(m.NumVertices()) + " vertices, " + Grouped(m.NumTriangles()) +
          " triangles");
  return m;
}

Mesh LayOut(const std::string& path, const OrderingSpec& ordering, uint64_t seed,
            TriangleOrder triangles, const Log& log) {
  Mesh m = LoadMesh(path, log);
  if (ordering.name == "ori" && triangles == TriangleOrder::kFile) return m;
  log.Say("laying out in " + ordering.text + " order, triangles " + TriangleOrderName(triangles));
  ApplyPermutationInPlace(&m, ComputeOrdering(ordering, m, seed), triangles);
  return m;
}

std::string MeshShortName(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

}  // namespace meshreuse
