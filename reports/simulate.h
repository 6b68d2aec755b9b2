// The runner behind `meshreuse simulate`: the set-associative simulator (analysis/cache_sim.h) on
// meshes streamed through the traced smoother (one run per mesh x ordering), meshreuse trace
// files and other tools' traces, each through tracer/access_stream.h. Rows in the simulator's own
// schema (CacheSimulation::Columns). With a machine (analysis/machine.h) the many-core simulator
// instead (analysis/multicore_sim.h): threads placed on cores, the streams interleaved.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "analysis/cache_sim.h"
#include "analysis/machine.h"
#include "analysis/multicore_sim.h"
#include "core/permutation.h"
#include "core/ranks/rank_part.h"
#include "core/smoother.h"
#include "core/table.h"
#include "reports/log.h"
#include "reports/run_info.h"

namespace meshreuse {

struct SimulateConfig {
  std::vector<std::string> inputs;
  std::string format;  // "": meshes and meshreuse traces; else a TraceFormat name
  std::vector<std::string> orderings = {"ori"};
  uint64_t seed = 1;
  int iterations = 1, threads = 1;  // for meshes: sweeps and streams
  UpdateMode mode = UpdateMode::kGaussSeidel;
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  CacheSpec cache = ParseCacheSpec("westmere-ex");
  uint32_t line_bytes = 64;
  bool instructions = false;  // lackey
  // A machine ("" : private caches per stream, `cache`): the many-core simulator.
  std::string machine;
  Placement placement = Placement::kCompact;
  int interleave = 1;    // for meshes with a machine: SmoothOptions::interleave
  std::string prefetch;  // levels with a next-line prefetcher ("" : the machine's; "none")
  // Meshes, private caches: simulate each of `ranks` parts as a rank of the distributed smoother
  // lays it out and sweeps it (reports/rank_locality.h), 0: the whole mesh.
  int32_t ranks = 0;
  std::string partition = "hilbert";
  CutPlacement cut_placement = CutPlacement::kLast;
  bool by_array = false;  // private caches: lookups and misses per array too (SimulateArrayTable)
};

// UsageError for what cannot run (levels without ways, a size that is no multiple of ways x line).
void CheckSimulateConfig(const SimulateConfig& cfg);
std::vector<std::unique_ptr<CacheSimulation>> RunSimulate(const SimulateConfig& cfg,
                                                          const Log& log);
Table SimulateTable(const std::vector<std::unique_ptr<CacheSimulation>>& runs, bool per_sweep);
// With cfg.by_array: each level's lookups and misses per array (CacheSimulation::ArrayColumns).
Table SimulateArrayTable(const std::vector<std::unique_ptr<CacheSimulation>>& runs);
// With cfg.machine: one MulticoreSimulation per mesh x ordering (or input), and its rows
// (MulticoreSimulation::Columns; `warm`: the last sweep's counts only).
std::vector<std::unique_ptr<MulticoreSimulation>> RunMachineSimulate(const SimulateConfig& cfg,
                                                                     const Log& log);
Table MachineTable(const std::vector<std::unique_ptr<MulticoreSimulation>>& runs, bool warm);
// "serial", "access" or a number of vertex visits per turn (SmoothOptions::interleave).
int ParseInterleave(const std::string& s);
std::string InterleaveName(int interleave);
Json SimulateConfigJson(const SimulateConfig& cfg);

}  // namespace meshreuse
