// Many-core simulation runs summarised (the report's many-core part and `simulate --machine`): a
// run is a mesh x ordering x placement x thread count, its warm (last) sweep's counts summed over
// the threads and the cost model's cycles C(p) of its slowest thread (the paper's equation 2 per
// thread, at both ends of the machine's latency ranges). From runs: Speedup(p) = C_ori(1) /
// C_ord(p), the per-ordering speedup C_ord(1) / C_ord(p) and Gain(p) = (C_ref(p) - C_ord(p)) /
// C_ref(p) against ORI and BFS, the quantities the report's predicted_speedup averages over meshes
// and `simulate --machine` prints per mesh, computed in one place so they agree.
#pragma once

#include <string>
#include <vector>

#include "analysis/multicore_sim.h"
#include "core/table.h"

namespace meshreuse {

struct MachineRun {
  std::string mesh, ordering, placement;
  int threads = 1;
  bool prefetch = false;
  ThreadStats total;                       // summed over threads
  double cycles_low = 0, cycles_high = 0;  // the slowest thread's, at each latency end
  std::vector<std::string> level_names;
};

// The warm (last) sweep of `sim` as a run; the whole run where the stream has no sweeps (another
// tool's trace).
MachineRun CollectMachineRun(const MulticoreSimulation& sim, const std::string& mesh,
                             const std::string& ordering, bool prefetch);

// The run of (mesh, ordering, placement, threads, prefetch), any placement at one thread; or
// nullptr.
const MachineRun* FindMachineRun(const std::vector<MachineRun>& runs, const std::string& mesh,
                                 const std::string& ordering, const std::string& placement,
                                 int threads, bool prefetch = false);

// A run's predicted ratios, [0] at the low and [1] at the high latency end; NaN where a run they
// need is missing (ori at one thread, the ordering at one thread, ori or bfs at p).
struct PredictedRatios {
  double speedup[2], self_speedup[2], gain_vs_ori_pct[2], gain_vs_bfs_pct[2];
};
PredictedRatios Predict(const std::vector<MachineRun>& runs, const std::string& mesh,
                        const std::string& ordering, const std::string& placement, int threads);

// `simulate --machine`'s answer: a row per mesh x ordering x placement x threads with C(p),
// Speedup(p), the per-ordering speedup and Gain(p) against ORI and BFS at both latency ends (the
// same cells as the report's predicted_speedup for one mesh), misses per level, memory accesses
// and their remote share, coherence misses and their share of the first level's misses.
Table MachineSummaryTable(const std::vector<MachineRun>& runs);
// One sentence per mesh x ordering at the largest thread count: its speedup and gain, and what
// drives them against BFS (or ORI): coherence misses, last-level misses, remote memory.
std::vector<std::string> MachineSentences(const std::vector<MachineRun>& runs);

}  // namespace meshreuse
