// ReuseHistogram's two layouts give one set of answers: the paged one (UsePages) against the
// dense one, and both against a naive std::map of counts, on random histograms of several shapes,
// for every query the outputs use (quantiles, tails, bins, rows, curve, capacities, merges); and
// the paged layout's memory follows the distances it holds, not the largest one; the dense
// layout's 32-bit counters carry exactly past 2^32 in every query and merge.
#include "analysis/reuse_histogram.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <stdexcept>

#include "analysis/cache_model.h"
#include "analysis/stack_distance.h"

namespace meshreuse {
namespace {

// (distance, count) draws of one shape; kCold among them for cold accesses.
std::vector<std::pair<uint64_t, uint64_t>> Draws(int shape, uint32_t seed) {
  std::mt19937_64 g(seed);
  std::vector<std::pair<uint64_t, uint64_t>> out;
  const int n = 1 + static_cast<int>(g() % 400);
  for (int i = 0; i < n; ++i) {
    uint64_t d = 0;
    switch (shape) {
      case 0:  // small distances
        d = g() % 100;
        break;
      case 1:  // spikes far apart (a scan, a mesh's sweep-long reuses)
        d = (g() % 5) * 100'003 + g() % 3;
        break;
      default:  // anything, page edges included
        d = g() % 3 == 0 ? (g() % 8) * 4096 + (g() % 2 ? 4095 : 0) : g() % 50'000;
    }
    if (g() % 17 == 0) d = StackDistance::kCold;
    out.emplace_back(d, 1 + g() % 5);
  }
  return out;
}

void Fill(ReuseHistogram* h, const std::vector<std::pair<uint64_t, uint64_t>>& draws, bool add1) {
  for (const auto& [d, n] : draws) {
    if (add1)
      for (uint64_t k = 0; k < n; ++k) h->Add(d);
    else
      h->AddCount(d, n);
  }
}

void ExpectSame(const ReuseHistogram& a, const ReuseHistogram& b,
                const std::map<uint64_t, uint64_t>& naive, uint64_t cold) {
  std::vector<std::pair<uint64_t, uint64_t>> want(naive.begin(), naive.end());
  ASSERT_EQ(a.Pairs(), want);
  ASSERT_EQ(b.Pairs(), want);
  EXPECT_EQ(a.cold(), cold);
  EXPECT_EQ(b.cold(), cold);
  EXPECT_EQ(a.finite(), b.finite());
  EXPECT_TRUE(a.sum() == b.sum());
  EXPECT_EQ(a.max(), naive.empty() ? 0 : naive.rbegin()->first);
  EXPECT_EQ(b.max(), a.max());
  if (a.finite()) {
    EXPECT_EQ(a.mean(), b.mean());
    for (double x : {0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 1.0}) {
      // naive: the smallest d with cum(d) >= x * finite
      uint64_t cum = 0, q = 0;
      for (const auto& [d, n] : naive) {
        cum += n;
        if (static_cast<long double>(cum) >=
            static_cast<long double>(x) * a.finite() - 1e-12L * a.finite()) {
          q = d;
          break;
        }
      }
      EXPECT_EQ(a.Quantile(x), q) << x;
      EXPECT_EQ(b.Quantile(x), q) << x;
    }
  }
  size_t i = 0;
  for (const auto& [d, n] : naive) {
    if (i++ % 8) continue;  // a sample of the edges: each query walks the counters
    for (uint64_t e : {d, d + 1, d > 0 ? d - 1 : 0}) {
      uint64_t at_least = 0;
      for (auto it = naive.lower_bound(e); it != naive.end(); ++it) at_least += it->second;
      ASSERT_EQ(a.CountAtLeast(e), at_least);
      ASSERT_EQ(b.CountAtLeast(e), at_least);
    }
  }
  for (uint64_t exact_below : {0, 7, 64}) {
    const auto x = a.Binned(exact_below), y = b.Binned(exact_below);
    ASSERT_EQ(x.size(), y.size());
    uint64_t total = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(x[i].lo, y[i].lo);
      EXPECT_EQ(x[i].hi, y[i].hi);
      EXPECT_EQ(x[i].count, y[i].count);
      uint64_t c = 0;  // naive: the draws inside the bin
      for (const auto& [d, n] : naive)
        if (d >= x[i].lo && d <= x[i].hi) c += n;
      EXPECT_EQ(x[i].count, c) << "bin " << x[i].lo << ".." << x[i].hi;
      total += x[i].count;
    }
    EXPECT_EQ(total, a.finite());
    Table ta({"k", "lo", "hi", "count"}), tb({"k", "lo", "hi", "count"});
    a.AppendRows(&ta, {"k"}, exact_below);
    b.AppendRows(&tb, {"k"}, exact_below);
    EXPECT_EQ(ta.Csv(), tb.Csv());
  }
  const auto ca = MissRatioCurve(a), cb = MissRatioCurve(b);
  ASSERT_EQ(ca.size(), cb.size());
  for (size_t i = 0; i < ca.size(); ++i) {
    EXPECT_EQ(ca[i].capacity, cb[i].capacity);
    EXPECT_EQ(ca[i].misses, cb[i].misses);
  }
  for (uint64_t n = 0; n <= a.accesses() + 1; n += 1 + a.accesses() / 50)
    for (bool exclude : {false, true})
      EXPECT_EQ(CapacityForMisses(a, n, exclude), CapacityForMisses(b, n, exclude)) << n;
}

TEST(ReuseHistogram, PagedAnswersAsDense) {
  for (int shape = 0; shape < 3; ++shape)
    for (uint32_t seed = 1; seed <= 20; ++seed) {
      SCOPED_TRACE("shape " + std::to_string(shape) + " seed " + std::to_string(seed));
      const auto draws = Draws(shape, seed);
      std::map<uint64_t, uint64_t> naive;
      uint64_t cold = 0;
      for (const auto& [d, n] : draws) (d == StackDistance::kCold ? cold : naive[d]) += n;
      ReuseHistogram dense, paged;
      paged.UsePages();
      const bool add1 = seed % 2;
      Fill(&dense, draws, add1);
      Fill(&paged, draws, !add1);
      EXPECT_TRUE(paged.paged());
      EXPECT_FALSE(dense.paged());
      ExpectSame(dense, paged, naive, cold);
      // Merges across layouts add the same counts.
      const auto more = Draws((shape + 1) % 3, seed + 100);
      for (const auto& [d, n] : more) (d == StackDistance::kCold ? cold : naive[d]) += n;
      ReuseHistogram other_dense, other_paged;
      other_paged.UsePages();
      Fill(&other_dense, more, true);
      Fill(&other_paged, more, false);
      ReuseHistogram d2 = std::move(dense), p2 = std::move(paged);
      d2.Merge(other_paged);
      p2.Merge(other_dense);
      ExpectSame(d2, p2, naive, cold);
    }
}

TEST(ReuseHistogram, EmptyAndColdOnlyAnswerAlike) {
  ReuseHistogram dense, paged;
  paged.UsePages();
  ExpectSame(dense, paged, {}, 0);
  dense.Add(StackDistance::kCold);
  paged.AddCount(StackDistance::kCold, 1);
  ExpectSame(dense, paged, {}, 1);
  EXPECT_THROW(paged.Quantile(0.5), std::domain_error);
}

TEST(ReuseHistogram, PagesFollowTheDistancesHeld) {
  // A scan's reuses all at one large distance: one page and an index, not an array of 10^8.
  ReuseHistogram h;
  h.UsePages();
  h.AddCount(100'000'000 - 1, 5);
  h.Add(3);
  EXPECT_LT(h.counter_bytes(), uint64_t{1} << 20);
  EXPECT_EQ(h.max(), 100'000'000u - 1);
  EXPECT_EQ(h.Quantile(0.5), 100'000'000u - 1);
  EXPECT_EQ(h.Quantile(0.1), 3u);
  ReuseHistogram dense;
  dense.AddCount(100'000'000 - 1, 5);
  EXPECT_GE(dense.counter_bytes(), uint64_t{400'000'000});  // 32-bit counters
}

TEST(ReuseHistogram, DenseCountersCarryPast32Bits) {
  // Counts at and beyond 2^32 at the first, a middle and the last distance, reached by Add one
  // at a time across the wrap, by AddCount with and without a carry out of the low word, and by
  // merging two dense histograms whose counters wrap only added together: every answer as the
  // paged layout's (64-bit counters) and a naive map's.
  const uint64_t w = uint64_t{1} << 32;
  ReuseHistogram dense, paged;
  paged.UsePages();
  std::map<uint64_t, uint64_t> naive;
  auto add = [&](uint64_t d, uint64_t n, bool one_by_one) {
    if (one_by_one) {
      for (uint64_t k = 0; k < n; ++k) dense.Add(d);
    } else {
      dense.AddCount(d, n);
    }
    paged.AddCount(d, n);
    naive[d] += n;
  };
  add(0, w - 2, false);
  add(0, 5, true);  // wraps on the second
  add(7, 3, true);
  add(7, 3 * w + (w - 1), false);  // a carry from n's high word and one out of the low word
  add(9, 2 * w, false);            // a multiple of 2^32: the low counter stays 0
  add(12, 1, true);
  add(12, w - 1, false);  // exactly 2^32: low 0, one carry
  ExpectSame(dense, paged, naive, 0);
  EXPECT_EQ(dense.max(), 12u);
  EXPECT_EQ(dense.CountAtLeast(9), 2 * w + w);
  EXPECT_EQ(dense.Quantile(1.0), 12u);

  ReuseHistogram a, b, ap, bp;
  ap.UsePages();
  bp.UsePages();
  std::map<uint64_t, uint64_t> sum;
  for (uint64_t d : {uint64_t{1}, uint64_t{4}, uint64_t{6}}) {
    const uint64_t x = w - d, y = d + 1 + (d == 6 ? w : 0);  // x + y wraps; d = 6 also carries
    a.AddCount(d, x), ap.AddCount(d, x);
    b.AddCount(d, y), bp.AddCount(d, y);
    sum[d] = x + y;
  }
  b.AddCount(5, 2), bp.AddCount(5, 2), sum[5] = 2;
  a.Merge(b);
  ap.Merge(bp);
  ExpectSame(a, ap, sum, 0);
}

TEST(ReuseHistogram, PagesOnlyBeforeAnyAdd) {
  ReuseHistogram h;
  h.Add(1);
  EXPECT_THROW(h.UsePages(), std::logic_error);
  ReuseHistogram c;
  c.Add(StackDistance::kCold);
  EXPECT_THROW(c.UsePages(), std::logic_error);
}

}  // namespace
}  // namespace meshreuse
