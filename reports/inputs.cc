// Mesh inputs of the runners; see inputs.h.
#include "reports/inputs.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/table.h"

namespace meshreuse {

ProgressListener PhaseListener(const Log& log, bool bytes) {
  if (!log.progress) return {};
  return [&log, bytes](const std::string& what, uint64_t done, uint64_t total, double s) {
    char b[200];
    if (total > 0 && done > 0) {
      const double f = std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
      std::snprintf(b, sizeof b, "%s: %.0f%% (%.1f s, about %.1f s left", what.c_str(), 100 * f, s,
                    s * (1 - f) / f);
    } else {
      std::snprintf(b, sizeof b, "%s: %.1f s so far", what.c_str(), s);
    }
    std::string line = b;
    if (bytes && s > 0) line += ", " + Fixed(static_cast<double>(done) / 1e6 / s, 0) + " MB/s";
    if (total > 0 && done > 0) line += ")";
    log.Say(line);
  };
}

std::vector<std::string> SaveMesh(const Mesh& m, const std::string& target, const Log& log) {
  const PhaseProgress phase("writing " + target, PhaseListener(log, false));
  return WriteMesh(m, target);
}

Mesh LoadMesh(const std::string& path, const Log& log) {
  log.Say("reading " + path);
  std::vector<std::string> warnings;
  Mesh m;
  {
    const PhaseProgress phase("reading " + path, PhaseListener(log, true));
    m = ReadMesh(path, &warnings);
  }
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
