// Meshes as the runners take them: read once with their warnings passed on, and laid out in an
// ordering (any spec of core/orderings/registry.h) with the triangle policy of permutation.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "core/progress.h"
#include "reports/log.h"

namespace meshreuse {

// Reads a mesh (any format of core/mesh_io.h); the reader's warnings go to log.Warn, prefixed
// with the path.
Mesh LoadMesh(const std::string& path, const Log& log);
// The mesh at `path` laid out in `ordering` (ori included) with the triangle policy; ori with
// TriangleOrder::kFile is the file as it is.
Mesh LayOut(const std::string& path, const OrderingSpec& ordering, uint64_t seed,
            TriangleOrder triangles, const Log& log);
// Writes a mesh (any format of core/mesh_io.h, WriteMesh) with progress on `log`; the files.
std::vector<std::string> SaveMesh(const Mesh& m, const std::string& target, const Log& log);
// The listener of a long phase (core/progress.h), said on `log` as "WHAT: 42% (1.2 s, about
// 1.6 s left)", with the rate in MB/s where `bytes`.
ProgressListener PhaseListener(const Log& log, bool bytes);
// "out/meshes/paper/carabiner.node" -> "carabiner": how tables name a mesh.
std::string MeshShortName(const std::string& path);

}  // namespace meshreuse
