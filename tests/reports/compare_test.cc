// The experiment runner on the tiny meshes, and the paper's averaged ratios on hand-made rows.
#include "reports/compare.h"

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace meshreuse {
namespace {

TEST(Compare, RowsPerMeshOrderingAndThreads) {
  CompareConfig cfg;
  cfg.meshes = {testing::DataPath("two_interior.node"), testing::DataPath("two_interior41.msh")};
  cfg.orderings = {"ori", "bfs", "rdr"};
  cfg.threads = {1, 2};
  cfg.repeat = 3;
  std::vector<std::string> progress;
  const std::vector<CompareRow> rows =
      RunCompare(cfg, [&](const std::string& s) { progress.push_back(s); });
  ASSERT_EQ(rows.size(), 12u);
  EXPECT_FALSE(progress.empty());
  for (const CompareRow& r : rows) {
    EXPECT_EQ(r.total_seconds.size(), 3u);
    EXPECT_EQ(r.sweeps.size(), 3u);
    EXPECT_EQ(r.median_total, Median(r.total_seconds));
    if (r.ordering == "ori" && r.threads == 1) {
      EXPECT_EQ(r.speedup_vs_ori1, 1.0);
    }
    if (r.ordering == "bfs") {
      EXPECT_EQ(r.gain_vs_bfs, 0.0);
    }
    EXPECT_GT(r.final_quality, 0.0);
  }
  EXPECT_EQ(CompareTable(rows).Rows(), 12u);
  EXPECT_EQ(CompareSummaryTable(rows).Rows(), 6u);
}

TEST(Compare, SummaryAveragesThePapersRatios) {
  auto row = [](const char* mesh, const char* ord, double t) {
    CompareRow r;
    r.mesh = mesh, r.ordering = ord, r.threads = 1, r.median_total = t;
    return r;
  };
  const std::vector<CompareRow> rows = {row("A", "ori", 2),   row("A", "bfs", 1),
                                        row("A", "rdr", 0.5), row("B", "ori", 4),
                                        row("B", "bfs", 4),   row("B", "rdr", 2)};
  // rdr: speedup mean(2/0.5, 4/2) = 3; T_bfs/T mean(2, 2) = 2; gain vs bfs mean(50%, 50%).
  EXPECT_EQ(CompareSummaryTable(rows).Csv(),
            "ordering,threads,meshes,speedup_vs_ori1,T_ori/T,T_bfs/T,gain_vs_ori_%,gain_vs_bfs_%\n"
            "ori,1,2,1.000,1.000,0.750,0.000,-50.000\n"  // gain mean(-100%, 0%)
            "bfs,1,2,1.500,1.500,1.000,25.000,0.000\n"
            "rdr,1,2,3.000,3.000,2.000,62.500,50.000\n");
}

TEST(Compare, MedianOfOddAndEven) {
  EXPECT_EQ(Median({3, 1, 2}), 2);
  EXPECT_EQ(Median({4, 1, 3, 2}), 2.5);
  EXPECT_TRUE(std::isnan(Median({})));
}

}  // namespace
}  // namespace meshreuse
