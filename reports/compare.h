// The experiment runner behind `meshreuse compare` (and the report's timing): meshes x orderings x
// thread counts, under the timing discipline of timing.h. Per mesh: the mesh read once; an untimed
// warm-up of every (ordering, threads) pair (computing and applying the ordering, smoothing to
// convergence); then rounds, each computing every ordering and smoothing every pair once from the
// same start, so noise on a shared machine hits all pairs alike. Each round records per pair the
// wall and the thread CPU time of the sweeps (per thread, summed), the ordering's and the apply's
// time. Rounds: `repeat` (at least 3), or with `repeat_auto` as many as it takes for every
// speedup's interval to be within +-2% (at least 3, at most `repeat_cap`). Every timed cell then
// carries its spread (min, median, max, 95% interval of the median), and Speedup and Gain
// (speedup.h) are ratios of per-sweep medians with their intervals.
// Memory: the mesh, one working copy (reordered from the mesh before every run) and a permutation
// per ordering, not a reordered mesh per ordering.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/kernels/kernel.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "core/table.h"
#include "reports/output.h"
#include "reports/run_info.h"
#include "reports/timed_runs.h"
#include "reports/timing.h"

namespace meshreuse {

struct CompareConfig : TimingOptions {
  // TimingOptions: threads, rounds, the clock, the smoother's options, the triangle order.
  std::vector<std::string> meshes;
  std::vector<std::string> orderings = {"ori", "bfs", "rdr", "random"};
  std::string kernel = kPaperKernel;  // core/kernels/: what is timed
  uint64_t seed = 1;                  // seeded orderings and the bootstrap
  // PAPI events to count around the sweeps of every run (empty: none); events this machine
  // cannot count are dropped.
  std::vector<std::string> counter_events;
};

// How --repeat auto ended on a mesh: settled (every speedup against ori x1 within +-2%) or at
// its cap, with the widest interval left.
struct RepeatAutoEnd {
  std::string mesh;
  int rounds = 0;
  bool settled = false;
  double widest = NAN;                  // the largest relative half-width of a speedup's interval
  std::string widest_row;               // "bfs x2"
  std::string Sentence(int cap) const;  // said when not settled
  Json ToJson() const;
};

struct CompareResult {
  std::vector<CompareRow> rows;
  Noise noise;
  std::vector<RepeatAutoEnd> repeat_auto;  // one per mesh under --repeat auto
};

// `progress` gets progress lines; `warn` the readers' warnings (dropped vertices, skipped
// elements), which a caller should show even when progress is silenced.
CompareResult RunCompare(const CompareConfig& cfg,
                         const std::function<void(const std::string&)>& progress = {},
                         const std::function<void(const std::string&)>& warn = {});

// One row per mesh x ordering x threads: sweeps, final quality, edge span, the spreads of the
// ordering's, apply's, per-sweep (wall and CPU) and total times, CPU/wall, CV, Speedup and Gain
// with their intervals and verdicts.
Table CompareTable(const std::vector<CompareRow>& rows);
// The same for people: medians with their intervals in brackets, the verdicts.
// The printed table: the per-sweep time with its interval on the chosen clock, the other clock's
// median beside it.
Table CompareTextTable(const std::vector<CompareRow>& rows, TimeClock clock);
// "5" -> {5, false, 15}; "auto" -> {3, true, 15}; "auto:20" -> {3, true, 20}. UsageError below 3.
void ParseRepeat(const std::string& text, int* repeat, bool* automatic, int* cap);
// The paper's headline numbers per ordering and thread count, averaged over the meshes (with
// intervals from resampling every mesh's rounds): Speedup T_ori(1)/T, T_ori/T and T_bfs/T at the
// same p, and the gains against ori and bfs; verdicts.
Table CompareSummaryTable(const std::vector<CompareRow>& rows, uint64_t seed,
                          TimeClock clock = TimeClock::kWall);
// Its medians and verdicts for people.
Table CompareSummaryTextTable(const Table& summary);
Json CompareJson(const std::vector<CompareRow>& rows);  // an array, one object per row
Json CompareConfigJson(const CompareConfig& cfg);
// What `compare` prints and writes: the rows and the summary over the meshes (--json: seed, noise,
// rows and summary; --csv: the rows); under --out compare.{csv,md}, summary.{csv,md},
// compare.json and run.json.
RunOutput CompareOutput(const CompareResult& result, const CompareConfig& cfg);

}  // namespace meshreuse
