// The timing runner on the tiny mesh: rows per mesh x ordering x threads, every round recorded on
// both clocks after a warm-up, spreads that agree with the rounds, the reference's own speedup,
// --repeat auto within its cap; the summary's means on hand-made rows whose answers are known.
#include "reports/compare.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "reports/speedup.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

TEST(Compare, RowsPerMeshOrderingAndThreads) {
  CompareConfig cfg;
  cfg.meshes = {testing::DataPath("two_interior.node")};
  cfg.orderings = {"ori", "bfs", "rdr"};
  cfg.threads = {1, 2};
  cfg.repeat = 3;
  std::vector<std::string> progress;
  const CompareResult res = RunCompare(cfg, [&](const std::string& s) { progress.push_back(s); });
  const std::vector<CompareRow>& rows = res.rows;
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_FALSE(progress.empty());
  for (const CompareRow& r : rows) {
    ASSERT_EQ(r.rounds.size(), 3u);
    EXPECT_EQ(r.sweep.median, Median(r.Values(&CompareRound::sweep_wall)));
    EXPECT_EQ(r.total.median, Median(r.Values(&CompareRound::total_wall)));
    EXPECT_LE(r.sweep.min, r.sweep.median);
    EXPECT_GE(r.sweep.max, r.sweep.median);
    EXPECT_LE(r.sweep.lo, r.sweep.median);
    EXPECT_GE(r.sweep.hi, r.sweep.median);
    for (const CompareRound& c : r.rounds) {
      EXPECT_GT(c.sweeps, 0);
      EXPECT_GT(c.total_cpu, 0.0);  // thread CPU time of the sweeps, measured
      EXPECT_GE(c.order, 0.0);
    }
    if (r.ordering == "ori" && r.threads == 1) {
      EXPECT_EQ(SpeedupVerdict(r.speedup_vs_ori1), Verdict::kReference);
    } else {
      EXPECT_TRUE(std::isfinite(r.speedup_vs_ori1.lo));
    }
    if (r.ordering == "bfs") {
      EXPECT_TRUE(std::isnan(r.gain_vs_bfs.median));  // no gain of an ordering over itself
    }
    EXPECT_GT(r.final_quality, 0.0);
  }
  EXPECT_EQ(res.noise.cores, Cores());
  EXPECT_EQ(CompareTable(rows).Rows(), 6u);
  EXPECT_EQ(CompareSummaryTable(rows, 1).Rows(), 6u);
}

TEST(Compare, RepeatAutoStaysWithinItsCapAndFewerThanThreeIsRefused) {
  CompareConfig cfg;
  cfg.meshes = {testing::DataPath("two_interior.node")};
  cfg.orderings = {"ori", "bfs"};
  cfg.repeat_auto = true;
  cfg.repeat_cap = 4;
  for (const CompareRow& r : RunCompare(cfg).rows) {
    EXPECT_GE(r.rounds.size(), 3u);
    EXPECT_LE(r.rounds.size(), 4u);
  }
  cfg.repeat_auto = false;
  cfg.repeat = 2;
  EXPECT_THROW(RunCompare(cfg), UsageError);
  int repeat = 0, cap = 15;
  bool automatic = false;
  ParseRepeat("auto:20", &repeat, &automatic, &cap);
  EXPECT_TRUE(automatic);
  EXPECT_EQ(cap, 20);
  EXPECT_THROW(ParseRepeat("1", &repeat, &automatic, &cap), UsageError);
  EXPECT_THROW(ParseRepeat("auto:x", &repeat, &automatic, &cap), UsageError);
}

// The warm-up's length changes nothing a timed round records but its times: each timed round
// still smooths to convergence from the same start. A warm-up of no sweep is refused.
TEST(Compare, AShortWarmUpLeavesTheTimedRoundsWhole) {
  CompareConfig cfg;
  cfg.meshes = {testing::DataPath("plate41.msh")};
  cfg.orderings = {"ori", "rdr"};
  cfg.threads = {1};  // (two threads' Gauss-Seidel races: their sweeps vary from run to run)
  cfg.repeat = 3;
  cfg.warmup_sweeps = 100;
  const CompareResult whole = RunCompare(cfg);
  cfg.warmup_sweeps = 1;
  std::vector<std::string> progress;
  const CompareResult one = RunCompare(cfg, [&](const std::string& s) { progress.push_back(s); });
  ASSERT_EQ(whole.rows.size(), one.rows.size());
  for (size_t i = 0; i < one.rows.size(); ++i) {
    ASSERT_EQ(one.rows[i].rounds.size(), 3u);
    EXPECT_GT(whole.rows[i].rounds[0].sweeps, 1);  // a warm-up of one sweep is shorter
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(one.rows[i].rounds[k].sweeps, whole.rows[i].rounds[k].sweeps);
    EXPECT_EQ(one.rows[i].final_quality, whole.rows[i].final_quality);
  }
  bool said = false;
  for (const std::string& s : progress)
    said = said || s.find("smoothed 1 sweep(s)") != std::string::npos;
  EXPECT_TRUE(said);
  cfg.warmup_sweeps = 0;
  EXPECT_THROW(RunCompare(cfg), UsageError);
}

// Rows whose every round takes the same time: the ratios, and their intervals, are exact.
CompareRow Row(const char* mesh, const char* ord, double sweep_seconds) {
  CompareRow r;
  r.mesh = mesh, r.ordering = ord, r.threads = 1;
  for (int i = 0; i < 3; ++i) {
    CompareRound c;
    c.sweeps = 10;
    c.sweep_wall = c.sweep_cpu = sweep_seconds;
    c.total_wall = c.total_cpu = 10 * sweep_seconds;
    r.rounds.push_back(c);
  }
  return r;
}

TEST(Compare, SummaryAveragesThePapersRatios) {
  const std::vector<CompareRow> rows = {Row("A", "ori", 2),   Row("A", "bfs", 1),
                                        Row("A", "rdr", 0.5), Row("B", "ori", 4),
                                        Row("B", "bfs", 4),   Row("B", "rdr", 2)};
  // rdr: speedup mean(2/0.5, 4/2) = 3; T_bfs/T mean(2, 2) = 2; gain vs bfs mean(50%, 50%).
  const Json s = CompareSummaryTable(rows, 1).JsonValue();
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[2]["ordering"], "rdr");
  EXPECT_DOUBLE_EQ(s[2]["speedup_vs_ori1"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(s[2]["speedup_vs_ori1_lo"].get<double>(), 3.0);  // no spread: exact
  EXPECT_EQ(s[2]["speedup_vs_ori1_verdict"], "faster");
  EXPECT_DOUBLE_EQ(s[2]["T_bfs/T"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(s[2]["gain_vs_bfs_pct"].get<double>(), 50.0);
  EXPECT_DOUBLE_EQ(s[0]["gain_vs_bfs_pct"].get<double>(), -50.0);  // ori: mean(-100%, 0%)
  EXPECT_EQ(s[0]["gain_vs_bfs_pct_verdict"], "slower");  // the mean, exact here, is below 0
  EXPECT_EQ(s[0]["speedup_vs_ori1_verdict"], "reference");
  EXPECT_TRUE(s[1]["gain_vs_bfs_pct"].is_null());  // none over itself
}

// A busy machine: the wall clock says the two orderings tie, the CPU clock that rdr costs half.
TEST(Compare, TheCpuClockRanksByTheWorkTheSweepsCost) {
  std::vector<CompareRow> rows = {Row("A", "ori", 2), Row("A", "rdr", 2)};
  for (CompareRound& c : rows[1].rounds) c.sweep_cpu = 1, c.total_cpu = 10;
  rows[1].rounds[0].sweep_wall = 1.9, rows[1].rounds[2].sweep_wall = 2.1;
  EXPECT_DOUBLE_EQ(Speedup(&rows[0], &rows[1], 1, TimeClock::kWall).median, 1.0);
  EXPECT_EQ(SpeedupVerdict(Speedup(&rows[0], &rows[1], 1, TimeClock::kWall)),
            Verdict::kNotDistinguishable);
  EXPECT_DOUBLE_EQ(Speedup(&rows[0], &rows[1], 1, TimeClock::kCpu).median, 2.0);
  const Json cpu = CompareSummaryTable(rows, 1, TimeClock::kCpu).JsonValue();
  EXPECT_DOUBLE_EQ(cpu[1]["speedup_vs_ori1"].get<double>(), 2.0);
  EXPECT_EQ(cpu[1]["speedup_vs_ori1_verdict"], "faster");
  EXPECT_EQ(ParseClock("cpu"), TimeClock::kCpu);
  EXPECT_EQ(std::string(ClockName(ParseClock("wall"))), "wall");
  EXPECT_THROW(ParseClock("cycles"), UsageError);
}

}  // namespace
}  // namespace meshreuse
