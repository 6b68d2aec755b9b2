// The many-core simulator (analysis/multicore_sim.h): hand-worked streams (two cores thrashing a
// shared set, a write invalidating another core's copy, an inclusive eviction removing a private
// line, a prefetched line hiding a miss), exactness against today's simulator (p = 1 on
// Westmere-EX without inclusion; a machine of private levels at every p), and a naive reference
// (one std::list per set, shared levels, inclusion, coherence by scanning every core, the
// prefetcher, written the obvious way) equal to it on random multi-stream traces and on small
// meshes at p = 1..8, both placements, inclusive and not.
#include "analysis/multicore_sim.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <list>
#include <optional>
#include <random>
#include <set>

#include "analysis/cache_sim.h"
#include "core/error.h"
#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

Machine Make(int sockets, int cores, std::vector<MachineLevel> levels, bool coherence = true) {
  Machine m;
  m.name = "test";
  m.sockets = sockets, m.cores_per_socket = cores;
  m.line_bytes = 64;
  m.levels = std::move(levels);
  m.memory_local = 100, m.memory_remote = 200;
  m.coherence = coherence;
  return m;
}

MachineLevel Level(const char* name, uint64_t bytes, uint32_t ways, bool shared,
                   bool inclusive = false, bool prefetch = false, double latency = 10) {
  MachineLevel l;
  l.cache = CacheLevel(name, bytes, ways, Replacement::kLru, {latency, latency});
  l.shared = shared, l.inclusive = inclusive, l.prefetch = prefetch;
  return l;
}

// --- hand-worked streams ----------------------------------------------------------------------

TEST(Multicore, TwoCoresThrashOneSharedSet) {
  // One socket, two cores; L1 one line each; the shared L2 one set of two ways. Core 0 cycles
  // lines 0 and 2, core 1 lines 4 and 6: four lines through two ways, every access misses both.
  MulticoreSimulation sim(Make(1, 2, {Level("L1", 64, 1, false), Level("L2", 128, 2, true)}),
                          Placement::kCompact);
  sim.Resize(2);
  for (int i = 0; i < 6; ++i) {
    sim.Access(0, (i % 2) * 128, 8, false);
    sim.Access(1, 256 + (i % 2) * 128, 8, false);
  }
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(sim.Stats(t).levels[1].accesses, 6u);
    EXPECT_EQ(sim.Stats(t).levels[1].misses, 6u);  // each line evicted by the other core's two
    EXPECT_EQ(sim.Stats(t).levels[1].cold, 2u);
    EXPECT_EQ(sim.Stats(t).memory_local, 6u);
  }
  // Alone, core 0's two lines fit the shared set: two cold misses, then hits.
  MulticoreSimulation alone(Make(1, 2, {Level("L1", 64, 1, false), Level("L2", 128, 2, true)}),
                            Placement::kCompact);
  alone.Resize(1);
  for (int i = 0; i < 6; ++i) alone.Access(0, (i % 2) * 128, 8, false);
  EXPECT_EQ(alone.Stats(0).levels[1].misses, 2u);
}

TEST(Multicore, AWriteInvalidatesAnotherCoresCopy) {
  MulticoreSimulation sim(Make(1, 2, {Level("L1", 1024, 2, false), Level("L2", 4096, 4, true)}),
                          Placement::kCompact);
  sim.Resize(2);
  sim.Access(0, 0, 8, false);  // core 0 reads line 0: cold everywhere
  sim.Access(1, 0, 8, true);   // core 1 writes it: L1 miss, shared L2 hit; core 0's copy goes
  sim.Access(0, 0, 8, false);  // core 0: an L1 coherence miss, the shared L2 hit
  const ThreadStats& a = sim.Stats(0);
  EXPECT_EQ(a.levels[0].misses, 2u);
  EXPECT_EQ(a.levels[0].cold, 1u);
  EXPECT_EQ(a.levels[0].coherence, 1u);
  EXPECT_EQ(a.levels[1].misses, 1u);
  EXPECT_EQ(sim.Stats(1).invalidations_sent, 1u);
  // Without coherence core 0's copy stays: a hit.
  MulticoreSimulation off(
      Make(1, 2, {Level("L1", 1024, 2, false), Level("L2", 4096, 4, true)}, false),
      Placement::kCompact);
  off.Resize(2);
  off.Access(0, 0, 8, false);
  off.Access(1, 0, 8, true);
  off.Access(0, 0, 8, false);
  EXPECT_EQ(off.Stats(0).levels[0].misses, 1u);
}

TEST(Multicore, AWriteInvalidatesAnotherSocketsSharedLevel) {
  MulticoreSimulation sim(Make(2, 1, {Level("L1", 64, 1, false), Level("L2", 4096, 4, true)}),
                          Placement::kCompact);
  sim.Resize(2);
  sim.Access(0, 0, 8, false);   // socket 0 holds line 0 in L1 and L2
  sim.Access(0, 64, 8, false);  // line 1 pushes line 0 out of core 0's one-line L1
  sim.Access(1, 0, 8, true);    // core 1 (socket 1) writes line 0: socket 0's L2 copy goes
  sim.Access(0, 0, 8, false);   // core 0: misses L1 and its socket's L2 (coherence), memory
  EXPECT_EQ(sim.Stats(0).levels[1].coherence, 1u);
  EXPECT_EQ(sim.Stats(0).levels[1].misses, 3u);
  EXPECT_EQ(sim.Stats(0).levels[0].coherence, 0u);  // L1 had lost it to capacity, not coherence
  EXPECT_EQ(sim.Stats(1).memory_remote, 1u);        // first touch: the pages live on socket 0
}

TEST(Multicore, AnInclusiveEvictionRemovesAPrivateLine) {
  // L1: one set of two ways; the inclusive L2: two sets of one way. Lines 0 and 2 share L2's
  // set 0: bringing 2 in evicts 0 from L2 and so from L1, which still had room for it.
  for (bool inclusive : {true, false}) {
    MulticoreSimulation sim(
        Make(1, 1, {Level("L1", 128, 2, false), Level("L2", 128, 1, true, inclusive)}),
        Placement::kCompact);
    sim.Resize(1);
    sim.Access(0, 0, 8, false);
    sim.Access(0, 128, 8, false);
    sim.Access(0, 0, 8, false);
    // Two victims: line 0 when 2 comes in, then line 2 when 0 comes back.
    EXPECT_EQ(sim.Stats(0).levels[0].inclusion_victims, inclusive ? 2u : 0u);
    EXPECT_EQ(sim.Stats(0).levels[0].misses, inclusive ? 3u : 2u);
  }
}

TEST(Multicore, APrefetchedLineIsBroughtIntoTheLevelsBelowToo) {
  // L1: 2 lines (1 set x 2 ways) with the prefetcher; L2 shared, inclusive, large.
  MulticoreSimulation sim(
      Make(1, 1, {Level("L1", 128, 2, false, false, true), Level("L2", 64 * 64, 4, true, true)}),
      Placement::kCompact);
  sim.Resize(1);
  for (uint64_t line : {0, 2, 4}) sim.Access(0, line * 64, 8, false);  // each brings line + 1
  sim.Access(0, 64, 8, false);  // line 1: long gone from L1, but in L2 since its prefetch
  const ThreadStats& s = sim.Stats(0);
  EXPECT_EQ(s.levels[0].misses, 4u);
  EXPECT_EQ(s.levels[0].prefetches, 4u);  // 1, 3, 5, then 2 again (evicted from L1 by then)
  EXPECT_EQ(s.levels[1].accesses, 4u);
  EXPECT_EQ(s.levels[1].misses, 3u);  // lines 0, 2, 4; line 1 hits
  EXPECT_EQ(s.levels[1].prefetches, 0u);
  EXPECT_EQ(s.memory_local, 3u);
}

TEST(Multicore, ANextLinePrefetchHidesAMiss) {
  MulticoreSimulation sim(Make(1, 1, {Level("L1", 1024, 2, false, false, true)}),
                          Placement::kCompact);
  sim.Resize(1);
  for (uint64_t a = 0; a < 8 * 64; a += 64) sim.Access(0, a, 8, false);  // a scan of 8 lines
  const CoreLevelStats& s = sim.Stats(0).levels[0];
  EXPECT_EQ(s.misses, 4u);  // lines 0, 2, 4, 6 miss; each brings the next
  EXPECT_EQ(s.prefetch_hits, 4u);
  EXPECT_EQ(s.prefetches, 4u);
  EXPECT_EQ(s.cold, 4u);
}

TEST(Multicore, PlacementAndMachines) {
  const Machine w = ParseMachine("westmere-ex");
  EXPECT_EQ(w.cores(), 32);
  EXPECT_EQ(w.private_levels(), 2u);
  EXPECT_TRUE(w.levels[2].inclusive);
  EXPECT_EQ(PlaceThreads(w, 4, Placement::kCompact), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(PlaceThreads(w, 4, Placement::kScatter), (std::vector<int>{0, 8, 16, 24}));
  EXPECT_EQ(PlaceThreads(w, 6, Placement::kScatter), (std::vector<int>{0, 8, 16, 24, 1, 9}));
  EXPECT_THROW(PlaceThreads(w, 33, Placement::kCompact), UsageError);
  testing::TempDir dir;
  std::ofstream(dir / "m.txt") << "# two sockets\nname small\nsockets 2\ncores 2\nline 64\n"
                                  "memory 100 200\nnuma interleave\nprivate L1=1K/2@4\n"
                                  "shared L2=8K/4@20 inclusive\nprefetch L1\n";
  const Machine m = ParseMachine(dir / "m.txt");
  EXPECT_EQ(m.name, "small");
  EXPECT_EQ(m.cores(), 4);
  EXPECT_TRUE(m.levels[0].prefetch);
  EXPECT_TRUE(m.levels[1].shared && m.levels[1].inclusive);
  EXPECT_EQ(m.numa, Numa::kInterleave);
  std::ofstream(dir / "bad.txt") << "sockets 2\nshared L2=8K/4@20\nprivate L1=1K/2@4\n"
                                    "memory 1 2\n";
  EXPECT_THROW(ParseMachine(dir / "bad.txt"), InputError);  // private after shared
  std::ofstream(dir / "bad2.txt") << "sockets 2\nwarp 9\n";
  EXPECT_THROW(ParseMachine(dir / "bad2.txt"), InputError);
  Machine p = w;
  SetPrefetch(&p, "L1,L2");
  EXPECT_TRUE(p.levels[0].prefetch && p.levels[1].prefetch && !p.levels[2].prefetch);
  EXPECT_THROW(SetPrefetch(&p, "L9"), UsageError);
}

// --- exactness against today's simulator -------------------------------------------------------

Mesh SmallMesh(int nx = 22, int ny = 18) {
  SyntheticOptions so;
  so.nx = nx, so.ny = ny, so.holes = 1, so.seed = 7;
  return BuildMesh(MakeSyntheticMesh(so));
}

// Each thread of a traced run against CacheSimulation's stream of the same thread.
void ExpectEqualsPerStream(const Machine& m, const CacheSpec& spec, int p, Placement pl,
                           int interleave) {
  Mesh a = SmallMesh(), b = SmallMesh();
  SmoothOptions o;
  o.max_iters = 2, o.tol = -1, o.threads = p, o.interleave = interleave;
  MulticoreSimulation multi(m, pl);
  StreamMesh(a, o, "mesh", "ori", multi);
  CacheSimulation single(spec, 64);
  o.interleave = kSerialShares;
  StreamMesh(b, o, "mesh", "ori", single);
  for (int t = 0; t < p; ++t)
    for (size_t l = 0; l < spec.levels.size(); ++l) {
      const LevelStats& s = single.Stats(t)[l];
      const CoreLevelStats& c = multi.Stats(t).levels[l];
      SCOPED_TRACE("p " + std::to_string(p) + " thread " + std::to_string(t) + " level " +
                   std::to_string(l));
      EXPECT_EQ(c.accesses, s.accesses);
      EXPECT_EQ(c.misses, s.misses);
      EXPECT_EQ(c.cold, s.cold);
      EXPECT_EQ(c.read_misses, s.read_misses);
      EXPECT_EQ(c.write_misses, s.write_misses);
    }
}

TEST(Multicore, OneCoreOfWestmereWithoutInclusionIsTodaysSimulator) {
  Machine w = ParseMachine("westmere-ex");
  w.levels[2].inclusive = false;
  ExpectEqualsPerStream(w, ParseCacheSpec("westmere-ex"), 1, Placement::kCompact, kSerialShares);
}

TEST(Multicore, PrivateLevelsAloneAreTodaysSimulatorAtEveryP) {
  const Machine m = Make(2, 4, {Level("L1", 2048, 4, false), Level("L2", 16384, 8, false)}, false);
  const CacheSpec spec = ParseCacheSpec("L1=2K/4,L2=16K/8");
  for (int p = 1; p <= 8; ++p)
    for (Placement pl : {Placement::kCompact, Placement::kScatter})
      for (int il : {kSerialShares, 1, kAccessGrain}) ExpectEqualsPerStream(m, spec, p, pl, il);
}

// --- the naive reference -----------------------------------------------------------------------

// Every rule of multicore_sim.h written the obvious way: lists per set (most recent first), a
// std::set per owner, and coherence by looking in every other core and socket.
struct Naive {
  struct Cache {
    uint64_t sets, ways;
    std::vector<std::list<uint64_t>> s;
    std::set<uint64_t> prefetched;
    std::list<uint64_t>& Set(uint64_t line) { return s[line % sets]; }
    bool Has(uint64_t line) {
      auto& x = Set(line);
      return std::find(x.begin(), x.end(), line) != x.end();
    }
    // LRU access: true on a hit; on a miss *victim is what fell out (or none).
    bool Touch(uint64_t line, std::optional<uint64_t>* victim) {
      auto& x = Set(line);
      auto it = std::find(x.begin(), x.end(), line);
      if (it != x.end()) {
        x.erase(it);
        x.push_front(line);
        return true;
      }
      x.push_front(line);
      victim->reset();
      if (x.size() > ways) {
        *victim = x.back();
        x.pop_back();
      }
      return false;
    }
    bool Remove(uint64_t line) {
      auto& x = Set(line);
      auto it = std::find(x.begin(), x.end(), line);
      if (it == x.end()) return false;
      x.erase(it);
      return true;
    }
  };
  struct Owner {
    std::vector<Cache> caches;
    std::set<uint64_t> seen, removed;
  };
  Machine m;
  std::vector<int> core_of, thread_of;
  std::vector<Owner> cores, sockets;
  std::vector<ThreadStats> stats;
  size_t np;
  Naive(const Machine& mm, int threads, Placement pl) : m(mm) {
    core_of = PlaceThreads(m, threads, pl);
    thread_of.assign(m.cores(), -1);
    for (int t = 0; t < threads; ++t) thread_of[core_of[t]] = t;
    np = m.private_levels();
    auto make = [&](size_t from, size_t to) {
      Owner o;
      for (size_t i = from; i < to; ++i) {
        const uint64_t sets = m.levels[i].cache.bytes / m.line_bytes / m.levels[i].cache.ways;
        o.caches.push_back(
            {sets, m.levels[i].cache.ways, std::vector<std::list<uint64_t>>(sets), {}});
      }
      return o;
    };
    for (int c = 0; c < m.cores(); ++c) cores.push_back(make(0, np));
    for (int s = 0; s < m.sockets; ++s) sockets.push_back(make(np, m.levels.size()));
    stats.assign(threads, ThreadStats());
    for (auto& s : stats) s.levels.resize(m.levels.size());
  }
  void Evicted(int socket, uint64_t line) {  // from an inclusive shared level
    for (int k = 0; k < m.cores_per_socket; ++k) {
      const int c = socket * m.cores_per_socket + k;
      for (size_t i = 0; i < np; ++i)
        if (cores[c].caches[i].Remove(line) && thread_of[c] >= 0)
          ++stats[thread_of[c]].levels[i].inclusion_victims;
    }
  }
  void Access(int t, uint64_t address, uint32_t size, bool write) {
    const int core = core_of[t], socket = core / m.cores_per_socket;
    const uint64_t first = address / 64, last = (address + std::max(size, 1u) - 1) / 64;
    bool all_missed = true, cold = false, reached_shared = false;
    for (size_t i = 0; i < m.levels.size(); ++i) {
      const bool shared = i >= np;
      reached_shared = reached_shared || shared;
      Owner& o = shared ? sockets[socket] : cores[core];
      Cache& c = o.caches[shared ? i - np : i];
      CoreLevelStats& s = stats[t].levels[i];
      ++s.accesses;
      if (i == 0 || i == np) cold = false;
      bool hit = true, coh = false;
      for (uint64_t l = first; l <= last; ++l) {
        std::optional<uint64_t> victim;
        if (c.Touch(l, &victim)) {
          if (m.levels[i].prefetch && c.prefetched.erase(l)) ++s.prefetch_hits, o.seen.insert(l);
          continue;
        }
        hit = false;
        if (i == 0 || i == np) cold = o.seen.insert(l).second || cold;
        coh = o.removed.count(l) || coh;
        c.prefetched.erase(l);
        if (shared && m.levels[i].inclusive && victim) Evicted(socket, *victim);
        if (m.levels[i].prefetch && !c.Has(l + 1)) {
          c.prefetched.insert(l + 1);
          ++s.prefetches;
          for (size_t j = i; j < m.levels.size(); ++j) {  // this level and those below lacking it
            const bool sj = j >= np;
            Owner& oj = sj ? sockets[socket] : cores[core];
            Cache& cj = oj.caches[sj ? j - np : j];
            if (cj.Has(l + 1)) continue;
            std::optional<uint64_t> v2;
            cj.Touch(l + 1, &v2);
            oj.removed.erase(l + 1);  // back in the owner: no longer taken by coherence
            if (sj && m.levels[j].inclusive && v2) Evicted(socket, *v2);
          }
        }
      }
      if (hit) {
        all_missed = false;
        break;
      }
      ++s.misses;
      if (cold) ++s.cold;
      if (coh) ++s.coherence;
      ++(write ? s.write_misses : s.read_misses);
    }
    for (uint64_t l = first; l <= last; ++l) {
      cores[core].removed.erase(l);
      if (reached_shared) sockets[socket].removed.erase(l);
    }
    if (all_missed) {
      const int home =
          m.numa == Numa::kFirstTouch ? 0 : static_cast<int>((first * 64 >> 12) % m.sockets);
      ++(home == socket ? stats[t].memory_local : stats[t].memory_remote);
    }
    if (write && m.coherence)
      for (uint64_t l = first; l <= last; ++l) {
        for (int d = 0; d < m.cores(); ++d) {
          if (d == core) continue;
          bool held = false;
          for (size_t i = 0; i < np; ++i) held = cores[d].caches[i].Remove(l) || held;
          if (held) cores[d].removed.insert(l), ++stats[t].invalidations_sent;
        }
        for (int s = 0; s < m.sockets; ++s) {
          if (s == socket) continue;
          bool held = false;
          for (Cache& c : sockets[s].caches) held = c.Remove(l) || held;
          if (held) sockets[s].removed.insert(l), ++stats[t].invalidations_sent;
        }
      }
  }
};

void ExpectSame(const ThreadStats& a, const ThreadStats& b, const std::string& what) {
  ASSERT_EQ(a.levels.size(), b.levels.size()) << what;
  for (size_t i = 0; i < a.levels.size(); ++i) {
    SCOPED_TRACE(what + " level " + std::to_string(i));
    EXPECT_EQ(a.levels[i].accesses, b.levels[i].accesses);
    EXPECT_EQ(a.levels[i].misses, b.levels[i].misses);
    EXPECT_EQ(a.levels[i].cold, b.levels[i].cold);
    EXPECT_EQ(a.levels[i].coherence, b.levels[i].coherence);
    EXPECT_EQ(a.levels[i].inclusion_victims, b.levels[i].inclusion_victims);
    EXPECT_EQ(a.levels[i].prefetches, b.levels[i].prefetches);
    EXPECT_EQ(a.levels[i].prefetch_hits, b.levels[i].prefetch_hits);
    EXPECT_EQ(a.levels[i].read_misses, b.levels[i].read_misses);
    EXPECT_EQ(a.levels[i].write_misses, b.levels[i].write_misses);
  }
  EXPECT_EQ(a.memory_local, b.memory_local) << what;
  EXPECT_EQ(a.memory_remote, b.memory_remote) << what;
  EXPECT_EQ(a.invalidations_sent, b.invalidations_sent) << what;
}

std::vector<Machine> SmallMachines() {
  std::vector<Machine> out;
  for (int variant = 0; variant < 4; ++variant) {
    const bool inclusive = variant & 1, prefetch = variant & 2;
    Machine m = Make(2, 4,
                     {Level("L1", 64 * 4 * 2, 2, false, false, prefetch),
                      Level("L2", 64 * 6 * 4, 4, false),  // 6 sets: not a power of two
                      Level("L3", 64 * 16 * 4, 4, true, inclusive, prefetch)},
                     true);
    m.numa = variant == 3 ? Numa::kInterleave : Numa::kFirstTouch;
    out.push_back(m);
  }
  Machine off = out[1];
  off.coherence = false;
  out.push_back(off);
  return out;
}

// Random streams of p threads on m through Access and through Consume, both against Naive;
// returns the threads' counts summed. far: every 4 KiB page of the stream 2^34 bytes from the
// next, so the line records live in the simulator's hash table (beyond its dense range) and it
// grows while accesses straddle and prefetch.
ThreadStats CheckRandomStream(const Machine& m, Placement pl, int p, bool far, int accesses,
                              std::mt19937_64& rng) {
  MulticoreSimulation sim(m, pl), batched(m, pl);
  sim.Resize(p);
  batched.Resize(p);
  Naive ref(m, p, pl);
  std::vector<uint64_t> at(p, 0);
  std::vector<Access> all;
  for (int i = 0; i < accesses; ++i) {
    const int t = static_cast<int>(rng() % p);
    // Each thread walks its own region with jumps, and sometimes the shared one.
    at[t] = rng() % 5 == 0 ? (rng() % 8192) * 8 : at[t] + 8 * (rng() % 9);
    uint64_t a = rng() % 3 == 0 ? (rng() % 512) * 8 : at[t] + (uint64_t(t) << 16);
    if (far) a = (a & 4095) | ((a >> 12) << 34);
    const uint32_t size = std::array<uint32_t, 4>{8, 8, 16, 4}[rng() % 4];
    const bool write = rng() % 4 == 0;
    sim.Access(t, a, size, write);
    ref.Access(t, a, size, write);
    Access x{};
    x.thread = static_cast<uint8_t>(t), x.address = a, x.size = size, x.write = write;
    // Runs of one thread (as a traced run delivers them), so the batched first-level hit runs
    // take several accesses at once.
    all.push_back(x);
    if (rng() % 3) {
      x.address = a + 8 * (rng() % 4);
      x.write = rng() % 6 == 0;
      sim.Access(t, x.address, size, x.write);
      ref.Access(t, x.address, size, x.write);
      all.push_back(x);
    }
  }
  // The same accesses through Consume, in batches of varied length (its first-level hit runs and
  // HitFirst, the path a traced run takes).
  for (size_t i = 0; i < all.size();) {
    const size_t n = std::min(all.size() - i, size_t{1} + rng() % 700);
    batched.Consume(all.data() + i, n);
    i += n;
  }
  ThreadStats total;
  for (int t = 0; t < p; ++t) {
    const std::string what = std::string(PlacementName(pl)) + " p " + std::to_string(p) +
                             " thread " + std::to_string(t) + (far ? " far" : "");
    ExpectSame(sim.Stats(t), ref.stats[t], what);
    ExpectSame(batched.Stats(t), ref.stats[t], what + ", batched");
    total += sim.Stats(t);
  }
  return total;
}

TEST(Multicore, MatchesANaiveReferenceOnRandomStreams) {
  std::mt19937_64 rng(11);
  for (const bool far : {false, true})
    for (const Machine& m : SmallMachines())
      for (Placement pl : {Placement::kCompact, Placement::kScatter}) {
        const int p = 1 + static_cast<int>(rng() % 4);
        const ThreadStats total = CheckRandomStream(m, pl, p, far, 30000, rng);
        // The rules under test did act: coherence with several threads, inclusion, the prefetcher.
        uint64_t coherence = 0, victims = 0, hidden = 0;
        for (const CoreLevelStats& l : total.levels)
          coherence += l.coherence, victims += l.inclusion_victims, hidden += l.prefetch_hits;
        if (p > 1 && m.coherence) {
          EXPECT_GT(coherence, 0u);
        }
        if (m.levels[2].inclusive) {
          EXPECT_GT(victims, 0u);
        }
        if (m.levels[0].prefetch) {
          EXPECT_GT(hidden, 0u);
        }
      }
}

// A line's record keeps a bit per core in as few bits as the highest core with a thread needs
// (8, 32 or 64; the small machines above have 8 cores): on 64 cores, threads on cores up to 19
// (32 bits), 39 and 63 (64 bits), writing and reading each other's lines, follow the same rules.
TEST(Multicore, MatchesANaiveReferenceOnManyCores) {
  std::mt19937_64 rng(12);
  for (int variant = 0; variant < 4; ++variant) {
    Machine m = SmallMachines()[variant];
    m.sockets = 8, m.cores_per_socket = 8;  // 64 cores
    for (const bool far : {false, true})
      for (Placement pl : {Placement::kCompact, Placement::kScatter})
        for (int p : {20, 40, 64}) {
          const ThreadStats total = CheckRandomStream(m, pl, p, far, 12000, rng);
          uint64_t coherence = 0;
          for (const CoreLevelStats& l : total.levels) coherence += l.coherence;
          EXPECT_GT(coherence, 0u);
        }
  }
  // The cores beyond 31 took part: a thread there had lines taken away by another's write.
  const Machine m = [] {
    Machine x = SmallMachines()[1];
    x.sockets = 8, x.cores_per_socket = 8;
    return x;
  }();
  MulticoreSimulation sim(m, Placement::kCompact);
  sim.Resize(64);
  for (int round = 0; round < 2; ++round)
    for (int t = 0; t < 64; ++t) sim.Access(t, 4096, 8, true);  // one line, written by all
  // Each write takes the line from the core before (and, first on its socket, from the socket
  // before), in both rounds; each thread's second write misses on its copy so taken.
  for (int t = 32; t < 64; ++t) {
    EXPECT_EQ(sim.Stats(t).levels[0].coherence, 1u) << t;
    EXPECT_EQ(sim.Stats(t).invalidations_sent, t % 8 == 0 ? 4u : 2u) << t;
  }
}

// The mesh's streams, recorded once per (p, interleaving), through both.
struct Recorder : AccessConsumer {
  std::vector<Access> all;
  int threads = 1;
  void Begin(const StreamInfo& info) override { threads = info.threads; }
  void Consume(const Access* a, size_t n) override { all.insert(all.end(), a, a + n); }
};

TEST(Multicore, MatchesANaiveReferenceOnMeshes) {
  for (int p : {1, 2, 3, 5, 8})
    for (int il : {kSerialShares, 1, 64, kAccessGrain}) {
      Mesh mesh = SmallMesh(14, 12);
      SmoothOptions o;
      o.max_iters = 2, o.tol = -1, o.threads = p, o.interleave = il;
      Recorder rec;
      StreamMesh(mesh, o, "mesh", "ori", rec);
      for (const Machine& m : SmallMachines())
        for (Placement pl : {Placement::kCompact, Placement::kScatter}) {
          MulticoreSimulation sim(m, pl), batched(m, pl);
          sim.Resize(p);
          batched.Resize(p);
          Naive ref(m, p, pl);
          for (const Access& a : rec.all) {
            sim.Access(a.thread, a.address, a.size, a.write);
            ref.Access(a.thread, a.address, a.size, a.write);
          }
          for (size_t i = 0; i < rec.all.size(); i += 4096)
            batched.Consume(rec.all.data() + i, std::min<size_t>(4096, rec.all.size() - i));
          for (int t = 0; t < p; ++t) {
            const std::string what = "p " + std::to_string(p) + " interleave " +
                                     std::to_string(il) + " " + PlacementName(pl) + " thread " +
                                     std::to_string(t);
            ExpectSame(sim.Stats(t), ref.stats[t], what);
            ExpectSame(batched.Stats(t), ref.stats[t], what + ", batched");
          }
        }
    }
}

}  // namespace
}  // namespace meshreuse
