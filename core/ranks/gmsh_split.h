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

// Writes `m` as a split set PREFIX1.msh .. PREFIX<parts>.msh in Gmsh's partitioned MSH 4.1 (for
// Gmsh, viewing, and any reader of its format): part k's file holds the triangles of part k-1 (a
// triangle goes to its smallest corner's part, the distributed smoother's rule) and their corners,
// node tag = vertex id + 1, element tag = triangle id + 1, one partitioned surface entity per part
// (tag k + 1, parent the model's surface 1) in $PartitionedEntities (Gmsh 4.8 reads the files as
// partitioned: "3 partitions, 1 partition entity"). All files are written as a unit.
// Read back with ReadGmshSplit: the same mesh; each vertex then goes to the lowest part holding
// one of its triangles, which may differ from `part`. Returns the files.
std::vector<std::string> WriteGmshSplit(const Mesh& m, const std::vector<int32_t>& part,
                                        int32_t parts, const std::string& prefix);

// Whether `path` is PREFIX_K.msh (K >= 1) with PREFIX_1.msh beside it.
bool IsGmshSplitPath(const std::string& path);
// Any file of the set names the set. InputError naming the file and the problem.
GmshSplit ReadGmshSplit(const std::string& path);

}  // namespace meshreuse
