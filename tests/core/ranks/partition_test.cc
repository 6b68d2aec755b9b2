// Partitions (core/ranks/partition.h) and their inheritance through refinement (core/refine.h):
// Hilbert ranges balanced to one vertex and contiguous along the curve; METIS parts in range;
// Scotch valid, balanced, deterministic across threads and better cut than the curve;
// MeasurePartition against a naive count with std::set (cut edges, cut and ghost vertices) and a
// valid colouring (adjacent parts differ); inherited parts by their rules, by hand on the unit
// square; refusals naming the place.
#include "core/ranks/partition.h"

#include <gtest/gtest.h>

#include <set>
#include <thread>

#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/refine.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

Mesh Medium() { return testing::Synthetic(40, 30, 2, 6); }

TEST(Partition, HilbertRangesAreBalancedAndFollowTheCurve) {
  const Mesh m = Medium();
  const Permutation h = ComputeOrdering("hilbert", m);
  for (int32_t parts : {1, 2, 3, 7, 64}) {
    const std::vector<int32_t> p = HilbertRangeParts(m, parts);
    const PartitionStats s = MeasurePartition(m, p, parts);
    int64_t lo = m.NumVertices(), hi = 0;
    for (int64_t o : s.owned) lo = std::min(lo, o), hi = std::max(hi, o);
    EXPECT_LE(hi - lo, 1) << parts;
    for (int32_t i = 1; i < m.NumVertices(); ++i)  // non-decreasing along the curve
      EXPECT_LE(p[h.OldOf(i - 1)], p[h.OldOf(i)]);
  }
}

// Scotch: every vertex in a part, no part empty, balanced to its 3% (plus one vertex), the same
// parts twice and from concurrent threads (every rank computes them independently), another seed
// other parts (at some part count), and fewer cut edges than the Hilbert ranges (a graph
// partitioner that saw the wrong graph would not beat the curve).
TEST(Partition, ScotchIsValidBalancedDeterministicAndCutsLessThanTheCurve) {
  const Mesh m = Medium();
  int seed_matters = 0;  // the seed reaches Scotch (at some part counts it changes nothing)
  for (int32_t parts : {1, 2, 3, 7, 16}) {
    const std::vector<int32_t> a = ScotchParts(m, parts, 1);
    ASSERT_EQ(a.size(), static_cast<size_t>(m.NumVertices()));
    std::vector<int64_t> owned(parts, 0);
    for (int32_t p : a) {
      ASSERT_GE(p, 0);
      ASSERT_LT(p, parts);
      ++owned[p];
    }
    for (int64_t o : owned) {
      EXPECT_GT(o, 0) << parts;
      EXPECT_LE(o, 1.03 * m.NumVertices() / parts + 1) << parts;
    }
    EXPECT_EQ(ScotchParts(m, parts, 1), a);
    std::vector<std::vector<int32_t>> concurrent(4);
    std::vector<std::thread> threads;
    for (auto& c : concurrent) threads.emplace_back([&] { c = ScotchParts(m, parts, 1); });
    for (auto& t : threads) t.join();
    for (const auto& c : concurrent) EXPECT_EQ(c, a) << parts;
    if (parts > 1) {
      EXPECT_LT(MeasurePartition(m, a, parts).cut_edges,
                MeasurePartition(m, HilbertRangeParts(m, parts), parts).cut_edges)
          << parts;
      seed_matters += ScotchParts(m, parts, 2) != a;
    }
  }
  EXPECT_GT(seed_matters, 0);
  EXPECT_EQ(PartsByMethod(m, "scotch", 3, 4), ScotchParts(m, 3, 4));
}

TEST(Partition, StatsMatchANaiveCountAndTheColouringIsProper) {
  const Mesh m = Medium();
  for (int method = 0; method < 2; ++method)
    for (int32_t parts : {1, 2, 5, 16}) {
      const std::vector<int32_t> p = method ? MetisParts(m, parts, 3) : HilbertRangeParts(m, parts);
      const PartitionStats s = MeasurePartition(m, p, parts);
      std::set<std::pair<int32_t, int32_t>> cut;
      std::vector<std::set<int32_t>> ghosts(parts), cut_owned(parts);
      std::set<std::pair<int32_t, int32_t>> adjacent;
      for (int32_t v = 0; v < m.NumVertices(); ++v) {
        ASSERT_GE(p[v], 0);
        ASSERT_LT(p[v], parts);
        for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
          if (p[*q] != p[v]) {
            cut.insert({std::min(v, *q), std::max(v, *q)});
            ghosts[p[v]].insert(*q);
            cut_owned[p[v]].insert(v);
            adjacent.insert({p[v], p[*q]});
          }
      }
      EXPECT_EQ(s.cut_edges, static_cast<int64_t>(cut.size()));
      for (int32_t q = 0; q < parts; ++q) {
        EXPECT_EQ(s.ghosts[q], static_cast<int64_t>(ghosts[q].size()));
        EXPECT_EQ(s.cut_owned[q], static_cast<int64_t>(cut_owned[q].size()));
      }
      for (const auto& [a, b] : adjacent) EXPECT_NE(s.colour[a], s.colour[b]);
      EXPECT_EQ(s.colours,
                parts == 1 ? 1 : *std::max_element(s.colour.begin(), s.colour.end()) + 1);
      if (parts == 1) {
        EXPECT_EQ(s.cut_edges, 0);
      }
    }
}

TEST(Partition, InheritedByTheRulesAndByHand) {
  // Unit square, K = 1: edge midpoints 4 (0-1), 5 (0-2), 6 (0-3), 7 (1-3), 8 (2-3) take their
  // lower end's part.
  const Mesh sq = testing::UnitSquare();
  RefineOptions o;
  EXPECT_EQ(InheritParts(sq, o, {0, 1, 2, 3}), (std::vector<int32_t>{0, 1, 2, 3, 0, 0, 0, 1, 2}));
  // K = 2 on a larger mesh: interior points take their coarse triangle's smallest corner's part;
  // checked through RefinePiece (a piece's interior ids are its triangle's alone).
  const Mesh m = Medium();
  const std::vector<int32_t> coarse = HilbertRangeParts(m, 4);
  o.levels = 2;
  const std::vector<int32_t> fine = InheritParts(m, o, coarse);
  ASSERT_EQ(static_cast<int64_t>(fine.size()), RefinedSizeOf(m, o).vertices);
  for (int32_t v = 0; v < m.NumVertices(); ++v) EXPECT_EQ(fine[v], coarse[v]);
  const int64_t first_interior = RefinedSizeOf(m, o).vertices - 3 * int64_t{m.NumTriangles()};
  for (int32_t t = 0; t < m.NumTriangles(); t += 17) {
    const RefinedPiece p = RefinePiece(m, o, t, t + 1);
    const int32_t* c = &m.tri[3 * t];
    for (int32_t id : p.ids)
      if (id >= first_interior) {  // K = 2: 3 interior points a triangle
        EXPECT_EQ(fine[id], coarse[std::min({c[0], c[1], c[2]})]);
      }
  }
}

TEST(Partition, Refusals) {
  const Mesh m = testing::TwoInterior();
  EXPECT_THROW(HilbertRangeParts(m, 0), UsageError);
  EXPECT_THROW(HilbertRangeParts(m, 9), UsageError);
  try {
    MeasurePartition(m, {0, 0, 1, 0, 2, 0, 0, 0}, 2, "p.txt");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "p.txt");
    EXPECT_EQ(e.line(), 5);
  }
}

}  // namespace
}  // namespace meshreuse
