// PAPI counters through the real code path. These machines have no hardware counters (PAPI says
// "Running in a VM", every preset unavailable), so the path is exercised with a software event that
// perf_event counts everywhere: library and thread initialisation, one event set per OpenMP thread
// created on its first Enter, start/stop around each sweep, accumulation per thread and summed.
// Where PAPI was not built in, the tests check that the counters say so and stay inert.
#include "analysis/papi_counters.h"

#include <gtest/gtest.h>
#include <omp.h>

#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

Mesh Synthetic() { return testing::Synthetic(120, 90, 2, 5); }

TEST(PapiCounters, SoftwareEventCountsPerThreadAroundTheSweeps) {
  PapiCounters c({"perf::TASK-CLOCK"}, 2);
  if (PapiCounters::Version().find("not built in") != std::string::npos) {
    EXPECT_FALSE(c.available());
    EXPECT_NE(c.reason().find("built without PAPI"), std::string::npos);
    GTEST_SKIP() << c.reason();
  }
  // A host whose PAPI perf_event component is off (libpfm4 finds no PMU under some hypervisors)
  // has no event at all; anywhere else the software event must count.
  if (!c.available() && c.reason().find("perf_event component disabled") != std::string::npos)
    GTEST_SKIP() << c.reason();
  ASSERT_TRUE(c.available()) << "perf::TASK-CLOCK should count wherever perf_event works: "
                             << c.reason();
  EXPECT_EQ(c.events(), (std::vector<std::string>{"perf::TASK-CLOCK"}));
  Mesh m = Synthetic();
  SmoothOptions o;
  o.max_iters = 4;
  o.tol = -1;
  o.threads = 2;
  o.region = &c;
  Smooth(m, o);
  EXPECT_EQ(c.error(), "");
  ASSERT_EQ(c.per_thread().size(), 2u);
  // Task clock in nanoseconds: both threads ran their share of four sweeps.
  EXPECT_GT(c.per_thread()[0][0], 0);
  if (omp_get_max_threads() >= 2) {
    EXPECT_GT(c.per_thread()[1][0], 0);
  }
  EXPECT_EQ(c.Sum()[0], c.per_thread()[0][0] + c.per_thread()[1][0]);
  // Accumulates: four more sweeps add to the totals.
  const long long before = c.Sum()[0];
  Smooth(m, o);
  EXPECT_GT(c.Sum()[0], before);
}

TEST(PapiCounters, UnavailableEventsAreDroppedWithPapisReason) {
  PapiCounters c({"NO_SUCH_EVENT_ANYWHERE"}, 1);
  EXPECT_FALSE(c.available());
  EXPECT_EQ(c.dropped(), (std::vector<std::string>{"NO_SUCH_EVENT_ANYWHERE"}));
  EXPECT_FALSE(c.reason().empty());
  // Inert: a smoothing run with it as the region counts nothing and does not fail.
  Mesh m = Synthetic();
  SmoothOptions o;
  o.max_iters = 1;
  o.region = &c;
  Smooth(m, o);
  EXPECT_TRUE(c.Sum().empty());
  EXPECT_EQ(c.error(), "");
}

TEST(PapiCounters, DefaultEventsAreThePapersLevelsThenCyclesAndInstructions) {
  EXPECT_EQ(DefaultCounterEvents(),
            (std::vector<std::string>{"PAPI_L1_DCM", "PAPI_L2_DCM", "PAPI_L3_TCM", "PAPI_TOT_CYC",
                                      "PAPI_TOT_INS"}));
  // Whatever this machine has, the probe decides by trying: each event either counts or is
  // dropped with a reason, never both, never neither.
  PapiCounters c(DefaultCounterEvents(), 1);
  EXPECT_EQ(c.events().size() + c.dropped().size(), 5u);
  if (!c.dropped().empty()) {
    EXPECT_FALSE(c.reason().empty());
  }
}

}  // namespace
}  // namespace meshreuse
