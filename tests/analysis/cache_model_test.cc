// Miss model, inverse model and cost model on distributions whose answers are known exactly.
#include "analysis/cache_model.h"

#include <gtest/gtest.h>

#include "analysis/stack_distance.h"
#include "core/error.h"

namespace meshreuse {
namespace {

TEST(CacheSpec, Parse) {
  const auto w = ParseCacheSpec("westmere-ex").levels;
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].bytes, 32768u);
  EXPECT_EQ(w[1].bytes, 262144u);
  EXPECT_EQ(w[2].bytes, 24u << 20);
  const auto c = ParseCacheSpec("L1=48K,L2=2M,L3=105M").levels;
  EXPECT_EQ(c[1].name, "L2");
  EXPECT_EQ(c[1].bytes, 2u << 20);
  EXPECT_EQ(ParseCacheSpec("X=100").levels[0].bytes, 100u);
  EXPECT_THROW(ParseCacheSpec("L1"), UsageError);
  EXPECT_THROW(ParseCacheSpec("L1=abc"), UsageError);
  EXPECT_THROW(ParseCacheSpec("L1=0K"), UsageError);
}

TEST(CacheSpec, PoliciesLatenciesAndBounds) {
  const CacheSpec s =
      ParseCacheSpec("L1=32K/8,L2=256K/8/fifo@12,L3=8M/16/random@40-90,mem@200-300");
  ASSERT_EQ(s.levels.size(), 3u);
  EXPECT_EQ(s.levels[0].policy, Replacement::kLru);
  EXPECT_EQ(s.levels[1].policy, Replacement::kFifo);
  EXPECT_EQ(s.levels[2].policy, Replacement::kRandom);
  EXPECT_EQ(s.levels[1].latency.low, 12);
  EXPECT_EQ(s.levels[2].latency.high, 90);
  EXPECT_EQ(s.memory.low, 200);
  EXPECT_TRUE(s.has_latencies());
  EXPECT_FALSE(ParseCacheSpec("L1=32K/8,L2=256K/8").has_latencies());
  EXPECT_TRUE(ParseCacheSpec("westmere-ex").has_latencies());
  // Sizes beyond 1 GiB, or that overflow, are refused, never wrapped.
  EXPECT_THROW(ParseCacheSpec("L1=2G/1"), UsageError);
  EXPECT_THROW(ParseCacheSpec("L1=999999999999G"), UsageError);
  EXPECT_THROW(ParseCacheSpec("L1=32K/8/lfu"), UsageError);
  EXPECT_THROW(ParseCacheSpec("L1=32K/8@x"), UsageError);
  EXPECT_THROW(ParseCacheSpec("L1=32K/8@90-10"), UsageError);
  EXPECT_THROW(ParseCacheSpec("mem"), UsageError);
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
  EXPECT_EQ(ModelMisses(h, ParseCacheSpec("westmere-ex").levels, 66)[0].capacity, 496u);
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
  const std::optional<CostRange> c =
      AdditionalCycles({1000, 100, 10}, ParseCacheSpec("westmere-ex"));
  ASSERT_TRUE(c);
  EXPECT_DOUBLE_EQ(c->low, 1000 * 10 + 100 * 38 + 10 * 175);
  EXPECT_DOUBLE_EQ(c->high, 1000 * 10 + 100 * 170 + 10 * 290);
  EXPECT_FALSE(AdditionalCycles({1000, 100}, ParseCacheSpec("westmere-ex")));  // level count
  EXPECT_FALSE(AdditionalCycles({1, 2, 3}, ParseCacheSpec("L1=32K,L2=256K,L3=24M")));
}

TEST(CostModel, AnyNumberOfLevels) {
  // Four levels: each level's misses are served by the next one, the last's by memory.
  const CacheSpec s = ParseCacheSpec("L1=32K@4,L2=256K@12,L3=8M@40,L4=64M@80-100,mem@300");
  const std::optional<CostRange> c = AdditionalCycles({1000, 100, 10, 1}, s);
  ASSERT_TRUE(c);
  EXPECT_DOUBLE_EQ(c->low, 1000 * 12 + 100 * 40 + 10 * 80 + 1 * 300);
  EXPECT_DOUBLE_EQ(c->high, 1000 * 12 + 100 * 40 + 10 * 100 + 1 * 300);
}

}  // namespace
}  // namespace meshreuse
