// The runner behind `meshreuse smooth`: each mesh read, laid out in an ordering (reordering timed
// apart from smoothing), smoothed (core/smoother.h) with PAPI counters around the sweeps where the
// machine has them; optionally the smoothed mesh written. Tables of the runs and of every sweep.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/papi_counters.h"
#include "core/kernels/kernel.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "core/table.h"
#include "reports/log.h"
#include "reports/output.h"
#include "reports/run_info.h"

namespace meshreuse {

struct SmoothConfig {
  std::vector<std::string> meshes;
  std::string ordering = "ori";
  std::string kernel = kPaperKernel;  // core/kernels/: what a sweep does
  uint64_t seed = 1;
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  SmoothOptions smooth;                     // region is set by the runner (counters)
  std::vector<std::string> counter_events;  // PAPI events around the sweeps; empty: none
  std::string output;                       // write the smoothed mesh here (one mesh only)
  // Visit the interior vertices in this file's order (core/visit_order.h), storage unchanged:
  // the serial sweep a distributed ordered run equals. Ordering ori, one mesh.
  std::string visit_order;
};

struct SmoothRun {
  std::string mesh, ordering, kernel = kPaperKernel;
  int32_t vertices = 0, triangles = 0;
  int threads = 1;
  UpdateMode mode = UpdateMode::kGaussSeidel;
  double reorder_seconds = 0;
  SmoothResult result;
  std::vector<std::string> events;                 // counters that counted
  std::vector<long long> sums;                     // per event, all threads and sweeps
  std::vector<std::vector<long long>> per_thread;  // [thread][event]
  std::vector<std::string> written;                // files of the smoothed mesh
};

// Called as the run goes, outside the timed region: a mesh laid out and about to be smoothed, each
// sweep (per-sweep printing), the mesh done.
struct SmoothHooks {
  std::function<void(const SmoothRun&)> start, done;
  std::function<void(const SweepRecord&)> sweep;
};

void CheckSmoothConfig(const SmoothConfig& cfg);  // UsageError
std::vector<SmoothRun> RunSmooth(const SmoothConfig& cfg, const Log& log,
                                 const SmoothHooks& hooks = {});
double MedianSweepSeconds(const SmoothRun& r);
Table SmoothSummaryTable(const std::vector<SmoothRun>& runs);
Table SmoothSweepTable(const std::vector<SmoothRun>& runs);
Json SmoothResultsJson(const std::vector<SmoothRun>& runs);
Json SmoothConfigJson(const SmoothConfig& cfg, const CounterNote& counters);
// What `smooth` prints and writes once the runs are done (each run's sweeps are printed as they
// come, by the CLI's hooks): the summary of several runs; --json the results and sweeps, --csv the
// sweeps; under --out summary.{csv,md}, sweeps.csv and run.json.
RunOutput SmoothOutput(const std::vector<SmoothRun>& runs, const SmoothConfig& cfg,
                       const CounterNote& counters);

}  // namespace meshreuse
