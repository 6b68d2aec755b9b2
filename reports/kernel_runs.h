// The report's kernels part (issue 41: the paper's conjecture that its ordering helps "mesh
// untangling, constraint mesh smoothing, and mesh swapping"): per mesh, each kernel of
// core/kernels/ in each ordering, simulated and timed on one thread.
//   - simulated: `traced_sweeps` sweeps streamed through the cache levels (analysis/cache_sim.h),
//     the sweep footprint (the floor no layout can beat, analysis/sweep_footprint.h) and the line
//     distances' quantiles (analysis/line_quantiles.h, exact below `quantile_depth` lines; a
//     stream whose quantile lies beyond is streamed again into the whole exact line-level reuse
//     analysis); the last (warm) sweep's misses and floor, the quantiles of every traced access
//     (the paper's Laplacian's read from Table 3's validation of the same stream where the caller
//     hands it: KernelRunsConfig::laplacian);
//   - timed: after an untimed warm-up (each kernel once), `rounds` rounds, each running every
//     kernel in every ordering once from the same layout (so noise hits all alike, as compare's
//     rounds), each run exactly `sweeps` sweeps: the per-sweep median of each run, its spread
//     over the rounds, and the speedups against ORI and BFS of the same kernel with their
//     intervals (speedup.h).
// Each ordering is computed and laid out once per mesh (while the layouts fit held_bytes); every
// simulation and timed run starts from a copy of its ordering's layout. The simulations run side
// by side on the host's cores, the timed runs one at a time.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "core/mesh.h"
#include "core/permutation.h"
#include "reports/phase_times.h"
#include "reports/timed_runs.h"
#include "reports/timing.h"
#include "reports/validation.h"

namespace meshreuse {

struct KernelRunsConfig {
  std::vector<std::string> kernels;
  std::vector<std::string> orderings;  // specs (a mesh's own file:PATH made already)
  std::vector<std::string> labels;     // as the tables name them, one per ordering
  int sweeps = 5;                      // timed sweeps per run
  int traced_sweeps = 2;               // simulated sweeps; the last is counted
  int rounds = 3;
  // The warm-up round's sweeps a run (at most `sweeps`), the timed runs' default (timed_runs.h).
  int warmup_sweeps = TimingOptions().warmup_sweeps;
  bool timing = true;
  TimeClock clock = TimeClock::kWall;
  uint64_t seed = 1;
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  CacheSpec cache;
  uint32_t line_bytes = 64;
  // The line distances found exactly without the whole LRU stack: q50 and q90 below it need one
  // stream (the paper's meshes and orderings: q90 <= 22 lines; one `--quick` row has 36), above
  // it a second.
  uint32_t quantile_depth = 32;
  // What the timed rounds keep from one round to the next (every ordering's layout, then the
  // kernels' set-ups) within this many bytes; the rest is made again each round (the same runs).
  uint64_t held_bytes = uint64_t{1} << 30;
  // Per ordering, where the caller has it (else empty or null): the paper's Laplacian sweep's
  // validation of this mesh in this ordering, Table 3's (reports/validation.h), made with these
  // traced_sweeps, cache, line_bytes, seed and triangle_order on one thread: the same stream the
  // kernel "laplacian" would trace here. That kernel's simulated part is then read from it (the
  // simulator's last sweep, the footprint's floor, the line quantiles) instead of streamed again.
  std::vector<const OrderingValidation*> laplacian;
};

struct KernelRun {
  std::string mesh, kernel, ordering;  // ordering: its label
  // The timed rounds: rounds (sweep_wall, sweep_cpu: per-sweep medians), sweep and sweep_cpu
  // spreads, speedup_vs_ori1 = T_ori / T and gain_vs_bfs, both against the same kernel on one
  // thread; final_quality: the kernel's measure after the first round.
  CompareRow time;
  std::vector<uint64_t> misses, floor;  // per cache level, the last traced sweep
  uint64_t accesses = 0;                // loads and stores of the last traced sweep
  uint64_t q50 = 0, q90 = 0;            // line-level reuse distances, every traced access
};

// Appends one row per kernel x ordering of `base` (named `mesh`) to `out`; `say` gets progress.
// `phases` (optional) gets the simulated and the timed part's wall and CPU seconds, each as a
// phase inside the caller's.
void MeasureKernels(const KernelRunsConfig& cfg, const std::string& mesh, const Mesh& base,
                    std::vector<KernelRun>* out, const std::function<void(const std::string&)>& say,
                    PhaseTimes* phases = nullptr);

}  // namespace meshreuse
