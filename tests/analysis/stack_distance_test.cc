// The analyzer against a naive O(N*M) reference on many random traces, the edge cases, compaction
// mid-trace, memory per distinct id, and the histogram's quantiles.
#include "analysis/stack_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "analysis/reference.h"
#include "analysis/reuse_histogram.h"
#include "analysis/synthetic_trace.h"
#include "core/synthetic.h"

namespace meshreuse {
namespace {

constexpr uint64_t kCold = StackDistance::kCold;

// For each access, walk back to the previous access of the same id, counting distinct ids (ids
// renumbered 0..M-1 first, so a stamp array marks the ones seen).
std::vector<uint64_t> Naive(const std::vector<uint64_t>& trace) {
  std::vector<uint64_t> sorted = trace;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  std::vector<size_t> id(trace.size());
  for (size_t i = 0; i < trace.size(); ++i)
    id[i] = std::lower_bound(sorted.begin(), sorted.end(), trace[i]) - sorted.begin();
  std::vector<size_t> stamp(sorted.size(), SIZE_MAX);
  std::vector<uint64_t> out;
  for (size_t i = 0; i < trace.size(); ++i) {
    uint64_t d = kCold, seen = 0;
    for (size_t j = i; j-- > 0;) {
      if (id[j] == id[i]) {
        d = seen;
        break;
      }
      if (stamp[id[j]] != i) stamp[id[j]] = i, ++seen;
    }
    out.push_back(d);
  }
  return out;
}

std::vector<uint64_t> Distances(const std::vector<uint64_t>& trace, uint64_t dense,
                                uint32_t min_cap, uint64_t* compactions = nullptr) {
  StackDistance sd(dense, min_cap);
  std::vector<uint64_t> out;
  for (uint64_t id : trace) out.push_back(sd.Access(id));
  if (compactions) *compactions = sd.compactions();
  return out;
}

std::vector<uint64_t> RandomTrace(SplitMix64& rng, size_t n, uint64_t alphabet, int kind) {
  std::vector<uint64_t> t(n);
  uint64_t window = 0;
  for (size_t i = 0; i < n; ++i) {
    switch (kind) {
      case 0:
        t[i] = rng.Below(alphabet);
        break;   // uniform
      case 1: {  // skewed (Zipf-like)
        const double u = rng.Uniform();
        t[i] = static_cast<uint64_t>(std::pow(u, 3.0) * alphabet);
        break;
      }
      case 2:
        t[i] = i % alphabet;
        break;  // cyclic scan
      default:  // sliding window
        if (rng.Below(8) == 0) ++window;
        t[i] = (window + rng.Below(16)) % alphabet;
    }
  }
  return t;
}

TEST(StackDistance, MatchesNaiveOnManyRandomTraces) {
  SplitMix64 rng(2024);
  int compacted = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const size_t n = static_cast<size_t>(rng.Below(3000));
    const uint64_t alphabet = 1 + rng.Below(trial % 3 == 0 ? 8 : 600);
    const int kind = trial % 4;
    std::vector<uint64_t> trace = RandomTrace(rng, n, alphabet, kind);
    const std::vector<uint64_t> expect = Naive(trace);
    uint64_t compactions = 0;
    SCOPED_TRACE("trial " + std::to_string(trial) + " n " + std::to_string(n) + " alphabet " +
                 std::to_string(alphabet) + " kind " + std::to_string(kind));
    ASSERT_EQ(Distances(trace, 1u << 20, 128, &compactions), expect) << "dense ids";
    compacted += compactions > 0;
    // The same trace with ids far above the dense range: the hashed path.
    for (uint64_t& id : trace) id += uint64_t{1} << 40;
    ASSERT_EQ(Distances(trace, 1u << 20, 128), expect) << "hashed ids";
    // A mix: half the ids dense, half hashed.
    for (size_t i = 0; i < trace.size(); ++i)
      if (trace[i] % 2) trace[i] -= uint64_t{1} << 40;
    ASSERT_EQ(Distances(trace, 1u << 20, 256), expect) << "mixed ids";
  }
  EXPECT_GT(compacted, 50) << "compaction should happen in many trials";
}

TEST(StackDistance, LongReusesGoThroughTheTree) {
  // Reuse gaps of thousands of positions (beyond the popcount shortcut), with compaction.
  SplitMix64 rng(7);
  std::vector<uint64_t> t = RandomTrace(rng, 12000, 2500, 0);  // gaps of ~2500, many > 3072
  uint64_t compactions = 0;
  EXPECT_EQ(Distances(t, 1u << 20, 4096, &compactions), Naive(t));
  EXPECT_GT(compactions, 0u);
}

TEST(StackDistance, VeryLongReusesUseTheFenwickTree) {
  // Reuse gaps of up to ~10^6 positions: thousands of Fenwick groups (512 positions each).
  SplitMix64 rng(11);
  for (uint64_t alphabet : {20000, 150000, 400000}) {
    std::vector<uint64_t> t = RandomTrace(rng, 1200000, alphabet, alphabet == 150000 ? 1 : 0);
    uint64_t compactions = 0;
    ASSERT_EQ(Distances(t, 1u << 20, 1u << 16, &compactions), TextbookStackDistances(t))
        << "alphabet " << alphabet;
    EXPECT_GT(compactions, 0u);
  }
  // A cyclic scan of 300,000 ids: every warm distance is 299,999, the gap 300,000 positions.
  StackDistance sd(300000);
  for (int lap = 0; lap < 3; ++lap)
    for (uint64_t id = 0; id < 300000; ++id) ASSERT_EQ(sd.Access(id), lap == 0 ? kCold : 299999u);
}

// The traces where long distances live (the benchmark shapes, smaller): a cyclic scan
// (every warm distance exact by construction), uniform random ids, and a mesh-like walk with 10%
// far reuses, each against the textbook analyzer, with dense and with hashed ids.
TEST(StackDistance, ScanUniformAndMixedTracesMatchTheTextbook) {
  const std::vector<uint64_t> scan = CyclicScanTrace(70000, 4);
  const std::vector<std::vector<uint64_t>> traces = {scan, UniformTrace(50000, 600000, 5),
                                                     MeshLikeTrace(40000, 900000, 0.1, 6),
                                                     MeshLikeTrace(3000, 200000, 0.02, 7)};
  for (size_t k = 0; k < traces.size(); ++k) {
    SCOPED_TRACE("trace " + std::to_string(k));
    const std::vector<uint64_t> expect = TextbookStackDistances(traces[k]);
    ASSERT_EQ(Distances(traces[k], 1u << 20, 1u << 16), expect) << "dense";
    std::vector<uint64_t> hashed = traces[k];
    for (uint64_t& id : hashed) id = id * 0x9E3779B97F4A7C15ull + (uint64_t{1} << 40);
    ASSERT_EQ(Distances(hashed, 1u << 20, 512), expect) << "hashed";
  }
  const std::vector<uint64_t> d = Distances(scan, 70000, 1u << 16);
  for (size_t i = 0; i < d.size(); ++i) ASSERT_EQ(d[i], i < 70000 ? kCold : 69999u);
}

// Ids of unknown range (dense_ids = 0): large ids first go to the hash table, then move into
// the direct array as it grows over them (owners renumbered); distances stay exact throughout.
TEST(StackDistance, HashedIdsMoveIntoTheArrayAsItGrows) {
  std::vector<uint64_t> t;
  for (uint64_t id = 399999; id > 300000; id -= 997) t.push_back(id);  // large ids first
  const std::vector<uint64_t> u = UniformTrace(400000, 500000, 8);
  t.insert(t.end(), u.begin(), u.end());
  t.insert(t.end(), u.begin(), u.begin() + 1000);
  t.push_back(uint64_t{1} << 40);  // stays hashed
  t.push_back(uint64_t{1} << 40);
  EXPECT_EQ(Distances(t, 0, 512), TextbookStackDistances(t));
  // One huge id among few does not buy a huge array.
  StackDistance sd(0);
  sd.Access(2000000000);
  sd.Access(1);
  EXPECT_LT(sd.MemoryBytes(), size_t{1} << 20);
}

// An LRU stack as a plain list (bottom first), with removal: the reference for Remove and
// StackBottomUp.
struct ListStack {
  std::vector<uint64_t> s;
  uint64_t Access(uint64_t id) {
    auto it = std::find(s.begin(), s.end(), id);
    uint64_t d = kCold;
    if (it != s.end()) {
      d = static_cast<uint64_t>(s.end() - it - 1);
      s.erase(it);
    }
    s.push_back(id);
    return d;
  }
  bool Remove(uint64_t id) {
    auto it = std::find(s.begin(), s.end(), id);
    if (it == s.end()) return false;
    s.erase(it);
    return true;
  }
};

TEST(StackDistance, RemoveAndStackMatchAListReference) {
  SplitMix64 rng(99);
  for (int trial = 0; trial < 40; ++trial) {
    const uint64_t alphabet = 1 + rng.Below(trial % 2 ? 40 : 900);
    const uint64_t offset = trial % 3 == 0 ? 0 : uint64_t{1} << 40;  // dense or hashed
    StackDistance sd(1000, 512);
    ListStack ref;
    for (int i = 0; i < 6000; ++i) {
      const uint64_t id = rng.Below(alphabet) + offset;
      if (rng.Below(10) == 0)
        ASSERT_EQ(sd.Remove(id), ref.Remove(id)) << "trial " << trial << " step " << i;
      else
        ASSERT_EQ(sd.Access(id), ref.Access(id)) << "trial " << trial << " step " << i;
    }
    EXPECT_EQ(sd.StackBottomUp(), ref.s) << "trial " << trial;
    EXPECT_EQ(sd.live(), ref.s.size());
  }
  // Without a known-dense range the window is chosen from the ids held: removals before it
  // (a sampler's) leave it unchosen until 64 are held again, then every distance still exact.
  for (int trial = 0; trial < 10; ++trial) {
    StackDistance sd(0, 512);
    ListStack ref;
    const uint64_t stride = uint64_t{8} << (trial % 4), base = trial % 2 ? 0x7f0000001000 : 64;
    for (uint64_t i = 0; i < 64; ++i)
      ASSERT_EQ(sd.Access(base + i * stride), ref.Access(base + i * stride));
    for (uint64_t i = 0; i < 64; ++i)
      ASSERT_EQ(sd.Remove(base + i * stride), ref.Remove(base + i * stride));
    for (int i = 0; i < 20000; ++i) {
      const uint64_t id = base + rng.Below(3000) * stride + (rng.Below(50) == 0 ? 1 : 0);
      if (rng.Below(10) == 0)
        ASSERT_EQ(sd.Remove(id), ref.Remove(id)) << "trial " << trial << " step " << i;
      else
        ASSERT_EQ(sd.Access(id), ref.Access(id)) << "trial " << trial << " step " << i;
    }
    EXPECT_EQ(sd.StackBottomUp(), ref.s) << "trial " << trial;
    uint64_t off_stride = 0;  // held ids off the stride: the only ones hashed
    for (uint64_t id : ref.s) off_stride += (id - base) % stride != 0;
    EXPECT_EQ(sd.hashed(), off_stride) << "trial " << trial;
  }
  StackDistance sd(0);
  EXPECT_FALSE(sd.Remove(5));
  EXPECT_EQ(sd.Access(5), kCold);
  EXPECT_TRUE(sd.Remove(5));
  EXPECT_EQ(sd.Access(5), kCold) << "a removed id is cold again";
}

// Addresses as ids (element granularity): a strided window makes them direct wherever they lie.
// Scans in shuffled laps over 3,000 addresses at base B and stride 2^s, with ids off the stride,
// below the window and far beyond it mixed in: every distance the textbook's; only those odd ids
// hashed; the stack bottom-up the ids themselves (checked by StackBottomUp against a list).
TEST(StackDistance, StridedAddressesAreDirectWhereverTheyLie) {
  SplitMix64 rng(17);
  for (uint64_t base : {uint64_t{0}, uint64_t{4096 * 7 + 64}, uint64_t{0x7f3a12345000}})
    for (int s : {0, 3, 6, 12}) {
      SCOPED_TRACE("base " + std::to_string(base) + " stride 2^" + std::to_string(s));
      std::vector<uint64_t> lap;
      for (uint64_t i = 0; i < 3000; ++i) lap.push_back(base + (i << s) + (uint64_t{1} << 20 << s));
      std::vector<uint64_t> t, odd;
      if (s > 0) odd.push_back(lap[5] + 1);  // off the stride
      odd.push_back(lap[0] - (uint64_t{1} << 19 << s) - (uint64_t{1} << 16 << s));  // below
      odd.push_back(lap[0] + (uint64_t{1} << 40));                                  // far beyond
      for (int k = 0; k < 3; ++k) {
        for (size_t i = lap.size(); i > 1; --i) std::swap(lap[i - 1], lap[rng.Below(i)]);
        for (size_t i = 0; i < lap.size(); ++i) {
          t.push_back(lap[i]);
          if (i % 500 == 7) t.insert(t.end(), odd.begin(), odd.end());
        }
      }
      EXPECT_EQ(Distances(t, 0, 512), TextbookStackDistances(t));
      StackDistance sd(0, 512);
      ListStack ref;
      for (uint64_t id : t) ASSERT_EQ(sd.Access(id), ref.Access(id));
      EXPECT_EQ(sd.hashed(), odd.size()) << "the strided ids went direct, the odd ones not";
      EXPECT_EQ(sd.StackBottomUp(), ref.s);
      for (uint64_t id : {lap[3], odd[0], lap[9]}) {
        ASSERT_EQ(sd.Remove(id), ref.Remove(id));
        ASSERT_EQ(sd.Access(lap[4]), ref.Access(lap[4]));
        ASSERT_EQ(sd.Access(id), ref.Access(id));
      }
      EXPECT_EQ(sd.StackBottomUp(), ref.s);
    }
}

// A window that must grow down: a scan from high addresses to low (the first 64 ids, which place
// the window, are its top), twice, on the stride of 8 far from 0; then ids below 0's reach.
TEST(StackDistance, TheWindowGrowsDownToIdsBelowIt) {
  std::vector<uint64_t> t;
  const uint64_t top = 0x55d0c0000000;
  for (int lap = 0; lap < 2; ++lap)
    for (uint64_t i = 0; i < 200000; ++i) t.push_back(top - 8 * i);
  EXPECT_EQ(Distances(t, 0, 512), TextbookStackDistances(t));
  StackDistance sd(0, 512);
  for (uint64_t id : t) sd.Access(id);
  EXPECT_EQ(sd.hashed(), 0u) << "every id of the scan direct";
  EXPECT_LT(sd.MemoryBytes(), 25u * 200000) << "4 bytes an entry, not a table's 28 per id";
  // Then ids far below the window (hashed: growing down to them would break the bound), twice.
  std::vector<uint64_t> low;
  for (uint64_t i = 0; i < 5000; ++i) low.push_back(8 * (5000 - i) + 8);
  for (uint64_t id : low) t.push_back(id);
  t.insert(t.end(), low.begin(), low.end());
  EXPECT_EQ(Distances(t, 0, 512), TextbookStackDistances(t));
  ListStack ref;
  StackDistance sd2(0, 512);
  std::vector<uint64_t> head(t.begin(), t.begin() + 3000), tail(t.end() - 20000, t.end());
  for (uint64_t id : head) ASSERT_EQ(sd2.Access(id), ref.Access(id));
  for (uint64_t id : tail) ASSERT_EQ(sd2.Access(id), ref.Access(id));
  ASSERT_TRUE(sd2.Remove(head[10]));
  ASSERT_TRUE(ref.Remove(head[10]));
  EXPECT_EQ(sd2.StackBottomUp(), ref.s);
}

TEST(StackDistance, EdgeCases) {
  EXPECT_TRUE(Distances({}, 100, 128).empty());
  EXPECT_EQ(Distances({5}, 100, 128), (std::vector<uint64_t>{kCold}));
  EXPECT_EQ(Distances({3, 3, 3, 3}, 100, 128),
            (std::vector<uint64_t>{kCold, 0, 0, 0}));                               // all equal
  EXPECT_EQ(Distances({1, 2, 3, 4}, 100, 128), (std::vector<uint64_t>(4, kCold)));  // all distinct
  EXPECT_EQ(Distances({0, 7, 0, 7, 0}, 100, 128),
            (std::vector<uint64_t>{kCold, kCold, 1, 1, 1}));  // id 0
  EXPECT_EQ(Distances({0, 0}, 0, 128),
            (std::vector<uint64_t>{kCold, 0}));  // id 0 hashed (address 0)
  EXPECT_EQ(Distances({1, 2, 3, 1, 2, 3}, 100, 128),
            (std::vector<uint64_t>{kCold, kCold, kCold, 2, 2, 2}));
}

TEST(StackDistance, CompactionMidTraceKeepsDistancesExact) {
  // A cyclic scan over 300 ids starting from a 512-position window: compactions every few laps
  // (the window then holds 4x the live ids), and every warm distance is exactly 299.
  StackDistance sd(1000, 128);
  for (int lap = 0; lap < 40; ++lap)
    for (uint64_t id = 0; id < 300; ++id) ASSERT_EQ(sd.Access(id), lap == 0 ? kCold : 299u);
  EXPECT_GE(sd.compactions(), 5u);
  EXPECT_EQ(sd.distinct(), 300u);
  EXPECT_EQ(sd.accesses(), 12000u);
}

TEST(StackDistance, MemoryFollowsDistinctIdsNotTraceLength) {
  SplitMix64 rng(3);
  const uint64_t distinct = 100000;
  StackDistance sd(distinct);
  for (uint64_t id = 0; id < distinct; ++id) sd.Access(id);
  for (int i = 0; i < 1000000; ++i) sd.Access(rng.Below(distinct));
  const size_t after_1m = sd.MemoryBytes();
  for (int i = 0; i < 9000000; ++i) sd.Access(rng.Below(distinct));
  EXPECT_EQ(sd.MemoryBytes(), after_1m) << "memory grew with the trace";
  EXPECT_LE(static_cast<double>(after_1m) / distinct, 32.0);
}

TEST(ReuseHistogram, QuantilesMeanAndTails) {
  ReuseHistogram h;
  for (uint64_t d : {0, 0, 1, 5, 9}) h.Add(d);
  h.Add(kCold);
  EXPECT_EQ(h.accesses(), 6u);
  EXPECT_EQ(h.cold(), 1u);
  EXPECT_EQ(h.finite(), 5u);
  EXPECT_DOUBLE_EQ(h.mean(), 3.0);
  EXPECT_EQ(h.Quantile(0.0), 0u);  // the smallest
  EXPECT_EQ(h.Quantile(0.4), 0u);  // 2 of 5 <= 0
  EXPECT_EQ(h.Quantile(0.41), 1u);
  EXPECT_EQ(h.Quantile(0.5), 1u);
  EXPECT_EQ(h.Quantile(0.8), 5u);
  EXPECT_EQ(h.Quantile(0.81), 9u);
  EXPECT_EQ(h.Quantile(1.0), 9u);  // the largest
  EXPECT_EQ(h.max(), 9u);
  EXPECT_EQ(h.CountAtLeast(1), 3u);
  EXPECT_EQ(h.CountAtLeast(10), 0u);
  EXPECT_THROW(h.Quantile(1.5), std::invalid_argument);
  EXPECT_THROW(ReuseHistogram().Quantile(0.5), std::domain_error);
  ReuseHistogram only_small;
  only_small.Add(4);
  EXPECT_EQ(only_small.Quantile(0.0), 4u);  // X = 0 is the smallest observed, not 0
}

TEST(ReuseHistogram, BinsAreExactThenLog2) {
  ReuseHistogram h;
  for (uint64_t d : {0, 1, 1, 3, 4, 7, 8, 100}) h.Add(d);
  const auto bins = h.Binned(4);
  ASSERT_EQ(bins.size(), 9u);  // 0 1 2 3 | 4-7 8-15 16-31 32-63 64-127
  EXPECT_EQ(bins[1].count, 2u);
  EXPECT_EQ(bins[4].lo, 4u);
  EXPECT_EQ(bins[4].hi, 7u);
  EXPECT_EQ(bins[4].count, 2u);
  EXPECT_EQ(bins[5].count, 1u);
  EXPECT_EQ(bins[8].count, 1u);
  uint64_t total = 0;
  for (const auto& b : bins) total += b.count;
  EXPECT_EQ(total, h.finite());
}

TEST(ReuseProfile, MeanPerStep) {
  ReuseProfile p({10, 4}, 2);  // two iterations, two steps each
  for (uint64_t d : {1, 1, 1, 1, 1, 3, 3, 3, 3, 3}) p.Add(d);
  p.Add(kCold);
  p.Add(2);
  p.Add(4);
  p.Add(4);
  p.Add(9);  // beyond the announced length: ignored
  const auto& s = p.steps();
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(s[0].mean(), 1.0);
  EXPECT_DOUBLE_EQ(s[1].mean(), 3.0);
  EXPECT_EQ(s[2].cold, 1u);
  EXPECT_DOUBLE_EQ(s[2].mean(), 2.0);
  EXPECT_DOUBLE_EQ(s[3].mean(), 4.0);
  EXPECT_EQ(s[3].iteration, 2);
}

}  // namespace
}  // namespace meshreuse
