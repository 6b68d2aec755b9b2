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
#include "core/smoother.h"
#include "core/table.h"
#include "reports/log.h"
#include "reports/machine_runs.h"
#include "reports/output.h"
#include "reports/run_info.h"
#include "reports/stream_source.h"

namespace meshreuse {

struct SimulateConfig : StreamSource {
  // StreamSource: the inputs, orderings, sweeps, threads (for meshes: streams), and, with a
  // machine, the streams' interleaving (`interleave`: a vertex visit of each thread per turn by
  // default there).
  CacheSpec cache = ParseCacheSpec("westmere-ex");
  uint32_t line_bytes = 64;
  // A machine ("" : private caches per stream, `cache`): the many-core simulator.
  std::string machine;
  // With a machine: a run per thread count (empty: `threads` alone) and placement, every
  // placement of a count fed from one stream (one thread: the first placement only, as any
  // placement puts it on socket 0's first core).
  std::vector<int> machine_threads;
  std::vector<Placement> placements = {Placement::kCompact};
  bool warm = false;        // per-thread rows of the last sweep only
  bool per_thread = false;  // print the per-thread rows, not the summary
  std::string prefetch;     // levels with a next-line prefetcher ("" : the machine's; "none")
  bool by_array = false;    // private caches: lookups and misses per array too (SimulateArrayTable)
};

// UsageError for what cannot run (levels without ways, a size that is no multiple of ways x line).
void CheckSimulateConfig(const SimulateConfig& cfg);
std::vector<std::unique_ptr<CacheSimulation>> RunSimulate(const SimulateConfig& cfg,
                                                          const Log& log);
Table SimulateTable(const std::vector<std::unique_ptr<CacheSimulation>>& runs, bool per_sweep);
// With cfg.by_array: each level's lookups and misses per array (CacheSimulation::ArrayColumns).
Table SimulateArrayTable(const std::vector<std::unique_ptr<CacheSimulation>>& runs);
// With cfg.machine: one MulticoreSimulation per input (x ordering for meshes) x thread count x
// placement, each with its run's summary (reports/machine_runs.h: the last sweep).
struct MachineSimulations {
  std::vector<std::unique_ptr<MulticoreSimulation>> sims;
  std::vector<MachineRun> runs;  // sims[i]'s
};
MachineSimulations RunMachineSimulate(const SimulateConfig& cfg, const Log& log);
// Their per-thread rows (MulticoreSimulation::Columns; `warm`: the last sweep's counts only).
Table MachineTable(const std::vector<std::unique_ptr<MulticoreSimulation>>& runs, bool warm);
// "serial", "access" or a number of vertex visits per turn (SmoothOptions::interleave).
int ParseInterleave(const std::string& s);
std::string InterleaveName(int interleave);
Json SimulateConfigJson(const SimulateConfig& cfg);
// What `simulate` prints and writes: the rows (per array with cfg.by_array) and the line saying
// what was simulated; under --out simulate.{csv,json} (and simulate-arrays), run.json.
RunOutput SimulateOutput(const std::vector<std::unique_ptr<CacheSimulation>>& runs,
                         const SimulateConfig& cfg, bool per_sweep);
// With a machine: the summary (MachineSummaryTable) and a sentence per ordering, or with
// cfg.per_thread the per-thread rows; --csv and --json the per-thread rows; under --out
// simulate.{csv,json} (per thread), summary.csv and run.json.
RunOutput MachineOutput(const MachineSimulations& m, const SimulateConfig& cfg);

}  // namespace meshreuse
