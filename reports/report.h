// The paper's experiment as one run (`meshreuse report`, behind scripts/reproduce.sh): meshes x
// orderings x thread counts x repetitions from one configuration, writing every table of the
// paper with its published values beside ours, the data behind every figure, run.json, a
// manifest of what was written (manifest.json: the plotting script and the checker read it) and
// a results README.md into one folder.
//
// What it measures, per mesh (each read once; report_data.h):
//   - Table 1: vertices, triangles (and interior vertices);
//   - Table 2: the first sweep's element stream (66-byte vertex records, the paper's model)
//     through the exact LRU analyzer; Figure 1 (one mesh, random/ori/bfs): every access's
//     distance, binned in time x log2 distance; the profile (one mesh, `profile_sweeps` sweeps);
//   - Table 3 and the miss rates: RunValidation (validation.h), the simulator or counters;
// then the execution times (RunCompare, compare.h). What it writes is declared once, in
// report_outputs.h: each table, data file and figure one line, each builder one file in
// reports/outputs/.
// Non-timing outputs (tables 1-3, misses, the figure data) depend only on the configuration and
// the binary: the same configuration gives them byte for byte (reports/report_test.cc). Timing
// outputs are medians over `repeat` interleaved rounds.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "reports/compare.h"
#include "reports/log.h"

namespace meshreuse {

struct ReportConfig : TimingOptions {
  // TimingOptions: the timed runs' threads, rounds (3 by default here), clock, the smoother's
  // options and the triangle order.
  ReportConfig() { repeat = 3; }
  std::vector<std::string> meshes;  // mesh files (.node, .msh)
  std::vector<std::string> orderings = {"ori", "bfs", "rdr"};
  uint64_t seed = 1;
  CacheSpec cache = ParseCacheSpec("westmere-ex");  // with ways
  uint32_t element_bytes = 66, line_bytes = 64;
  int validate_sweeps = 2;  // traced sweeps for Table 3 and the miss rates
  int profile_sweeps = 8;
  // Figure meshes by short name ("ocean"); a name not among the meshes skips its figure, and an
  // empty one too. Figure 1's orderings are computed for it whether or not they are in
  // `orderings`.
  std::string figure1_mesh = "ocean", profile_mesh = "carabiner";
  std::vector<std::string> figure1_orderings = {"random", "ori", "bfs"};
  int figure1_time_bins = 400;
  bool timing = true;  // false: no RunCompare (the non-timing tables only; tests)
  // The many-core part (the paper's Figure 11 and its 32-core claims, simulated): each mesh x
  // ordering streamed at every thread count of `machine_threads` (a visit of each thread per
  // turn) through `machine` with both placements, `machine_sweeps` sweeps of which the last
  // (warm) is counted; and at one thread with a next-line prefetcher at `prefetch_levels`
  // (Table 3's gap). "": no many-core part. Figure 11 draws carabiner, crake and dialog (the
  // paper's), or the first three meshes when they are absent (scripts/plot_machine.py).
  std::string machine = "westmere-ex";
  std::vector<int> machine_threads = {1, 2, 4, 8, 16, 24, 32};
  int machine_sweeps = 2;
  std::string prefetch_levels = "L1,L2";
  std::vector<std::string> counter_events = {"PAPI_L1_DCM", "PAPI_L2_DCM", "PAPI_L3_TCM"};
  std::vector<std::string> command_line;  // for run.json
  std::string label;                      // e.g. "quick", "full", "scale": in run.json and README
  // A compare.csv measured elsewhere (reports/measured.h), drawn beside the many-core
  // prediction; "": none.
  std::string measured;
  // The kernels part (reports/kernel_runs.h): each of `kernels` in each of `kernel_orderings` on
  // every mesh, simulated (`validate_sweeps` sweeps through `cache`) and timed (`kernel_sweeps`
  // sweeps per run, `repeat` rounds, one thread). local-opt is left out by default: a sweep of it
  // costs about ten Laplacian sweeps, and the full run keeps its time. Empty: no kernels part.
  std::vector<std::string> kernels = {"laplacian", "smart-laplacian", "untangle", "edge-swap",
                                      "assembly",  "spmv"};
  std::vector<std::string> kernel_orderings = {"ori", "bfs", "rdr", "grid-wave", "rcm", "hilbert"};
  int kernel_sweeps = 5;
  // Phases before the report (scripts/reproduce.sh: setup, build, meshing), "NAME WALL CPU" per
  // line: put first in the README's and run.json's breakdown of the time.
  std::string prior_phases;
};

// Throws UsageError for a configuration that cannot run (no mesh, no ordering, a bad thread
// count, a duplicate mesh name, a missing permutation file), before any work.
void CheckReportConfig(const ReportConfig& cfg);

// Writes into `out_dir` (created; must not hold a previous report's files): tables/*.{csv,md,tex},
// data/*, run.json, manifest.json, README.md. Returns the README's path. Files are written
// atomically. `log` gets "step, mesh, ordering, elapsed, remaining" lines and the readers'
// warnings.
// `figures`, when given, draws the figures once the tables and data are written (timed with the
// rest, before README.md and run.json).
std::string RunReport(const ReportConfig& cfg, const std::string& out_dir, const Log& log,
                      const std::function<void()>& figures = {});

}  // namespace meshreuse
