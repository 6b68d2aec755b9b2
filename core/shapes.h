// The paper's nine test meshes (Table 4 of Aupy, Park, Raghavan). The originals are not public; we
// ship one .poly outline per name under core/shapes/ (drawn by scripts/make_shapes.py to resemble
// the name) and mesh it with Triangle to the paper's vertex count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshreuse {

struct ShapeInfo {
  const char* name;
  int64_t paper_vertices;
  int64_t paper_triangles;
  const char* outline;  // what the .poly draws
};

const std::vector<ShapeInfo>& Shapes();
const ShapeInfo* FindShape(const std::string& name);  // nullptr when unknown
std::string ShapeNames();                             // "carabiner, crake, ..."
// Folder holding NAME.poly: $MESHREUSE_SHAPES if set, else the source tree's core/shapes.
std::string ShapesDir();

}  // namespace meshreuse
