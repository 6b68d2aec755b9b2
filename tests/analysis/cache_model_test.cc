// Miss model, inverse model and cost model on distributions whose answers are known exactly.
#include "analysis/cache_model.h"

#include <gtest/gtest.h>

#include "analysis/stack_distance.h"

namespace meshreuse {
namespace {

TEST(CacheSpec, Parse) {
  const auto w = ParseCacheSpec("westmere-ex");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].bytes, 32768u);
  EXPECT_EQ(w[1].bytes, 262144u);
  EXPECT_EQ(w[2].bytes, 24u << 20);
  const auto c = ParseCacheSpec("L1=48K,L2=2M,L3=105M");
  EXPECT_EQ(c[1].name, "L2");
  EXPECT_EQ(c[1].bytes, 2u << 20);
  EXPECT_EQ(ParseCacheSpec("X=100")[0].bytes, 100u);
  EXPECT_THROW(ParseCacheSpec("L1"), std::invalid_argument);
  EXPECT_THROW(ParseCacheSpec("L1=abc"), std::invalid_argument);
  EXPECT_THROW(ParseCacheSpec("L1=0K"), std::invalid_argument);
}

TEST(MissModel, CyclicScanMissesAllOrOnlyCold) {
  // 1000 ids scanned 10 times: 1000 cold, then 9000 accesses at distance 999.
  StackDistance sd(2000);
  ReuseHistogram h;
  for (int lap = 0; lap < 10; ++lap)
    for (uint64_t id = 0; id < 1000; ++id) h.Add(sd.Access(id));
  // Unit 32 bytes: capacities 999 (31968 B), 1000 (32000 B) and 1 (32 B).
  const auto m = ModelMisses(h, {{"A", 999 * 32}, {"B", 1000 * 32}, {"C", 32}}, 32);
  EXPECT_EQ(m[0].capacity, 999u);
  EXPECT_EQ(m[0].misses, 10000u);  // distance 999 >= capacity 999: every access misses
  EXPECT_EQ(m[1].misses, 1000u);   // fits: only cold misses
  EXPECT_EQ(m[2].misses, 10000u);
  EXPECT_DOUBLE_EQ(m[1].rate, 0.1);
  // The paper's element model: 32 KiB / 66 B = 496 elements.
  EXPECT_EQ(ModelMisses(h, ParseCacheSpec("westmere-ex"), 66)[0].capacity, 496u);
}

TEST(InverseModel, CapacityOfTheNthLargest) {
  ReuseHistogram h;
  for (uint64_t d : {1, 2, 2, 3, 50, 70}) h.Add(d);
  h.Add(StackDistance::kCold);
  h.Add(StackDistance::kCold);
  // Largest first: cold, cold, 70, 50, 3, 2, 2, 1.
  EXPECT_EQ(CapacityForMisses(h, 1), kInfiniteCapacity);
  EXPECT_EQ(CapacityForMisses(h, 2), kInfiniteCapacity);
  EXPECT_EQ(CapacityForMisses(h, 3), 70u);
  EXPECT_EQ(CapacityForMisses(h, 4), 50u);
  EXPECT_EQ(CapacityForMisses(h, 6), 2u);
  EXPECT_EQ(CapacityForMisses(h, 8), 1u);
  EXPECT_EQ(CapacityForMisses(h, 9), 0u);  // more misses than accesses
  // Consistency with the forward model: a cache of capacity CapacityForMisses(n) misses >= n.
  for (uint64_t n = 3; n <= 8; ++n)
    EXPECT_GE(h.cold() + h.CountAtLeast(CapacityForMisses(h, n)), n);
}

TEST(InverseModel, ExcludeColdTakesColdMissesAsCompulsory) {
  ReuseHistogram h;
  for (uint64_t d : {1, 2, 2, 3, 50, 70}) h.Add(d);
  h.Add(StackDistance::kCold);
  h.Add(StackDistance::kCold);
  // Two misses are the two cold accesses: no reuse needs to miss, any capacity above 70 does.
  EXPECT_EQ(CapacityForMisses(h, 2, true), 71u);
  EXPECT_EQ(CapacityForMisses(h, 1, true), 71u);
  // Beyond the cold ones the answer is the forward model's, with or without the option.
  EXPECT_EQ(CapacityForMisses(h, 3, true), 70u);
  EXPECT_EQ(CapacityForMisses(h, 5, true), CapacityForMisses(h, 5));
}

TEST(CostModel, EquationTwo) {
  const std::vector<LevelMisses> l = {{"L1", 0, 1000, 0}, {"L2", 0, 100, 0}, {"L3", 0, 10, 0}};
  const CostRange c = AdditionalCycles(l);
  EXPECT_DOUBLE_EQ(c.low, 1000 * 10 + 100 * 38 + 10 * 175);
  EXPECT_DOUBLE_EQ(c.high, 1000 * 10 + 100 * 170 + 10 * 290);
  EXPECT_THROW(AdditionalCycles({l[0], l[1]}), std::invalid_argument);
}

}  // namespace
}  // namespace meshreuse
