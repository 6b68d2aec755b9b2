// Shared helpers for the test suites: paths to tests/data and small meshes.
#pragma once

#include <string>

#include "core/mesh.h"
#include "core/mesh_io.h"

namespace meshreuse::testing {

inline std::string DataPath(const std::string& name) {
  return std::string(MESHREUSE_TEST_DATA) + "/" + name;
}

// The hand-computed sweep's mesh: boundary vertices 0..5 on a 4 x 2 rectangle, interior 6 and 7.
inline Mesh TwoInterior() { return ReadMesh(DataPath("two_interior.node")); }

}  // namespace meshreuse::testing
