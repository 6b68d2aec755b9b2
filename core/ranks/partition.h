// Vertex partitions for smoothing across ranks (issue 23, ../shared/scale-out.md section 3b):
// contiguous ranges of the Hilbert order (the default: no dependency, balanced to one vertex, one
// file for any P), METIS k-way and Scotch (better cuts, one node), and what a partition costs a
// distributed sweep: cut edges, ghosts per part, balance, and the greedy colouring of the part
// graph that orders the cut vertices' rounds. Parts inherited through refinement: core/refine.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace meshreuse {

// Part p holds Hilbert positions [n p / P, n (p + 1) / P). P in 1..n (UsageError otherwise).
std::vector<int32_t> HilbertRangeParts(const Mesh& m, int32_t parts);
// Scotch's graph partitioning (SCOTCH_graphPart with its balance strategy, 3% imbalance allowed)
// into `parts` parts, deterministic and seeded, so every rank computes the same parts; the free
// (CeCILL-C) alternative to METIS, with 64-bit indices (Debian's scotch-int64 build).
std::vector<int32_t> ScotchParts(const Mesh& m, int32_t parts, uint64_t seed);
// METIS_PartGraphKway into `parts` parts, seeded (one part: all zero).
std::vector<int32_t> MetisParts(const Mesh& m, int32_t parts, uint64_t seed);

// Part p holds the ids [n p / P, n (p + 1) / P) as stored (RangeOwner): the partition a
// distributed read of a mesh file takes (rank_neighbourhood.h), Hilbert ranges when the file is in
// Hilbert order.
std::vector<int32_t> RangeParts(const Mesh& m, int32_t parts);

// "hilbert", "metis", "scotch", "ranges" or "gmsh" (UsageError naming --partition otherwise;
// gmsh's parts come with the mesh, core/ranks/gmsh_split.h, and PartsByMethod refuses it).
void CheckPartitionMethod(const std::string& method);
// A partition from a file (`--partition file:PATH`): what `mesh partition -o` writes, or METIS's
// and Scotch's plain output, one part per line, line k vertex k's ('#' starts a comment). It must
// give every vertex of the mesh (`vertices`) a part in 0..parts-1; a part may be empty. InputError
// naming the file and line otherwise (read no further than `vertices` parts).
std::vector<int32_t> ReadPartitionFile(const std::string& path, int32_t vertices, int32_t parts);
inline bool IsPartitionFile(const std::string& method) { return method.rfind("file:", 0) == 0; }
std::vector<int32_t> PartsByMethod(const Mesh& m, const std::string& method, int32_t parts,
                                   uint64_t seed);

struct PartitionStats {
  int32_t parts = 0;
  int64_t cut_edges = 0;           // edges whose ends lie in two parts
  std::vector<int64_t> owned;      // vertices per part
  std::vector<int64_t> ghosts;     // per part: distinct vertices of other parts next to its own
  std::vector<int64_t> cut_owned;  // per part: its vertices with a neighbour elsewhere
  std::vector<int32_t> colour;     // greedy colouring of the part graph, parts in id order
  int32_t colours = 0;
  double imbalance() const;  // max owned / mean owned
};
// The greedy colouring of the part graph (`neighbours[p]`: the parts next to p, symmetric), parts
// in id order, each the least colour no lower neighbour has; `colours` gets the count.
std::vector<int32_t> GreedyPartColouring(const std::vector<std::vector<int32_t>>& neighbours,
                                         int32_t* colours);
// Throws InputError(name, 0, ...) for a part outside [0, parts).
PartitionStats MeasurePartition(const Mesh& m, const std::vector<int32_t>& part, int32_t parts,
                                const std::string& name = "partition");

}  // namespace meshreuse
