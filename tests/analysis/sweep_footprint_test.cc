// The sweep footprint against std::set per sweep on random streams (straddling accesses,
// canonical and other addresses), and MissFloor by hand. (The floor checked as a floor, on meshes
// in every ordering: tests/reports/validation_test.cc.)
#include "analysis/sweep_footprint.h"

#include <gtest/gtest.h>

#include <set>

#include "core/access.h"
#include "core/synthetic.h"

namespace meshreuse {
namespace {

// Lines of 64 B and of 48 (not a power of two); a third of the accesses repeat their thread's
// address before (a repeat is looked up by no one), the first of each sweep included (it still
// counts in its sweep).
TEST(SweepFootprint, CountsEachSweepsDistinctLines) {
  for (bool canonical : {true, false})
    for (const uint32_t bytes : {64u, 48u})
      for (uint64_t seed = 1; seed <= 5; ++seed) {
        SplitMix64 rng(seed);
        SweepFootprint f(bytes);
        StreamInfo info;
        info.canonical = canonical;
        info.threads = 2;
        f.Begin(info);
        std::vector<std::vector<std::set<uint64_t>>> want(2, std::vector<std::set<uint64_t>>(4));
        const uint64_t base = canonical ? AddressCanonicalizer::kCanonicalBase : 12345;
        uint64_t before[2] = {base, base + 64};
        for (int sweep = 1; sweep <= 4; ++sweep) {
          f.BeginSweep(sweep);
          std::vector<Access> batch;
          for (int k = 0; k < 500; ++k) {
            Access a{};
            a.thread = static_cast<uint8_t>(rng.Below(2));
            a.address = k < 4 || rng.Below(3) == 0 ? before[a.thread] : base + rng.Below(64 * 300);
            before[a.thread] = a.address;
            a.size =
                static_cast<uint32_t>(rng.Below(130));  // some straddle: their first line counts
            batch.push_back(a);
            want[a.thread][sweep - 1].insert(a.address / bytes);
          }
          f.Consume(batch.data(), batch.size());
        }
        ASSERT_EQ(f.lines().size(), 2u);
        for (size_t t = 0; t < 2; ++t) {
          ASSERT_EQ(f.lines()[t].size(), 4u);
          for (size_t s = 0; s < 4; ++s) EXPECT_EQ(f.lines()[t][s], want[t][s].size()) << t << s;
        }
      }
}

TEST(SweepFootprint, FloorByHand) {
  CacheSpec c;
  c.levels = {{"L1", 64 * 10, 2}, {"L2", 64 * 100, 4}};
  // Sweeps of 500, 500, 105 lines: L1 holds 10 -> 500 + 490 + 95; L1+L2 hold 110 -> 500 + 390 + 0.
  EXPECT_EQ(MissFloor({{500, 500, 105}}, c, 64), (std::vector<uint64_t>{1085, 890}));
  // Two threads, each its own hierarchy: the sum of their floors.
  EXPECT_EQ(MissFloor({{500, 500, 105}, {20, 30}}, c, 64),
            (std::vector<uint64_t>{1085 + 40, 890 + 20}));
}

}  // namespace
}  // namespace meshreuse
