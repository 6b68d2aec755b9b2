// The runners behind `meshreuse mesh refine` and `meshreuse-mpi refine`: uniform refinement, each
// triangle into 4^K (core/refine.h), with global ids any process can compute from the coarse mesh
// alone. In one process the fine mesh is built whole (layout refinement, hilbert or pieces); with
// `ranks` and the pieces layout it is written into FILE.mrm by that many ranks as threads of this
// process, none holding the fine mesh (reports/distributed_refine.h: the runner of `mpirun -np P
// meshreuse-mpi refine`), byte for byte the same file.
#pragma once

#include <cstdint>
#include <string>

#include "core/refine.h"
#include "reports/distributed_refine.h"
#include "reports/log.h"
#include "reports/output.h"

namespace meshreuse {

extern const char* const kPiecesLayoutHelp;  // what the pieces layout is, for --help

struct MeshRefineConfig {
  std::string mesh, output;  // output: PATH.vtk, PATH.mrm, or a prefix for .node/.ele
  RefineOptions refine;
  std::string layout;  // refinement, hilbert, pieces; "": hilbert for .mrm, else refinement
  int32_t ranks = 0;   // > 0: pieces into PATH.mrm from this many ranks (threads)
};

// UsageError for a layout, ranks or output that cannot go together.
void CheckMeshRefineConfig(const MeshRefineConfig& cfg);
RunOutput RunMeshRefine(const MeshRefineConfig& cfg, const Log& log);
// What a distributed refinement prints (rank 0): the sizes, the checks, the content id, the file
// and each rank's table.
RunOutput DistRefineOutput(const DistRefineResult& r, const DistRefineConfig& cfg);

}  // namespace meshreuse
