// Where a run's time went (reports/phase_times.h): phases in the order first seen, re-entered
// phases adding up, a phase listed when it starts (before what runs inside it), the total leaving
// out the phases marked as inside another, and the prior-phases file read or refused by line.
#include "reports/phase_times.h"

#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "core/error.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

TEST(PhaseTimes, OrderSumsAndTheTotal) {
  PhaseTimes t;
  t.Add("build", 10, 18);
  {
    const PhaseTimes::Scope outer = t.Time("simulation");
    t.Add("simulation, 4 threads", 3, 2, "inside the one above");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  t.Add("build", 5, 2);
  ASSERT_EQ(t.phases().size(), 3u);
  EXPECT_EQ(t.phases()[0].name, "build");
  EXPECT_DOUBLE_EQ(t.phases()[0].wall, 15);
  EXPECT_DOUBLE_EQ(t.phases()[0].cpu, 20);
  EXPECT_EQ(t.phases()[1].name, "simulation");  // listed when it started
  EXPECT_GE(t.phases()[1].wall, 0.02);
  EXPECT_EQ(t.phases()[2].note, "inside the one above");
  const std::string md = t.Markdown();
  // The total is build + simulation, not the phase inside the simulation.
  const double total = 15 + t.phases()[1].wall;
  char want[64];
  std::snprintf(want, sizeof want, "**%.1f s**", total);
  EXPECT_NE(md.find(want), std::string::npos) << md;
  EXPECT_NE(md.find("| simulation, 4 threads (inside the one above) | 3.0 s | 2.0 s |"),
            std::string::npos)
      << md;
  const Json j = t.ToJson();
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[0]["phase"], "build");
  EXPECT_DOUBLE_EQ(j[0]["wall_s"].get<double>(), 15);
  EXPECT_EQ(j[2]["note"], "inside the one above");
}

TEST(PhaseTimes, PriorPhasesFileReadOrRefusedByLine) {
  testing::TempDir dir;
  const std::string good = dir / "good.txt";
  std::ofstream(good) << "# from reproduce.sh\nsetup 0.3 0.2\n\nbuild 120.5 230.25\n";
  PhaseTimes t;
  t.AddFile(good);
  ASSERT_EQ(t.phases().size(), 2u);
  EXPECT_EQ(t.phases()[1].name, "build");
  EXPECT_DOUBLE_EQ(t.phases()[1].cpu, 230.25);
  for (const auto& [text, line] :
       std::vector<std::pair<std::string, int>>{{"setup 1 2\nbuild 3\n", 2},
                                                {"setup 1 2 3\n", 1},
                                                {"build -1 2\n", 1},
                                                {"build 1 x\n", 1},
                                                {"a 1 1\nb 2 nan\n", 2}}) {
    const std::string bad = dir / "bad.txt";
    std::ofstream(bad) << text;
    PhaseTimes u;
    try {
      u.AddFile(bad);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.txt:" + std::to_string(line)), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(t.AddFile(dir / "absent.txt"), InputError);
}

}  // namespace
}  // namespace meshreuse
