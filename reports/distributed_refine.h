// The runner behind `mpirun -np P meshreuse-mpi refine MESH --levels K -o OUT.mrm` (issue 23;
// ../shared/scale-out.md 3b-3c): a refined mesh file written by every rank at once, no rank holding
// the fine mesh. Every rank reads the coarse mesh and lays it out in Hilbert order
// (LayOutForRanks), takes a range of coarse triangles (PiecesLayout::Split, balanced by fine
// vertices) and writes its blocks' sections of the file in the pieces layout (core/refine.h: ids
// computed without communication); once every rank has written, each hashes a share of the blocks
// and rank 0 writes the tables and renames the file into place. The file is byte for byte what
// `meshreuse mesh refine MESH --levels K --layout pieces -o OUT.mrm` writes from one process, for
// any number of ranks. Each rank checks its fine triangles' areas; the transport moves the bytes
// (MPI in cli/mpi_main.cc, threads in core/ranks/thread_communicator.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/ranks/halo_smoother.h"
#include "core/refine.h"
#include "core/table.h"
#include "reports/log.h"

namespace meshreuse {

struct DistRefineConfig {
  std::string mesh, output;  // output: PATH.mrm, a regular file or a new path
  RefineOptions refine;
};

struct RefineRankStats {
  int32_t rank = 0;
  int64_t coarse_triangles = 0, vertices = 0, triangles = 0;
  double seconds = 0;      // refining and writing this rank's range
  double cpu_seconds = 0;  // this rank's thread CPU time doing it
  uint64_t peak_rss_bytes = 0;
};

struct DistRefineResult {
  int64_t coarse_vertices = 0, coarse_triangles = 0, vertices = 0, triangles = 0;
  int64_t euler = 0;         // V - E + T of the fine mesh (E from T and its boundary edges)
  int64_t coarse_euler = 0;  // the coarse mesh's
  double min_area2 = 0;      // RefinedRange::min_area2 over every rank's fine triangles
  uint64_t content_id = 0;   // of the written file (its header)
  double seconds = 0;        // the whole run on rank 0
  std::vector<RefineRankStats> ranks;  // rank 0: every rank's; others: empty
};

// UsageError (exit 2) for a configuration no rank may start: no mesh, an output that is not a
// mesh file, options out of range.
void CheckDistRefineConfig(const DistRefineConfig& cfg);
// Every rank calls it with the same configuration. InputError when the fine mesh would have a
// triangle that is degenerate or turned against its coarse triangle (rounding on a coarse triangle
// too thin for the jitter); nothing is written then.
DistRefineResult RunDistributedRefine(const DistRefineConfig& cfg, Communicator& tx,
                                      const Log& log);
Table RefineRankTable(const std::vector<RefineRankStats>& ranks);

}  // namespace meshreuse
