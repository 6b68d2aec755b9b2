// SetAssociativeCache, one level on its own: FIFO and random replacement by hand, every policy
// against the most-recent-first array it replaced (victims, invalidations and renumbering
// included), the hit loop against one access at a time, and the slots the many-core simulator's
// back-invalidation filter keeps. (Its counts against models and naive hierarchies:
// cache_sim_test.)
#include "analysis/set_associative_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace meshreuse {
namespace {

TEST(SetAssociativeCache, FifoAndRandomReplacement) {
  // One set of two ways. FIFO: a hit does not refresh, so after 0, 1, 0 the next miss evicts 0.
  SetAssociativeCache fifo(128, 2, 64, Replacement::kFifo);
  EXPECT_FALSE(fifo.Access(0));
  EXPECT_FALSE(fifo.Access(1));
  EXPECT_TRUE(fifo.Access(0));
  EXPECT_FALSE(fifo.Access(2));  // evicts 0, the first in
  EXPECT_FALSE(fifo.Access(0));
  EXPECT_TRUE(fifo.Access(2));
  SetAssociativeCache lru(128, 2, 64);
  EXPECT_FALSE(lru.Access(0));
  EXPECT_FALSE(lru.Access(1));
  EXPECT_TRUE(lru.Access(0));
  EXPECT_FALSE(lru.Access(2));  // evicts 1, the least recent
  EXPECT_TRUE(lru.Access(0));
  // Random: deterministic for a stream, and never more than `ways` lines in a set.
  auto run = [] {
    SetAssociativeCache r(256, 4, 64, Replacement::kRandom);
    std::vector<bool> hits;
    for (uint64_t i = 0; i < 200; ++i) hits.push_back(r.Access(i * 7 % 9));
    return hits;
  };
  EXPECT_EQ(run(), run());
  SetAssociativeCache r(256, 4, 64, Replacement::kRandom);
  for (uint64_t l = 0; l < 4; ++l) r.Access(l);
  for (uint64_t l = 0; l < 4; ++l) EXPECT_TRUE(r.Access(l));  // four fit in four ways
}

// One level as valgrind's simulator and this class before issue 40 kept it: per set an array with
// the most recent line first, a hit moving its line to the front (LRU), a miss evicting the last
// way, an invalidation moving the ways after it up; random replacement by position, with the
// same xorshift sequence. The fast level (signatures, tags and stamps) must agree access by access,
// victim by victim, for every policy, with padding (ways not a multiple of four) and more than 32
// ways (a second group of signatures), under lookups, invalidations and membership tests.
struct ArrayLevel {
  uint64_t sets;
  uint32_t ways;
  Replacement policy;
  std::vector<std::vector<uint64_t>> s;  // tags = line + 1, 0 empty
  uint64_t rng = 0x9E3779B97F4A7C15ull, victim = ~uint64_t{0};
  ArrayLevel(uint64_t sets_, uint32_t ways_, Replacement p)
      : sets(sets_), ways(ways_), policy(p), s(sets_, std::vector<uint64_t>(ways_, 0)) {}
  bool Access(uint64_t line) {
    std::vector<uint64_t>& set = s[line % sets];
    const auto it = std::find(set.begin(), set.end(), line + 1);
    if (it != set.end()) {
      if (policy == Replacement::kLru) std::rotate(set.begin(), it, it + 1);
      return true;
    }
    if (policy == Replacement::kRandom) {
      const auto empty = std::find(set.begin(), set.end(), 0u);
      if (empty != set.end()) {
        *empty = line + 1;
        victim = ~uint64_t{0};
        return false;
      }
      rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
      victim = set[rng % ways] - 1;
      set[rng % ways] = line + 1;
      return false;
    }
    victim = set.back() - 1;
    std::rotate(set.begin(), set.end() - 1, set.end());
    set.front() = line + 1;
    return false;
  }
  bool Invalidate(uint64_t line) {
    std::vector<uint64_t>& set = s[line % sets];
    const auto it = std::find(set.begin(), set.end(), line + 1);
    if (it == set.end()) return false;
    std::rotate(it, it + 1, set.end());
    set.back() = 0;
    return true;
  }
};

TEST(SetAssociativeCache, MatchesTheMostRecentFirstArrayOnRandomStreams) {
  // renumber: the stamps renumbered every few uses (the clock's limit made small), or never.
  // tags_from: the step from which lines 2^32 apart come (the level keeps its tags from the first
  // of them on, written then from the signatures of the full level): at once, or half way.
  // base: the pool's first line; 2^32 - 20 puts the pool across a high half's end, so that among
  // the tags of one half (no tag kept) come the next half's, and its tag of low half 0, 2^32 (an
  // empty way's signature: it must make the level keep its tags).
  for (const uint64_t base : {uint64_t{0}, (uint64_t{1} << 32) - 20})
    for (const int tags_from : {0, 2000})
      for (const bool renumber : {false, true})
        for (const Replacement p : {Replacement::kLru, Replacement::kFifo, Replacement::kRandom})
          for (const uint32_t ways : {1u, 2u, 3u, 4u, 7u, 8u, 12u, 24u, 33u, 40u})
            for (const uint64_t sets : {uint64_t{1}, uint64_t{3}, uint64_t{4}}) {
              SetAssociativeCache fast(sets * ways * 64, ways, 64, p);
              if (renumber) fast.LimitClockForTest(ways + 1 + static_cast<uint32_t>(sets));
              ArrayLevel ref(sets, ways, p);
              std::mt19937_64 rng(ways * 131 + sets + static_cast<uint64_t>(p));
              // Lines from a pool a little larger than the cache, some 2^32 lines apart (the same
              // signature in one set: only the full tag tells them apart).
              const uint64_t pool = sets * ways + ways / 2 + 2;
              const std::string what = std::string(ReplacementName(p)) + " ways " +
                                       std::to_string(ways) + " sets " + std::to_string(sets) +
                                       (renumber ? " renumbered" : "") + " tags from " +
                                       std::to_string(tags_from) + " base " + std::to_string(base);
              for (int i = 0; i < 4000; ++i) {
                uint64_t line = base + rng() % pool;
                if (i >= tags_from && rng() % 5 == 0) line += uint64_t{1} << 32;
                const int op = static_cast<int>(rng() % 10);
                if (op == 0) {
                  ASSERT_EQ(fast.Invalidate(line), ref.Invalidate(line)) << what << " step " << i;
                } else if (op == 1) {
                  const bool held = std::count(ref.s[line % sets].begin(), ref.s[line % sets].end(),
                                               line + 1) > 0;
                  ASSERT_EQ(fast.Contains(line), held) << what << " step " << i;
                } else {
                  const bool hit = fast.Access(line);
                  ASSERT_EQ(hit, ref.Access(line)) << what << " step " << i;
                  if (!hit) {
                    ASSERT_EQ(fast.victim(), ref.victim) << what << " step " << i;
                  }
                }
              }
            }
}

// HitRun (the simulators' loop over first-level hits) against Access one line at a time: the
// same hits, and every access it does not take is one Access would miss (or one of another
// thread). Pools within one high half of the tag (HitRun reads no tag there), with the lines whose
// tag's low half is 0 (an empty way's signature; invalidations keep ways empty), and mixed halves
// (confirmed on the tag); the clock's limit small or not; a line often repeated (a run takes its
// last line again without a lookup or a stamp); and misses done in the run (on_miss installs
// the line and the run goes on, as the many-core simulator's MissPlain does) or not.
TEST(SetAssociativeCache, HitRunEqualsAccessOnRandomStreams) {
  for (const Replacement p : {Replacement::kLru, Replacement::kFifo, Replacement::kRandom})
    for (const uint32_t ways : {2u, 8u, 24u, 40u})
      for (const uint64_t sets : {uint64_t{4}, uint64_t{3}})
        for (const bool mixed : {false, true})
          for (const bool renumber : {false, true})
            for (const bool in_run : {false, true}) {
              SetAssociativeCache run(sets * ways * 64, ways, 64, p),
                  one(sets * ways * 64, ways, 64, p);
              if (renumber) run.LimitClockForTest(ways + 5), one.LimitClockForTest(ways + 5);
              std::mt19937_64 rng(ways * 7 + sets + 2 * static_cast<uint64_t>(p) + mixed);
              const uint64_t base =
                  (uint64_t{5} << 32) - 40;  // tags 2^32 * 5 - 39 ...: low half 0 among them
              const uint64_t pool = sets * ways + ways + 3;
              const std::string what = std::string(ReplacementName(p)) + " ways " +
                                       std::to_string(ways) + " sets " + std::to_string(sets) +
                                       (mixed ? " mixed" : "") + (renumber ? " renumbered" : "") +
                                       (in_run ? " misses in the run" : "");
              std::vector<uint64_t> lines(64);
              std::vector<uint8_t> thread(64);
              std::vector<char> hit_run(64), hit_one(64);  // access by access
              std::vector<char> done(64);                  // a miss on_miss did
              uint64_t hits = 0;
              for (int batch = 0; batch < 300; ++batch) {
                for (int k = 0; k < 6; ++k) {  // empty ways again (signature 0)
                  const uint64_t line = base + rng() % pool;
                  ASSERT_EQ(run.Invalidate(line), one.Invalidate(line)) << what;
                }
                for (size_t k = 0; k < lines.size(); ++k) {
                  lines[k] = base + rng() % pool;
                  if (mixed && rng() % 7 == 0) lines[k] += uint64_t{3} << 32;
                  if (k > 0 && rng() % 3 == 0) lines[k] = lines[k - 1];  // a run's last line again
                  thread[k] = rng() % 9 == 0;  // thread 1's accesses are not this level's
                }
                std::fill(hit_run.begin(), hit_run.end(), 0);
                std::fill(hit_one.begin(), hit_one.end(), 0);
                std::fill(done.begin(), done.end(), 0);
                for (size_t i = 0; i < lines.size();) {
                  i = SetAssociativeCache::WithGroups(run.groups(), [&](auto g) {
                    return run.HitRun<decltype(g)::value>(
                        i, lines.size(),
                        [&](size_t k, uint64_t& line) {
                          line = lines[k];
                          return thread[k] == 0;
                        },
                        [&](size_t k, uint64_t) { hit_run[k] = 1; },
                        [&](size_t k, uint64_t line) {
                          if (!in_run || rng() % 4 == 0) return false;  // the loop below does it
                          run.InstallMissed(line);
                          done[k] = 1;
                          return true;
                        });
                  });
                  if (i == lines.size()) break;
                  // A miss, a hit with the clock at its limit, or any access after a miss done
                  // in the run that changed the level's tags or left the clock near its limit.
                  if (thread[i] == 0) {
                    const bool hit = run.Access(lines[i]);
                    hit_run[i] = hit;
                    ASSERT_TRUE(!hit || renumber || (i > 0 && done[i - 1]))
                        << what << " batch " << batch << " at " << i << ": HitRun stopped at a hit";
                  }
                  ++i;
                }
                for (size_t k = 0; k < lines.size(); ++k)
                  if (thread[k] == 0) hit_one[k] = one.Access(lines[k]);
                ASSERT_EQ(hit_run, hit_one) << what << " batch " << batch;
                hits += static_cast<uint64_t>(std::count(hit_one.begin(), hit_one.end(), 1));
              }
              EXPECT_GT(hits, 1000u) << what;  // the runs had hits to take
            }
}

// SlotOf and ForEachLine (the many-core simulator's back-invalidation filter keeps a byte per
// slot): the lines ForEachLine lists are exactly those Contains finds, each with a slot of its
// own below slots() inside its set's, which stays the line's while it is held (hits, other
// installs and invalidations in its set); a line not held has none. Within one high half, and
// across halves (tags kept); LRU and FIFO (random moves ways: no slot kept there).
TEST(SetAssociativeCache, SlotsStayWhileHeldAndLinesListAsHeld) {
  for (const Replacement p : {Replacement::kLru, Replacement::kFifo})
    for (const uint32_t ways : {2u, 8u, 24u})
      for (const uint64_t sets : {uint64_t{4}, uint64_t{3}})
        for (const bool mixed : {false, true}) {
          SetAssociativeCache c(sets * ways * 64, ways, 64, p);
          std::mt19937_64 rng(ways * 11 + sets + static_cast<uint64_t>(p) + 5 * mixed);
          const uint64_t base = (uint64_t{5} << 32) - 40;
          const uint64_t pool = sets * ways * 2 + 5;
          const std::string what = std::string(ReplacementName(p)) + " ways " +
                                   std::to_string(ways) + " sets " + std::to_string(sets) +
                                   (mixed ? " mixed" : "");
          std::vector<uint64_t> universe;
          for (uint64_t k = 0; k < pool; ++k) {
            universe.push_back(base + k);
            if (mixed) universe.push_back(base + k + (uint64_t{3} << 32));
          }
          std::map<uint64_t, uint64_t> slot;  // of each line held, as first seen
          for (int step = 0; step < 4000; ++step) {
            const uint64_t line = universe[rng() % universe.size()];
            if (rng() % 5 == 0)
              c.Invalidate(line);
            else
              c.Access(line);
            std::set<uint64_t> listed;
            c.ForEachLine([&](uint64_t l) { EXPECT_TRUE(listed.insert(l).second) << what; });
            std::set<uint64_t> slots;
            for (const uint64_t l : universe) {
              const uint64_t k = c.SlotOf(l);
              ASSERT_EQ(c.Contains(l), listed.count(l) == 1) << what << " step " << step;
              if (!c.Contains(l)) {
                ASSERT_EQ(k, ~uint64_t{0}) << what;
                slot.erase(l);
                continue;
              }
              ASSERT_LT(k, c.slots()) << what;
              ASSERT_GE(k, c.FirstSlotOf(l)) << what;
              ASSERT_LT(k, c.FirstSlotOf(l) + ways) << what;
              ASSERT_TRUE(slots.insert(k).second) << what << ": two lines in one slot";
              const auto it = slot.emplace(l, k).first;
              ASSERT_EQ(it->second, k) << what << " step " << step << ": a held line moved";
            }
            ASSERT_EQ(listed.size(), slot.size()) << what;
          }
        }
}

}  // namespace
}  // namespace meshreuse
