// The set-associative simulator: hand-computed conflict misses the fully associative model cannot
// see, equality with the model when ways = lines, a power-of-two stride, straddling accesses,
// non-power-of-two set counts, the hierarchy's filtering, and a naive reference (one std::list per
// set, valgrind's rules written the obvious way) on random multi-level traces.
#include "analysis/cache_sim.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <list>
#include <random>
#include <set>

#include "analysis/cache_model.h"
#include "analysis/reuse_histogram.h"
#include "analysis/stack_distance.h"
#include "core/smoother.h"
#include "core/synthetic.h"

namespace meshreuse {
namespace {

// The obvious implementation: per level, per set, a list with the most recent line first.
struct NaiveHierarchy {
  struct Level {
    uint64_t sets, ways;
    std::vector<std::list<uint64_t>> s;
  };
  std::vector<Level> levels;
  std::set<uint64_t> seen;
  std::vector<LevelStats> stats;
  int shift;
  NaiveHierarchy(const std::vector<CacheLevel>& l, uint32_t line) : shift(__builtin_ctz(line)) {
    for (const CacheLevel& c : l) {
      const uint64_t sets = c.bytes / line / c.ways;
      levels.push_back({sets, c.ways, std::vector<std::list<uint64_t>>(sets)});
    }
    stats.resize(l.size());
  }
  bool Touch(Level& L, uint64_t line) {
    std::list<uint64_t>& set = L.s[line % L.sets];
    const auto it = std::find(set.begin(), set.end(), line);
    const bool hit = it != set.end();
    if (hit) set.erase(it);
    set.push_front(line);
    if (set.size() > L.ways) set.pop_back();
    return hit;
  }
  void Access(uint64_t a, uint32_t size, bool write) {
    const uint64_t first = a >> shift, last = (a + std::max(size, 1u) - 1) >> shift;
    bool cold = false;
    for (uint64_t l = first; l <= last; ++l) cold = seen.insert(l).second || cold;
    for (size_t i = 0; i < levels.size(); ++i) {
      ++stats[i].accesses;
      bool hit = true;
      for (uint64_t l = first; l <= last; ++l) hit = Touch(levels[i], l) && hit;
      if (hit) return;
      ++stats[i].misses;
      stats[i].cold += cold;
      ++(write ? stats[i].write_misses : stats[i].read_misses);
    }
  }
};

void ExpectSame(const LevelStats& a, const LevelStats& b, const std::string& what) {
  EXPECT_EQ(a.accesses, b.accesses) << what;
  EXPECT_EQ(a.misses, b.misses) << what;
  EXPECT_EQ(a.cold, b.cold) << what;
  EXPECT_EQ(a.read_misses, b.read_misses) << what;
  EXPECT_EQ(a.write_misses, b.write_misses) << what;
}

TEST(SetAssociativeCache, ConflictMissesTheFullyAssociativeModelCannotSee) {
  // 4 lines of 64 B in 2 sets of 2 ways. Lines 0, 2, 4 all map to set 0; cycling through them
  // misses every time (LRU evicts the one needed next), although their reuse distance is 2 and a
  // fully associative cache of 4 lines would hit on every reuse.
  CacheHierarchy h({{"L1", 256, 2}}, 64);
  StackDistance sd(100);
  ReuseHistogram hist;
  for (int lap = 0; lap < 5; ++lap)
    for (uint64_t line : {0, 2, 4}) {
      h.Access(line * 64, 8, false);
      hist.Add(sd.Access(line));
    }
  EXPECT_EQ(h.stats()[0].accesses, 15u);
  EXPECT_EQ(h.stats()[0].misses, 15u);
  EXPECT_EQ(h.stats()[0].cold, 3u);
  EXPECT_EQ(ModelMisses(hist, {{"L1", 256}}, 64)[0].misses, 3u);  // the model: cold only
  // Lines 0 and 1 go to different sets: after the cold misses, hits.
  CacheHierarchy g({{"L1", 256, 2}}, 64);
  for (int lap = 0; lap < 5; ++lap)
    for (uint64_t line : {0, 1, 2, 3}) g.Access(line * 64, 8, false);
  EXPECT_EQ(g.stats()[0].misses, 4u);
}

TEST(SetAssociativeCache, EqualsTheFullyAssociativeModelWhenWaysEqualLines) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const uint64_t lines = 1 + rng() % 64, universe = 1 + rng() % 300;
    CacheHierarchy h({{"L1", lines * 64, static_cast<uint32_t>(lines)}}, 64);
    StackDistance sd(universe + 1);
    ReuseHistogram hist;
    std::geometric_distribution<uint64_t> near(0.05);
    uint64_t x = 0;
    for (int i = 0; i < 3000; ++i) {
      x = (rng() % 4 == 0) ? rng() % universe : (x + near(rng)) % universe;
      h.Access(x * 64 + rng() % 56, 8, rng() % 5 == 0);
      hist.Add(sd.Access(x));
    }
    EXPECT_EQ(h.stats()[0].misses, ModelMisses(hist, {{"L1", lines * 64}}, 64)[0].misses)
        << "lines " << lines << " universe " << universe;
    EXPECT_EQ(h.stats()[0].cold, hist.cold());
  }
}

TEST(SetAssociativeCache, PowerOfTwoStrideLandsInOneSet) {
  // 32 KiB, 8 ways, 64 B lines: 64 sets, so addresses 4 KiB apart share a set. Nine of them cycled
  // miss every time (LRU), eight fit after their cold misses.
  for (int n : {8, 9}) {
    CacheHierarchy h({{"L1", 32 << 10, 8}}, 64);
    for (int lap = 0; lap < 10; ++lap)
      for (int i = 0; i < n; ++i) h.Access(uint64_t(i) * 4096, 8, false);
    EXPECT_EQ(h.stats()[0].misses, n == 8 ? 8u : 90u) << n << " lines";
  }
  SetAssociativeCache c(32 << 10, 8, 64);
  EXPECT_EQ(c.sets(), 64u);
}

TEST(SetAssociativeCache, StraddlingAccessCountsOnceAndMissesIfEitherLineMisses) {
  CacheHierarchy h({{"L1", 1024, 4}}, 64);
  h.Access(60, 8, false);  // bytes 60..67: lines 0 and 1, both new
  EXPECT_EQ(h.stats()[0].accesses, 1u);
  EXPECT_EQ(h.stats()[0].misses, 1u);
  EXPECT_EQ(h.stats()[0].cold, 1u);
  h.Access(0, 8, false);   // line 0: installed by the straddle, a hit
  h.Access(64, 8, false);  // line 1: a hit
  EXPECT_EQ(h.stats()[0].misses, 1u);
  h.Access(120, 16, true);  // lines 1 (hit) and 2 (new): one miss, a write miss, cold
  EXPECT_EQ(h.stats()[0].accesses, 4u);
  EXPECT_EQ(h.stats()[0].misses, 2u);
  EXPECT_EQ(h.stats()[0].write_misses, 1u);
  EXPECT_EQ(h.stats()[0].cold, 2u);
  EXPECT_EQ(h.distinct_lines(), 3u);
}

TEST(SetAssociativeCache, NonPowerOfTwoSetsUseTheRemainder) {
  SetAssociativeCache c(3 * 2 * 64, 2, 64);  // 3 sets of 2 ways
  EXPECT_EQ(c.sets(), 3u);
  // Lines 0, 3, 6 share set 0: the third evicts the first.
  EXPECT_FALSE(c.Access(0));
  EXPECT_FALSE(c.Access(3));
  EXPECT_TRUE(c.Access(0));
  EXPECT_FALSE(c.Access(6));  // evicts 3 (least recent)
  EXPECT_TRUE(c.Access(0));
  EXPECT_FALSE(c.Access(3));
  EXPECT_TRUE(c.Access(1) == false && c.Access(4) == false && c.Access(0) == true);
  EXPECT_THROW(SetAssociativeCache(1000, 3, 64), std::invalid_argument);
  EXPECT_THROW(CacheHierarchy({{"L1", 1024, 0}}, 64), std::invalid_argument);
}

TEST(CacheHierarchy, MatchesANaiveReferenceOnRandomTraces) {
  std::mt19937_64 rng(2024);
  for (int trial = 0; trial < 12; ++trial) {
    // Small caches (so every level misses), some with set counts that are not powers of two.
    const uint32_t line = trial % 3 == 0 ? 32 : 64;
    const std::vector<CacheLevel> levels = {{"L1", uint64_t{line} * (2 + trial % 3) * 4, 4},
                                            {"L2", uint64_t{line} * (5 + trial) * 8, 8},
                                            {"L3", uint64_t{line} * 96 * (1 + trial % 2) * 12, 12}};
    CacheHierarchy h(levels, line);
    NaiveHierarchy ref(levels, line);
    std::geometric_distribution<uint64_t> step(0.02);
    uint64_t a = 0;
    for (int i = 0; i < 40000; ++i) {
      a = rng() % 7 == 0 ? rng() % (1 << 20) : a + step(rng) * 4;
      const uint32_t size = std::array<uint32_t, 5>{1, 4, 8, 16, 0}[rng() % 5];
      const bool write = rng() % 4 == 0;
      h.Access(a, size, write);
      ref.Access(a, size, write);
    }
    for (size_t l = 0; l < levels.size(); ++l)
      ExpectSame(h.stats()[l], ref.stats[l],
                 "trial " + std::to_string(trial) + " " + levels[l].name);
    // Each level sees exactly the misses of the one above.
    EXPECT_EQ(h.stats()[1].accesses, h.stats()[0].misses);
    EXPECT_EQ(h.stats()[2].accesses, h.stats()[1].misses);
  }
}

TEST(CacheSimulation, PerSweepStatsAddUpAndTheSinkSeesEveryAccess) {
  SyntheticOptions so;
  so.nx = 30, so.ny = 24, so.holes = 1, so.seed = 3;
  Mesh m = BuildMesh(MakeSyntheticMesh(so));
  SmoothOptions o;
  o.max_iters = 3;
  o.tol = -1;
  o.threads = 2;
  const std::vector<CacheLevel> levels = {{"L1", 2048, 4}, {"L2", 16384, 8}};
  CacheSimulation sim(levels, 64, 2);
  CacheSimSink sink{&sim};
  RecordingSink rec;
  FanOutSink<CacheSimSink, RecordingSink> both{sink, rec};
  Smooth(m, o, both);
  ASSERT_EQ(sim.sweeps(), 3u);
  // The same accesses replayed into a fresh simulation, thread by thread, at the canonical
  // addresses the sink uses.
  CacheSimulation replay(levels, 64, 2);
  const AddressCanonicalizer canon(rec.layout);
  for (const RecordingSink::Ref& r : rec.refs)
    replay.Access(r.thread, canon(r.thread, r.ref), r.ref.size, r.ref.write);
  const std::vector<uint64_t> per = RefsPerSweep(m, 2);
  for (int t = 0; t < 2; ++t) {
    LevelStats sum;
    for (size_t s = 0; s < 3; ++s) {
      const std::vector<LevelStats> st = sim.SweepStats(t, s);
      EXPECT_EQ(st[0].accesses, per[t]) << "thread " << t << " sweep " << s;
      sum += st[0];
    }
    ExpectSame(sum, sim.Stats(t)[0], "L1 sum of sweeps");
    for (size_t l = 0; l < levels.size(); ++l)
      ExpectSame(sim.Stats(t)[l], replay.Stats(t)[l], "replay");
    EXPECT_GT(sim.Stats(t)[0].misses, sim.Stats(t)[0].cold);  // small caches: capacity misses
    // Cold misses in later sweeps: none (every line was touched in sweep 1).
    EXPECT_EQ(sim.SweepStats(t, 2)[0].cold, 0u);
  }
}

TEST(CacheSpec, Associativity) {
  const auto w = ParseCacheSpec("westmere-ex");
  EXPECT_EQ(w[0].ways, 8u);
  EXPECT_EQ(w[1].ways, 8u);
  EXPECT_EQ(w[2].ways, 24u);
  const auto c = ParseCacheSpec("L1=48K/12,L2=1280K/20,LLC=30M");
  EXPECT_EQ(c[0].bytes, 48u << 10);
  EXPECT_EQ(c[0].ways, 12u);
  EXPECT_EQ(c[1].bytes, 1280u << 10);
  EXPECT_EQ(c[1].ways, 20u);
  EXPECT_EQ(c[2].ways, 0u);  // not given: the model does not need it
  EXPECT_THROW(ParseCacheSpec("L1=32K/"), std::invalid_argument);
  EXPECT_THROW(ParseCacheSpec("L1=32K/0"), std::invalid_argument);
  EXPECT_THROW(ParseCacheSpec("L1=/8"), std::invalid_argument);
  EXPECT_THROW(ParseCacheSpec("L1=32K/x"), std::invalid_argument);
}

}  // namespace
}  // namespace meshreuse
