// The runner behind `meshreuse mesh partition`: a vertex partition for smoothing across ranks
// (core/ranks/partition.h) and what it costs a distributed sweep (cut edges, owned, cut and ghost
// vertices per part, balance, colours of the part graph); with `levels`, the coarse mesh's
// partition inherited by its refinement (core/refine.h: the parts of `mesh refine --levels K`'s
// vertices). Writes the partition file (one part per vertex, a line each) and a Gmsh split set
// when asked.
#pragma once

#include <cstdint>
#include <string>

#include "reports/log.h"
#include "reports/output.h"

namespace meshreuse {

struct MeshPartitionConfig {
  std::string mesh;
  std::string method = "hilbert";  // hilbert, metis, scotch, ranges or gmsh
  int32_t parts = 2;
  uint64_t seed = 1;
  int levels = 0;      // refine into 4^levels and inherit the parts
  std::string output;  // the partition file ("": none)
  std::string split;   // a Gmsh split set's prefix ("": none)
};

// UsageError for an unknown method or a split prefix that names no file.
void CheckMeshPartitionConfig(const MeshPartitionConfig& cfg);
// The per-part table (at most 64 parts), the summary line and the files written, as text.
RunOutput RunMeshPartition(const MeshPartitionConfig& cfg, const Log& log);

}  // namespace meshreuse
