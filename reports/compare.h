// The experiment runner behind `meshreuse compare`: meshes x orderings x thread counts. Each mesh
// is read once and each ordering computed once (ordering and apply times measured separately); then
// `repeat` rounds each smooth every (ordering, threads) pair once from the same start, so noise on
// a shared machine hits all pairs alike. It holds the mesh, one working copy and the permutations:
// the working copy is reordered from the mesh before every run. Times are medians over the rounds.
// The paper's formulas:
//   Speedup(ord, p) = T_ori(1) / T_ord(p)          Gain(ord vs bfs, p) = (T_bfs(p) - T_ord(p)) /
//   T_bfs(p)
// with T the total smoothing time to convergence.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/permutation.h"
#include "core/smoother.h"
#include "reports/table.h"

namespace meshreuse {

struct CompareConfig {
  std::vector<std::string> meshes;
  std::vector<std::string> orderings = {"ori", "bfs", "rdr", "random"};
  std::vector<int> threads = {1};
  int repeat = 5;
  uint64_t seed = 1;
  SmoothOptions smooth;  // tol, max_iters, mode; threads are taken from `threads`
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  // PAPI events to count around the sweeps of every run (empty: none). Events this machine
  // cannot count are dropped; `counter_note` then says why (counters_available: any left).
  std::vector<std::string> counter_events;
};

struct CompareRow {
  std::string mesh, ordering;
  int threads = 1;
  int32_t vertices = 0, triangles = 0;
  double order_seconds = 0;
  // Applying the ordering to the mesh: the median over the runs, each into the reused working copy
  // (what a code that reorders its own arrays pays), and the first apply, into new arrays (page
  // faults included).
  double apply_seconds = 0, apply_first_seconds = 0;
  EdgeSpan span;                      // locality of the ordering (permutation.h)
  std::vector<int> sweeps;            // per round
  std::vector<double> total_seconds;  // per round
  std::vector<double> sweep_seconds;  // every sweep of every round
  double final_quality = 0;           // of the first round
  double median_total = 0, median_sweep = 0;
  double speedup_vs_ori1 = 0;  // NaN when the run has no ori on one thread
  double gain_vs_bfs = 0;      // NaN when the run has no bfs at this thread count
  // Counters (CompareConfig::counter_events that count here): per event, the sum over threads
  // and sweeps of each round, and its median over the rounds.
  std::vector<std::string> counter_events;
  std::vector<std::vector<long long>> counters;  // [round][event]
  std::vector<double> counter_medians;           // [event]
};

// Why configured counters are not (all) recorded here, empty if they are; and whether any is.
struct CounterNote {
  bool available = false;
  std::string note;
};
CounterNote ProbeCounters(const std::vector<std::string>& events);

// `progress` gets progress lines; `warn` the readers' warnings (dropped vertices, skipped
// elements), which a caller should show even when progress is silenced.
std::vector<CompareRow> RunCompare(const CompareConfig& cfg,
                                   const std::function<void(const std::string&)>& progress = {},
                                   const std::function<void(const std::string&)>& warn = {});

double Median(std::vector<double> v);
Table CompareTable(const std::vector<CompareRow>& rows);
// The paper's headline numbers, averaged (arithmetic mean) over the meshes, per ordering and thread
// count: Speedup T_ori(1)/T_ord(p), and the ratios and gains against ori and bfs at the same p.
Table CompareSummaryTable(const std::vector<CompareRow>& rows);
std::string CompareJson(const std::vector<CompareRow>& rows);  // a JSON array

}  // namespace meshreuse
