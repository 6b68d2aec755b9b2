// Gmsh's partitioned meshes (`gmsh -part N -part_split`: PREFIX_1.msh .. PREFIX_N.msh, MSH 4.1,
// each part's nodes and elements with a $PartitionedEntities section; node tags are global) read
// as one mesh with Gmsh's partition (issue 23, interchange with Gmsh). The parts are merged by node
// tag -- a node on a part boundary is in several files and must have the same coordinates, bit for
// bit, in each -- into vertices in increasing node tag and triangles in increasing element tag
// (the order of the unsplit file Gmsh writes without -part); a vertex belongs to the
// lowest-numbered part holding one of its triangles (Gmsh partitions elements, a distributed
// smoother vertices). Refused by name: a missing part file, a part count other than
// the files' $PartitionedEntities, a node whose coordinates differ between parts, a triangle in two
// parts (ghost elements, `-part_ghosts`: split without them).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace meshreuse {

struct GmshSplit {
  RawMesh raw;                // merged: vertices and triangles by increasing tag
  std::vector<int32_t> part;  // per vertex of raw, 0-based
  int32_t parts = 0;
  std::vector<std::string> files;  // PREFIX_1.msh .. PREFIX_N.msh
};

// Whether `path` is PREFIX_K.msh (K >= 1) with PREFIX_1.msh beside it.
bool IsGmshSplitPath(const std::string& path);
// Any file of the set names the set. InputError naming the file and the problem.
GmshSplit ReadGmshSplit(const std::string& path);

}  // namespace meshreuse
