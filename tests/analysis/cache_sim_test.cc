// The set-associative simulator: hand-computed conflict misses the fully associative model cannot
// see, equality with the model when ways = lines, a power-of-two stride, straddling accesses,
// non-power-of-two set counts, the hierarchy's filtering, and a naive reference (one std::list per
// set, valgrind's rules written the obvious way) on random multi-level traces.
#include "analysis/cache_sim.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <list>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "analysis/cache_model.h"
#include "analysis/reuse_histogram.h"
#include "analysis/stack_distance.h"
#include "core/error.h"
#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"
#include "tracer/trace_formats.h"

namespace meshreuse {
namespace {

// The obvious implementation: per level, per set, a list with the most recent line first (LRU),
// or the most recently installed first (FIFO: a hit leaves the list as it is).
struct NaiveHierarchy {
  struct Level {
    uint64_t sets, ways;
    std::vector<std::list<uint64_t>> s;
    bool fifo = false;
  };
  std::vector<Level> levels;
  std::vector<std::string> names;
  std::set<uint64_t> seen;
  std::vector<LevelStats> stats;
  int shift;
  NaiveHierarchy(const std::vector<CacheLevel>& l, uint32_t line) : shift(__builtin_ctz(line)) {
    for (const CacheLevel& c : l) {
      const uint64_t sets = c.bytes / line / c.ways;
      levels.push_back(
          {sets, c.ways, std::vector<std::list<uint64_t>>(sets), c.policy == Replacement::kFifo});
      names.push_back(c.name);
    }
    stats.resize(l.size());
  }
  bool Touch(Level& L, uint64_t line) {
    std::list<uint64_t>& set = L.s[line % L.sets];
    const auto it = std::find(set.begin(), set.end(), line);
    const bool hit = it != set.end();
    if (hit && L.fifo) return true;
    if (hit) set.erase(it);
    set.push_front(line);
    if (set.size() > L.ways) set.pop_back();
    return hit;
  }
  // A fetch goes through I1 (if any) instead of the first data level; data never goes to I1.
  void Access(uint64_t a, uint32_t size, bool write, bool fetch = false) {
    const uint64_t first = a >> shift, last = (a + std::max(size, 1u) - 1) >> shift;
    // The record of first touches takes an access's end lines (one of three lines or more leaves
    // its middle lines out, as CacheHierarchy always has).
    bool cold = seen.insert(first).second;
    cold = seen.insert(last).second || cold;
    const bool has_i1 = std::count(names.begin(), names.end(), "I1") > 0;
    bool first_data = true;
    for (size_t i = 0; i < levels.size(); ++i) {
      if (names[i] == "I1" && !fetch) continue;
      if (names[i] != "I1") {
        const bool skip = fetch && has_i1 && first_data;
        first_data = false;
        if (skip) continue;
      }
      ++stats[i].accesses;
      bool hit = true;
      for (uint64_t l = first; l <= last; ++l) hit = Touch(levels[i], l) && hit;
      if (hit) return;
      ++stats[i].misses;
      stats[i].cold += cold;
      ++(fetch ? stats[i].fetch_misses : write ? stats[i].write_misses : stats[i].read_misses);
    }
  }
};

void ExpectSame(const LevelStats& a, const LevelStats& b, const std::string& what) {
  EXPECT_EQ(a.accesses, b.accesses) << what;
  EXPECT_EQ(a.misses, b.misses) << what;
  EXPECT_EQ(a.cold, b.cold) << what;
  EXPECT_EQ(a.read_misses, b.read_misses) << what;
  EXPECT_EQ(a.write_misses, b.write_misses) << what;
  EXPECT_EQ(a.fetch_misses, b.fetch_misses) << what;
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
  EXPECT_THROW(SetAssociativeCache(1000, 3, 64), UsageError);
  EXPECT_THROW(CacheHierarchy({{"L1", 1024, 0}}, 64), UsageError);
}

TEST(CacheHierarchy, MatchesANaiveReferenceOnRandomTraces) {
  std::mt19937_64 rng(2024);
  for (int trial = 0; trial < 12; ++trial) {
    // Small caches (so every level misses), some with set counts that are not powers of two; LRU
    // and, on odd trials, a FIFO L2; one access in five an instruction fetch, which every fourth
    // trial sends through an instruction cache I1 (listed first or second).
    const uint32_t line = trial % 3 == 0 ? 32 : 64;
    const Replacement l2 = trial % 2 ? Replacement::kFifo : Replacement::kLru;
    std::vector<CacheLevel> levels = {{"L1", uint64_t{line} * (2 + trial % 3) * 4, 4},
                                      {"L2", uint64_t{line} * (5 + trial) * 8, 8, l2},
                                      {"L3", uint64_t{line} * 96 * (1 + trial % 2) * 12, 12}};
    if (trial % 4 == 1)
      levels.insert(levels.begin() + trial % 8 / 4, CacheLevel{"I1", uint64_t{line} * 3 * 2, 2});
    CacheHierarchy h(levels, line);
    NaiveHierarchy ref(levels, line);
    std::geometric_distribution<uint64_t> step(0.02);
    uint64_t a = 0;
    for (int i = 0; i < 40000; ++i) {
      a = rng() % 7 == 0 ? rng() % (1 << 20) : a + step(rng) * 4;
      const uint32_t size = std::array<uint32_t, 5>{1, 4, 8, 16, 0}[rng() % 5];
      const bool write = rng() % 4 == 0, fetch = !write && rng() % 5 == 0;
      h.Access(a, size, write, fetch);
      ref.Access(a, size, write, fetch);
    }
    for (size_t l = 0; l < levels.size(); ++l)
      ExpectSame(h.stats()[l], ref.stats[l],
                 "trial " + std::to_string(trial) + " " + levels[l].name);
    // Each level sees exactly the misses of the one above (both first levels, with an I1).
    std::vector<LevelStats> s = h.stats();
    if (levels.size() == 4) {
      const size_t i1 = levels[0].name == "I1" ? 0 : 1;
      EXPECT_GT(s[i1].fetch_misses, 0u);
      EXPECT_EQ(s[i1].misses, s[i1].fetch_misses);
      EXPECT_EQ(s[1 - i1].fetch_misses, 0u);
      EXPECT_EQ(s[2].accesses, s[0].misses + s[1].misses);
      s.erase(s.begin(), s.begin() + 1);
      s[0].misses = s[1].accesses;
    }
    EXPECT_EQ(s[1].accesses, s[0].misses);
    EXPECT_EQ(s[2].accesses, s[1].misses);
  }
}

// Consume, the path every stream takes (first-level hits in runs, HitFirst, the rest through
// Access), against the naive hierarchy per thread: threads' runs interleaved, random batch sizes,
// straddling and wide accesses just below a line's end (a line that may just have missed), fetches
// with and without an I1.
TEST(CacheSimulation, ConsumeMatchesANaiveReferencePerThread) {
  std::mt19937_64 rng(4040);
  for (int trial = 0; trial < 8; ++trial) {
    const uint32_t line = 64;
    std::vector<CacheLevel> levels = {{"L1", uint64_t{line} * (2 + trial % 3) * 4, 4},
                                      {"L2", uint64_t{line} * (5 + trial) * 8, 8},
                                      {"L3", uint64_t{line} * 96 * 12, 12}};
    if (trial % 4 == 3) levels.insert(levels.begin(), CacheLevel{"I1", uint64_t{line} * 6, 2});
    const int threads = 1 + trial % 3;
    CacheSpec spec;
    spec.levels = levels;
    CacheSimulation sim(spec, line);
    StreamInfo info;
    info.threads = threads;
    sim.Begin(info);
    std::vector<NaiveHierarchy> ref(threads, NaiveHierarchy(levels, line));
    std::vector<uint64_t> at(threads, 0);
    std::geometric_distribution<uint64_t> step(0.05);
    std::vector<Access> all;
    while (all.size() < 60000) {
      const uint8_t t = static_cast<uint8_t>(rng() % threads);
      for (int k = 1 + static_cast<int>(rng() % 12); k > 0; --k) {  // a run of thread t
        uint64_t& a = at[t];
        a = rng() % 9 == 0 ? rng() % (1 << 18) : a + step(rng) * 4;
        Access x{};
        x.address = (uint64_t{t} << 24) + a;
        // Mostly one line; one in twelve from just below a line's end over two lines or (after
        // trial 3, one in forty) over three or more, where the line before it may just have missed.
        x.size = std::array<uint32_t, 4>{1, 4, 8, 16}[rng() % 4];
        if (rng() % 12 == 0) {
          x.address = (x.address | (line - 1)) - rng() % 4;
          x.size = trial > 3 && rng() % 40 == 0 ? 2 * line + 8 : 12;
        }
        x.thread = t;
        x.write = rng() % 4 == 0;
        x.kind = static_cast<uint8_t>(!x.write && rng() % 5 == 0 ? AccessKind::kFetch
                                                                 : AccessKind::kNone);
        all.push_back(x);
        ref[t].Access(x.address, x.size, x.write,
                      x.kind == static_cast<uint8_t>(AccessKind::kFetch));
      }
    }
    for (size_t i = 0; i < all.size();) {
      const size_t n = std::min<size_t>(all.size() - i, 1 + rng() % 700);
      sim.Consume(all.data() + i, n);
      i += n;
    }
    for (int t = 0; t < threads; ++t)
      for (size_t l = 0; l < levels.size(); ++l)
        ExpectSame(sim.Stats(t)[l], ref[t].stats[l],
                   "trial " + std::to_string(trial) + " thread " + std::to_string(t) + " " +
                       levels[l].name);
  }
}

// Cachegrind's own numbers (tests/data/lackey/make.sh): a static transpose program traced by
// lackey and simulated by cachegrind with I1=D1=4 KiB 2-way and LL=64 KiB 4-way. With an I1 every
// count is cachegrind's: I1mr, D1mr/D1mw, DLmr/DLmw, ILmr (a modify is a read and a write that
// always hits, which cachegrind counts as the read alone). Without --instructions the data levels
// still match at D1; the LL then misses the instruction lines' evictions.
TEST(CacheSimulation, LackeyTraceMissesEqualCachegrinds) {
  const std::string dir = std::string(MESHREUSE_TEST_DATA) + "/lackey/";
  std::ifstream cg(dir + "transpose.cachegrind");
  std::string line, events, summary;
  std::vector<std::string> spec;
  while (std::getline(cg, line)) {
    std::istringstream in(line);
    std::string key, name;
    in >> key;
    if (key == "events:") events = line.substr(8);
    if (key == "summary:") summary = line.substr(9);
    if (key == "desc:") {  // "desc: D1 cache:  4096 B, 64 B, 2-way associative"
      uint64_t bytes = 0, line_bytes = 0, ways = 0;
      std::string b, c;
      in >> name >> c >> bytes >> b >> line_bytes >> b >> ways;
      ASSERT_EQ(line_bytes, 64u) << line;
      spec.push_back((name == "LL" ? "LL" : name) + "=" + std::to_string(bytes) + "/" +
                     std::to_string(ways));
    }
  }
  std::map<std::string, uint64_t> cgv;
  std::istringstream e(events), v(summary);
  for (std::string name; e >> name;) v >> cgv[name];
  ASSERT_EQ(cgv.size(), 9u) << events;
  ASSERT_EQ(spec.size(), 3u);
  const std::string levels = spec[0] + "," + spec[1] + "," + spec[2];  // I1, D1, LL
  CacheSimulation with_i1(ParseCacheSpec(levels), 64);
  StreamForeignTrace(dir + "transpose.lackey.zst", ParseTraceFormat("lackey"), true, with_i1);
  const std::vector<LevelStats>& s = with_i1.Stats(0);
  EXPECT_EQ(s[0].accesses, cgv["Ir"]);
  EXPECT_EQ(s[0].fetch_misses, cgv["I1mr"]);
  EXPECT_EQ(s[0].misses, cgv["I1mr"]);
  EXPECT_EQ(s[1].read_misses, cgv["D1mr"]);
  EXPECT_EQ(s[1].write_misses, cgv["D1mw"]);
  EXPECT_EQ(s[1].fetch_misses, 0u);
  EXPECT_EQ(s[2].read_misses, cgv["DLmr"]);
  EXPECT_EQ(s[2].write_misses, cgv["DLmw"]);
  EXPECT_EQ(s[2].fetch_misses, cgv["ILmr"]);
  EXPECT_EQ(s[2].accesses, cgv["I1mr"] + cgv["D1mr"] + cgv["D1mw"]);
  EXPECT_GT(cgv["D1mw"], cgv["D1mr"]);  // the transpose's column-wise stores: mostly write misses
  CacheSimulation data(ParseCacheSpec(spec[1] + "," + spec[2]), 64);
  StreamForeignTrace(dir + "transpose.lackey.zst", ParseTraceFormat("lackey"), false, data);
  EXPECT_EQ(data.Stats(0)[0].read_misses, cgv["D1mr"]);
  EXPECT_EQ(data.Stats(0)[0].write_misses, cgv["D1mw"]);
}

TEST(CacheSimulation, AnInstructionCacheNeedsADataLevel) {
  EXPECT_THROW(CacheSimulation(ParseCacheSpec("I1=4K/2"), 64), UsageError);
  EXPECT_THROW(CacheSimulation(ParseCacheSpec("I1=4K/2,D1=4K/2,I1=8K/2"), 64), UsageError);
}

// A 30 x 24 synthetic mesh with a hole, and `sweeps` exact sweeps on two threads.
Mesh SmallMesh(uint64_t seed) {
  SyntheticOptions so;
  so.nx = 30, so.ny = 24, so.holes = 1, so.seed = seed;
  return BuildMesh(MakeSyntheticMesh(so));
}
SmoothOptions TwoThreads(int sweeps) {
  SmoothOptions o;
  o.max_iters = sweeps;
  o.tol = -1;
  o.threads = 2;
  return o;
}

TEST(CacheSimulation, PerSweepStatsAddUpAndEveryAccessIsSimulated) {
  Mesh m = SmallMesh(3);
  const SmoothOptions o = TwoThreads(3);
  const CacheSpec levels = ParseCacheSpec("L1=2K/4,L2=16K/8");
  CacheSimulation sim(levels, 64);
  testing::RecordingConsumer rec;
  FanOut both({&sim, &rec});
  StreamMesh(m, o, "mesh", "ori", both);
  ASSERT_EQ(sim.sweeps(), 3u);
  // The same accesses replayed into a fresh simulation, thread by thread.
  CacheSimulation replay(levels, 64);
  replay.Resize(2);
  for (const Access& a : rec.all) replay.Access(a.thread, a.address, a.size, a.write);
  const std::vector<uint64_t> per = RefsPerSweep(m, 2);
  for (int t = 0; t < 2; ++t) {
    LevelStats sum;
    for (size_t s = 0; s < 3; ++s) {
      const std::vector<LevelStats> st = sim.SweepStats(t, s);
      EXPECT_EQ(st[0].accesses, per[t]) << "thread " << t << " sweep " << s;
      sum += st[0];
    }
    ExpectSame(sum, sim.Stats(t)[0], "L1 sum of sweeps");
    for (size_t l = 0; l < levels.levels.size(); ++l)
      ExpectSame(sim.Stats(t)[l], replay.Stats(t)[l], "replay");
    EXPECT_GT(sim.Stats(t)[0].misses, sim.Stats(t)[0].cold);  // small caches: capacity misses
    // Cold misses in later sweeps: none (every line was touched in sweep 1).
    EXPECT_EQ(sim.SweepStats(t, 2)[0].cold, 0u);
  }
}

TEST(CacheSimulation, ByArrayAddsUpAndFollowsEachArraysAccesses) {
  Mesh m = SmallMesh(5);
  const SmoothOptions o = TwoThreads(2);
  // A last level that never evicts: its misses are the cold ones, which a naive first-touch
  // count attributes to the array whose access first touched a line.
  const CacheSpec levels = ParseCacheSpec("L1=2K/4,L2=16K/8,L3=64M/16");
  CacheSimulation sim(levels, 64);
  sim.CountByArray();
  testing::RecordingConsumer rec;
  FanOut both({&sim, &rec});
  StreamMesh(m, o, "mesh", "ori", both);
  std::map<std::pair<int, int>, uint64_t> accesses, cold;  // (thread, array)
  std::set<std::pair<int, uint64_t>> seen;                 // (thread, line)
  for (const Access& a : rec.all) {
    ++accesses[{a.thread, a.array}];
    bool fresh = false;
    for (uint64_t l = a.address / 64; l <= (a.address + a.size - 1) / 64; ++l)
      fresh |= seen.insert({a.thread, l}).second;
    cold[{a.thread, a.array}] += fresh;
  }
  int arrays_seen = 0;
  for (int t = 0; t < 2; ++t)
    for (size_t l = 0; l < 3; ++l) {
      uint64_t lookups = 0, misses = 0;
      for (int a = 0; a < 256; ++a) {
        lookups += sim.ArrayAccesses(t, a, l), misses += sim.ArrayMisses(t, a, l);
        if (l == 0) {
          EXPECT_EQ(sim.ArrayAccesses(t, a, 0), accesses[std::make_pair(t, a)])
              << "thread " << t << " array " << a;
          arrays_seen += accesses[std::make_pair(t, a)] > 0;
        }
        if (l == 2) {
          EXPECT_EQ(sim.ArrayMisses(t, a, 2), cold[std::make_pair(t, a)]) << "array " << a;
        }
      }
      EXPECT_EQ(lookups, sim.Stats(t)[l].accesses) << "thread " << t << " level " << l;
      EXPECT_EQ(misses, sim.Stats(t)[l].misses) << "thread " << t << " level " << l;
    }
  EXPECT_GE(arrays_seen, 2 * 7);  // interior, v2v, v2t, tri, qualities, xy, bound: each thread
  Table t(CacheSimulation::ArrayColumns());
  sim.AppendArrayRows(&t);
  EXPECT_EQ(t.Rows(), static_cast<size_t>(arrays_seen) * 3);
  EXPECT_EQ(t.Row(0)[3], "interior");
  // Without CountByArray nothing is counted, and the counts are per array of this run only.
  CacheSimulation plain(levels, 64);
  StreamMesh(m, o, "mesh", "ori", plain);
  EXPECT_EQ(plain.ArrayAccesses(0, static_cast<int>(Array::kCoords), 0), 0u);
}

// Per-sweep state and rows follow the accesses: of 4 streams and 5 sweeps, one stream accesses
// in sweeps 2 and 4, another in sweep 5 only; the rest never. Rows: every stream's total, and
// one row per (stream, sweep) that had an access.
TEST(CacheSimulation, PerSweepRowsOnlyWhereAStreamHasAccesses) {
  CacheSimulation sim(ParseCacheSpec("L1=1K/2"), 64);
  StreamInfo info;
  info.input = "t";
  info.threads = 4;
  sim.Begin(info);
  for (int s = 1; s <= 5; ++s) {
    sim.BeginSweep(s - 1);
    if (s == 2 || s == 4) sim.Access(1, 64 * s, 8, false);
    if (s == 4) sim.Access(1, 64 * s, 8, true);
    if (s == 5) sim.Access(3, 0, 8, false);
  }
  sim.End();
  ASSERT_EQ(sim.sweeps(), 5u);
  EXPECT_EQ(sim.SweepStats(1, 3)[0].accesses, 2u);
  EXPECT_EQ(sim.SweepStats(1, 2)[0].accesses, 0u);
  EXPECT_EQ(sim.SweepStats(3, 4)[0].misses, 1u);
  EXPECT_EQ(sim.SweepStats(0, 4)[0].accesses, 0u);
  Table t(CacheSimulation::Columns());
  sim.AppendRows(&t, true);
  std::vector<std::string> where;
  for (size_t r = 0; r < t.Rows(); ++r) where.push_back(t.Row(r)[2] + ":" + t.Row(r)[3]);
  EXPECT_EQ(where,
            (std::vector<std::string>{"0:all", "1:all", "1:2", "1:4", "2:all", "3:all", "3:5"}));
}

TEST(CacheSpec, Associativity) {
  const auto w = ParseCacheSpec("westmere-ex").levels;
  EXPECT_EQ(w[0].ways, 8u);
  EXPECT_EQ(w[1].ways, 8u);
  EXPECT_EQ(w[2].ways, 24u);
  const auto c = ParseCacheSpec("L1=48K/12,L2=1280K/20,LLC=30M").levels;
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
