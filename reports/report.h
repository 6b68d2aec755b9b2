// The paper's experiment as one run (`meshreuse report`, behind scripts/reproduce.sh): meshes x
// orderings x thread counts x repetitions from one configuration, writing every table of the
// paper with its published values beside ours, the data behind every figure, run.json and a
// results README.md into one folder.
//
// What it runs, per mesh (each read once; each ordering computed once per step):
//   - Table 1: vertices, triangles (and interior vertices) beside the paper's;
//   - Table 2: the first sweep's element stream (66-byte vertex records, the paper's model)
//     through the exact LRU analyzer: quantiles 50/75/90/100%, accesses, mean, the histogram;
//   - Figure 1 (one mesh, random/ori/bfs): the reuse distance of every access of the first sweep,
//     binned in time x log2 distance so ten million points stay readable;
//   - the profile figure (one mesh, `profile_sweeps` sweeps): mean distance in 100 steps a sweep;
//   - Table 3 and the miss rates: RunValidation (validation.h), the simulator or counters;
//   - execution times (RunCompare, compare.h): to convergence, per sweep, on each thread count,
//     the paper's speedups and gains, and the reordering's cost in ORI sweeps.
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

namespace meshreuse {

struct ReportConfig {
  std::vector<std::string> meshes;  // mesh files (.node, .msh)
  std::vector<std::string> orderings = {"ori", "bfs", "rdr"};
  std::vector<int> threads = {1};
  int repeat = 3;
  uint64_t seed = 1;
  SmoothOptions smooth;  // tol, max_iters (threads come from `threads`)
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  std::vector<CacheLevel> levels;  // with ways; empty: the paper's Westmere-EX
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
  std::vector<std::string> counter_events = {"PAPI_L1_DCM", "PAPI_L2_DCM", "PAPI_L3_TCM"};
  std::vector<std::string> command_line;  // for run.json
  std::string label;                      // e.g. "quick", "full", "scale": in run.json and README
};

// Throws std::invalid_argument for a configuration that cannot run (no mesh, no ordering, a bad
// thread count, a duplicate mesh name), before any work.
void CheckReportConfig(const ReportConfig& cfg);

// Writes into `out_dir` (created; must not hold a previous report's files): tables/*.{csv,md,tex},
// data/*.csv (figures' input), run.json, README.md. Returns the README's path. Files are written
// atomically. `progress` gets "step, mesh, ordering, elapsed, remaining" lines; `warn` the
// readers' warnings.
std::string RunReport(const ReportConfig& cfg, const std::string& out_dir,
                      const std::function<void(const std::string&)>& progress = {},
                      const std::function<void(const std::string&)>& warn = {});

// The figures the plotting scripts make from a report's data (scripts/plot_report.py), as
// "name: what" lines for the README; the files are figures/<name>.{png,pdf}.
struct FigureSpec {
  std::string name, title;
};
std::vector<FigureSpec> ReportFigures(const ReportConfig& cfg);

}  // namespace meshreuse
