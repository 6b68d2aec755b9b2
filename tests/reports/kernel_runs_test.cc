// The kernels part's simulated quantities (reports/kernel_runs.h) against their definitions: per
// kernel and ordering, q50 and q90 of the line reuse distances of every traced access equal the
// whole exact analysis (ReuseAnalysis) of the kernel's stream, whether the short-distance
// quantiles answered (the default depth) or the stream went again through the whole analysis
// (depth 1: every q90 beyond it); the random ordering puts q90 beyond the default depth, the
// others below, so both paths run at the default too. Misses and floor the same at every depth.
#include "reports/kernel_runs.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "analysis/reuse_analysis.h"
#include "core/kernels/kernel.h"
#include "core/orderings/registry.h"
#include "reports/validation.h"
#include "tests/test_util.h"
#include "tracer/access_stream.h"

namespace meshreuse {
namespace {

TEST(KernelRuns, LineQuantilesEqualTheWholeAnalysisOnEitherPath) {
  const Mesh base = testing::Synthetic(60, 50, 3, 11);
  KernelRunsConfig c;
  c.kernels = {"smart-laplacian", "edge-swap", "spmv"};
  c.orderings = c.labels = {"ori", "random", "rdr"};
  c.timing = false;
  c.cache = ParseCacheSpec("L1=4K/4,L2=32K/8");
  const uint32_t depth = c.quantile_depth;
  std::vector<KernelRun> atd, at1;
  MeasureKernels(c, "m", base, &atd, [](const std::string&) {});
  c.quantile_depth = 1;
  MeasureKernels(c, "m", base, &at1, [](const std::string&) {});
  ASSERT_EQ(atd.size(), 9u);
  ASSERT_EQ(at1.size(), 9u);
  bool beyond = false, below = false;
  for (size_t i = 0; i < atd.size(); ++i) {
    const KernelRun& r = atd[i];
    // The reference: the same stream into the whole analysis, by hand.
    Mesh laid;
    ApplyPermutationInto(base, ComputeOrdering(r.ordering, base, c.seed), c.triangle_order, &laid);
    ReuseOptions ro;
    ro.granularity = Granularity::kLine;
    ro.profile = false;
    ReuseAnalysis exact(ro);
    StreamMesh(laid, ExactSweeps(c.traced_sweeps), "m", r.ordering, exact, &ParseKernel(r.kernel));
    const ReuseHistogram& h = exact.line(0)->hist;
    EXPECT_EQ(r.q50, h.Quantile(0.5)) << r.kernel << " " << r.ordering;
    EXPECT_EQ(r.q90, h.Quantile(0.9)) << r.kernel << " " << r.ordering;
    EXPECT_EQ(at1[i].q50, r.q50) << r.kernel << " " << r.ordering;
    EXPECT_EQ(at1[i].q90, r.q90) << r.kernel << " " << r.ordering;
    EXPECT_EQ(at1[i].misses, r.misses);
    EXPECT_EQ(at1[i].floor, r.floor);
    (r.q90 >= depth ? beyond : below) = true;
  }
  EXPECT_TRUE(beyond);
  EXPECT_TRUE(below);
}

// The Laplacian's simulated part read from Table 3's validation of the same mesh and orderings
// (KernelRunsConfig::laplacian, as the report hands it) equals the one the kernels part streams
// itself: accesses, each level's misses and floor of the last sweep, q50 and q90. A validation
// that does not match (another sweep count) is not used; nor is one for another kernel's rows.
TEST(KernelRuns, LaplacianFromTable3sValidationEqualsItsOwnSimulation) {
  const Mesh base = testing::Synthetic(60, 50, 3, 11);
  KernelRunsConfig c;
  c.kernels = {"laplacian", "smart-laplacian"};
  c.orderings = c.labels = {"ori", "random", "rdr"};
  c.timing = false;
  c.cache = ParseCacheSpec("L1=4K/4,L2=32K/8");
  std::vector<KernelRun> own, read;
  MeasureKernels(c, "m", base, &own, [](const std::string&) {});
  ValidationConfig vc;
  vc.mesh_name = "m";
  vc.orderings = {};
  for (const std::string& o : c.orderings) vc.orderings.push_back(ParseOrderingSpec(o));
  vc.iterations = c.traced_sweeps;
  vc.cache = c.cache;
  vc.line_bytes = c.line_bytes;
  vc.counter_events.clear();
  const std::vector<OrderingValidation> v = RunValidation(base, vc);
  ASSERT_EQ(v.size(), 3u);
  for (const OrderingValidation& x : v) c.laplacian.push_back(&x);
  MeasureKernels(c, "m", base, &read, [](const std::string&) {});
  ASSERT_EQ(own.size(), 6u);
  ASSERT_EQ(read.size(), 6u);
  for (size_t i = 0; i < own.size(); ++i) {
    const std::string what = own[i].kernel + " " + own[i].ordering;
    EXPECT_GT(own[i].accesses, 0u) << what;
    EXPECT_EQ(read[i].accesses, own[i].accesses) << what;
    EXPECT_EQ(read[i].misses, own[i].misses) << what;
    EXPECT_EQ(read[i].floor, own[i].floor) << what;
    EXPECT_EQ(read[i].q50, own[i].q50) << what;
    EXPECT_EQ(read[i].q90, own[i].q90) << what;
  }
  // The validation's sweeps are the rows' source: with its last sweep's counts changed, the
  // Laplacian's rows change and the others do not; with another sweep count, none does.
  std::vector<OrderingValidation> changed = v;
  for (OrderingValidation& x : changed) ++x.sweeps.back()[0][0].misses;
  for (size_t o = 0; o < 3; ++o) c.laplacian[o] = &changed[o];
  std::vector<KernelRun> bumped;
  MeasureKernels(c, "m", base, &bumped, [](const std::string&) {});
  for (size_t i = 0; i < own.size(); ++i)
    EXPECT_EQ(bumped[i].misses[0], own[i].misses[0] + (own[i].kernel == "laplacian" ? 1 : 0));
  for (OrderingValidation& x : changed) x.iterations = c.traced_sweeps + 1;
  bumped.clear();
  MeasureKernels(c, "m", base, &bumped, [](const std::string&) {});
  for (size_t i = 0; i < own.size(); ++i) EXPECT_EQ(bumped[i].misses, own[i].misses);
}

// The timed rounds keeping every layout and set-up from one round to the next, or none (a budget
// of 0 bytes: each made again in every round), or the layouts alone: the same runs (each round's
// sweeps and the kernel's final measure).
TEST(KernelRuns, TimedRoundsKeepingLayoutsAndSetUpsRunTheSameSweeps) {
  const Mesh base = testing::Synthetic(40, 30, 2, 5);
  KernelRunsConfig c;
  c.kernels = {"smart-laplacian", "edge-swap", "assembly"};
  c.orderings = c.labels = {"ori", "bfs", "random"};
  c.cache = ParseCacheSpec("L1=4K/4");
  c.rounds = 2, c.sweeps = 3;
  std::vector<std::vector<KernelRun>> runs(3);
  for (int budget = 0; budget < 3; ++budget) {
    c.held_bytes = budget == 0 ? (uint64_t{1} << 30) : budget == 1 ? 0 : 3 * 200000;
    MeasureKernels(c, "m", base, &runs[budget], [](const std::string&) {});
  }
  ASSERT_EQ(runs[0].size(), 9u);
  for (int budget = 1; budget < 3; ++budget) {
    ASSERT_EQ(runs[budget].size(), runs[0].size());
    for (size_t i = 0; i < runs[0].size(); ++i) {
      const CompareRow &a = runs[0][i].time, &b = runs[budget][i].time;
      EXPECT_EQ(a.final_quality, b.final_quality) << runs[0][i].kernel << " " << i;
      ASSERT_EQ(a.rounds.size(), 2u);
      ASSERT_EQ(b.rounds.size(), 2u);
      for (size_t r = 0; r < 2; ++r) EXPECT_EQ(a.rounds[r].sweeps, b.rounds[r].sweeps);
    }
  }
}

}  // namespace
}  // namespace meshreuse
