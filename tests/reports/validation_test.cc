// The validation runner on a small mesh: the fully associative levels of the simulator equal the
// line model exactly (a level with ways = lines is fully associative LRU), the element model counts
// the element stream, Table 3 carries the paper's values for the paper's meshes and explains an
// infinite capacity, and counters that cannot count leave every number labelled simulated.
#include "reports/validation.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/orderings/registry.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

Mesh Small() { return testing::Synthetic(40, 30, 1, 8); }

TEST(Validation, FullyAssociativeL1EqualsTheLineModelAndCountsAddUp) {
  const Mesh m = Small();
  ValidationConfig cfg;
  cfg.mesh_name = "carabiner.node";  // the paper's name, but not its size
  cfg.orderings = {"ori", "bfs"};
  cfg.iterations = 2;
  // L1: 2 KiB fully associative (32 lines, 32 ways); L2/L3 set-associative.
  cfg.cache.levels = {{"L1", 2048, 32}, {"L2", 16384, 4}, {"L3", 65536, 8}};
  cfg.counter_events = {"NO_SUCH_EVENT"};
  const std::vector<OrderingValidation> r = RunValidation(m, cfg);
  ASSERT_EQ(r.size(), 2u);
  for (const OrderingValidation& v : r) {
    SCOPED_TRACE(v.ordering);
    ASSERT_EQ(v.levels.size(), 3u);
    EXPECT_EQ(v.levels[0].simulated.misses, v.levels[0].model_line);  // exact: same LRU
    EXPECT_EQ(v.levels[0].simulated.accesses, v.line_accesses);
    EXPECT_EQ(v.levels[1].simulated.accesses, v.levels[0].simulated.misses);
    EXPECT_EQ(v.line_accesses, 2 * RefsPerSweep(m)[0]);
    EXPECT_EQ(v.element_accesses, 2 * AccessesPerSweep(m)[0]);
    // Cold element touches: the vertices a sweep touches (interior ones and their neighbours).
    std::vector<char> touched(m.NumVertices(), 0);
    for (int32_t u : m.interior) {
      touched[u] = 1;
      for (const int32_t* p = m.v2v.RowBegin(u); p != m.v2v.RowEnd(u); ++p) touched[*p] = 1;
    }
    EXPECT_EQ(v.element_cold, static_cast<uint64_t>(std::count(touched.begin(), touched.end(), 1)));
    EXPECT_FALSE(v.levels[0].measured);
    EXPECT_EQ(v.counters, "simulated");
    EXPECT_EQ(v.sweeps.size(), 2u);
    for (const LevelValidation& l : v.levels) EXPECT_EQ(l.table3_misses, l.simulated.misses);
  }
  const Table t3 = Table3(r);
  ASSERT_EQ(t3.Rows(), 2u);
  const std::string csv = t3.Csv();
  // The paper's carabiner has 328,082 vertices, this one about 1,200: no paper values beside it.
  EXPECT_EQ(csv.find("106.00"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",,,,"), std::string::npos) << csv;  // missing: empty in CSV
  EXPECT_EQ(ValidationTable(r).Rows(), 6u);
  EXPECT_EQ(ValidationSweepTable(r).Rows(), 12u);
}

TEST(Validation, InfiniteCapacityIsExplained) {
  const Mesh m = Small();
  ValidationConfig cfg;
  cfg.mesh_name = "small";
  cfg.orderings = {"ori"};
  cfg.iterations = 1;
  // A huge L2: only cold misses, exactly the line stream's cold accesses, which miss at any
  // capacity: no finite line capacity explains them.
  cfg.cache.levels = {{"L1", 1024, 4}, {"L2", 64 << 20, 16}};
  cfg.counter_events = {};
  std::vector<OrderingValidation> r = RunValidation(m, cfg);
  ASSERT_EQ(r[0].levels[1].simulated.misses, r[0].levels[1].simulated.cold);
  EXPECT_EQ(r[0].levels[1].capacity_lines, kInfiniteCapacity);
  const std::vector<std::string> notes = Table3Notes(r, false);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[1].find("no finite capacity explains them"), std::string::npos);
  EXPECT_NE(notes[1].find("--exclude-cold"), std::string::npos);
  cfg.exclude_cold = true;
  r = RunValidation(m, cfg);
  EXPECT_NE(r[0].levels[1].capacity_lines, kInfiniteCapacity);
  EXPECT_EQ(Table3Notes(r, true).size(), 1u);
}

// The layout-independent floor (analysis/sweep_footprint.h) checked as a floor: in every ordering
// at 1 and 2 threads no simulated level misses less, and a level that holds the whole sweep
// misses exactly the floor (its cold misses).
TEST(Validation, NoOrderingMissesLessThanTheFloor) {
  SyntheticOptions so;
  so.nx = 50, so.ny = 40, so.holes = 2, so.seed = 4;
  const Mesh m = BuildMesh(MakeSyntheticMesh(so));
  for (int threads : {1, 2}) {
    ValidationConfig cfg;
    cfg.mesh_name = "synthetic";
    cfg.orderings.clear();
    for (const OrderingInfo& o : Orderings())
      if (!o.takes_argument()) cfg.orderings.push_back(o.name);
    cfg.iterations = 3;
    cfg.threads = threads;
    // Small caches (the sweep is about 150 KiB) and one that holds it all.
    cfg.cache.levels = {{"L1", 2048, 4}, {"L2", 16384, 8}, {"L3", 1 << 22, 16}};
    const std::vector<OrderingValidation> r = RunValidation(m, cfg);
    for (const OrderingValidation& v : r) {
      SCOPED_TRACE(v.ordering + " threads " + std::to_string(threads));
      ASSERT_EQ(v.sweep_lines.size(), static_cast<size_t>(threads));
      uint64_t cold = 0;
      for (const auto& t : v.sweep_lines) {
        ASSERT_EQ(t.size(), 3u);
        EXPECT_GT(t[1], (2048 + 16384) / 64u);  // each thread's sweep outgrows its L1 + L2
        cold += t[0];
      }
      for (const LevelValidation& l : v.levels)
        EXPECT_GE(l.simulated.misses, l.floor) << l.level.name;
      EXPECT_GT(v.levels[1].floor, cold);  // warm sweeps add to the floor
      EXPECT_EQ(v.levels[2].floor, cold);  // L3 holds it: the cold lines alone
      EXPECT_EQ(v.levels[2].simulated.misses, v.levels[2].floor);
    }
  }
}

}  // namespace
}  // namespace meshreuse
