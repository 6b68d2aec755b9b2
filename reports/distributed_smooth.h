// The runner behind `mpirun -np P meshreuse-mpi smooth MESH` (issue 23; ../shared/scale-out.md
// 3b): every rank reads the mesh (a mesh that fits one node), computes the same partition
// (Hilbert ranges, METIS seeded, or ranges of ids) and colouring -- or, for a mesh file
// (FILE.mrm) with the ranges partition, reads only its range and ghost ring (rank_neighbourhood.h)
// and learns the part graph from one all-gather; with PT-Scotch, reads its range's graph rows,
// partitions them with the other ranks, learns its part's ids and its ghosts' owners from the
// directory (part_directory.h) and reads only that part and its ghost ring --, keeps its part
// (core/ranks/rank_part.h) and smooths it with the ghost exchanges of core/ranks/halo_smoother.h;
// rank 0 gathers the moved vertices, writes the smoothed mesh (equal to the serial smoother's
// output: bit for bit at -np 1, and along the gathered order pi at any P), pi itself, and a table
// per rank. The transport moves the bytes (MPI in cli/mpi_main.cc, threads in
// core/ranks/thread_communicator.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/ranks/halo_smoother.h"
#include "core/ranks/rank_neighbourhood.h"
#include "core/table.h"
#include "reports/log.h"
#include "reports/output.h"
#include "reports/run_info.h"
#include "reports/timing.h"

namespace meshreuse {

struct DistSmoothConfig {
  std::string mesh;
  std::string partition = "hilbert";             // partition.h's methods, or ptscotch
  std::string ordering = "ori";                  // each rank's layout of its part (registry spec)
  CutPlacement placement = CutPlacement::kLast;  // where each part keeps its cut vertices
  uint64_t seed = 1;                             // METIS and seeded orderings
  HaloOptions smooth;
  std::string output;  // the smoothed mesh (rank 0 writes it)
  std::string pi_out;  // the serial visit order the run equals (ordered mode)
  // `--partition ptscotch`: a partition the job's ranks compute together (PT-Scotch over MPI; set
  // by cli/mpi_main.cc, which holds the communicator). Every rank calls it at once with its range
  // of graph rows (core/ranks/rank_neighbourhood.h) and gets those rows' parts; who owns what then
  // follows from core/ranks/part_directory.h. Empty: ptscotch is refused (threads, or a build
  // without it).
  std::function<std::vector<int32_t>(const GraphRows& rows, int32_t parts, uint64_t seed)>
      job_partition;
};

struct SmoothRankStats {
  int32_t rank = 0, colour = 0;
  int64_t owned = 0, noncut = 0, cut = 0, boundary = 0, ghosts = 0, triangles = 0, links = 0;
  double setup_seconds = 0;   // read, partition and layout
  double smooth_seconds = 0;  // wall time of the sweeps
  double cpu_seconds = 0;     // thread CPU time moving, packing and summing quality
  double wait_seconds = 0;    // blocked receiving ghosts
  double work_seconds = 0;    // wall time of the spans cpu_seconds measures
  uint64_t messages = 0, bytes_sent = 0, peak_rss_bytes = 0;
  uint64_t bytes_read = 0;  // of the mesh file, by a distributed read (0: the whole file read)
};

struct DistSmoothResult {
  int32_t vertices = 0, triangles = 0, parts = 0, colours = 0;
  int64_t cut_edges = 0;
  HaloResult result;  // this rank's (sweeps and qualities are the same on every rank)
  std::vector<SmoothRankStats> ranks;  // rank 0: every rank's; others: empty
  // Rank 0: the machine around the sweeps (rank 0's load average before and after; the lowest
  // rank's CPU/wall over its work spans): a busy machine is said, as compare says it.
  Noise noise;
  std::vector<std::string> written;
};

void CheckDistSmoothConfig(const DistSmoothConfig& cfg);  // UsageError
// MESH and its partition as every rank computes them: LoadForRanks and PartsByMethod, or for
// `gmsh` the Gmsh split set MESH belongs to, merged, with Gmsh's parts (core/ranks/gmsh_split.h;
// the set's part count must be `parts`).
struct PartitionedMesh {
  Mesh mesh;
  std::vector<int32_t> part;
};
PartitionedMesh LoadPartitioned(const std::string& path, const std::string& method, int32_t parts,
                                uint64_t seed, const Log& log);
// Whether each rank reads only its part of MESH (a mesh file, FILE.mrm, with --partition ranges
// or ptscotch: core/ranks/rank_neighbourhood.h) rather than the whole mesh.
bool ReadsRanges(const DistSmoothConfig& cfg);
// MESH as every rank reads it: the serial smoother's default layout (vertex ids unchanged,
// triangles sorted by their smallest corner); UsageError when `parts` exceeds its vertices.
Mesh LoadForRanks(const std::string& path, int32_t parts, const Log& log);
// Every rank calls it with the same configuration. `on_sweep` runs on every rank after each sweep;
// `on_setup` once the partition is known (rank 0 prints the header from it).
DistSmoothResult RunDistributedSmooth(
    const DistSmoothConfig& cfg, Communicator& tx, const Log& log,
    const std::function<void(const DistSmoothResult&)>& on_setup = {},
    const std::function<void(const HaloSweep&)>& on_sweep = {});
Table RankStatsTable(const std::vector<SmoothRankStats>& ranks);
Json DistSmoothJson(const DistSmoothConfig& cfg, const DistSmoothResult& r);
// What rank 0 prints after the sweeps (the summary line and each rank's table) and writes under
// --out (sweeps.csv, ranks.csv, run.json).
RunOutput DistSmoothOutput(const DistSmoothResult& r, const DistSmoothConfig& cfg);

}  // namespace meshreuse
