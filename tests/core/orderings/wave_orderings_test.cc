// wave-blocks, metis-wave and grid-wave (issue 24) against literal reference implementations of the
// definitions at the head of their files (explicit level lists, std::queue, std::stable_sort,
// linear scans) on the mesh corpus at many sizes and partitions; hand-worked orders on the
// two-interior mesh; the limits where they are plain BFS; and the references checked to be
// sensitive (a changed rule changes the order on most meshes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <set>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

std::vector<int32_t> Neighbours(const Mesh& m, int32_t v) {
  return std::vector<int32_t>(m.v2v.RowBegin(v), m.v2v.RowEnd(v));
}

// wave-blocks as written. `parent_arc` false: every vertex cut by its own index in its level
// instead of inheriting its parent's arc (a rule the test shows matters).
std::vector<int32_t> ReferenceWaveBlocks(const Mesh& m, int64_t block, int64_t band,
                                         bool parent_arc = true) {
  const int32_t n = m.NumVertices();
  // Levels as lists: per component, from its lowest unvisited id, a std::queue BFS.
  std::vector<std::vector<int32_t>> levels;
  std::vector<bool> starts_component;  // per level
  std::vector<int32_t> parent(n, -1);
  std::vector<bool> seen(n, false);
  for (int32_t s = 0; s < n; ++s) {
    if (seen[s]) continue;
    seen[s] = true;
    std::vector<int32_t> cur{s};
    bool first = true;
    while (!cur.empty()) {
      levels.push_back(cur);
      starts_component.push_back(first);
      first = false;
      std::vector<int32_t> next;
      for (int32_t v : cur)
        for (int32_t q : Neighbours(m, v))
          if (!seen[q]) seen[q] = true, parent[q] = v, next.push_back(q);
      cur = next;
    }
  }
  std::vector<int32_t> order;
  size_t l = 0;
  while (l < levels.size()) {
    std::vector<size_t> band_levels{l};
    int64_t count = static_cast<int64_t>(levels[l].size());
    size_t e = l + 1;
    while (e < levels.size() && !starts_component[e] &&
           count + static_cast<int64_t>(levels[e].size()) <= band) {
      count += static_cast<int64_t>(levels[e].size());
      band_levels.push_back(e++);
    }
    const int64_t h = static_cast<int64_t>(band_levels.size());
    int64_t w = 1;
    while (w * h < block) ++w;  // ceil(block / h), by counting
    std::vector<int64_t> arc(n, -1);
    std::vector<int32_t> members;
    for (size_t k = 0; k < band_levels.size(); ++k)
      for (size_t i = 0; i < levels[band_levels[k]].size(); ++i) {
        const int32_t v = levels[band_levels[k]][i];
        arc[v] = (k == 0 || !parent_arc) ? static_cast<int64_t>(i) / w : arc[parent[v]];
        members.push_back(v);
      }
    std::stable_sort(members.begin(), members.end(),
                     [&](int32_t a, int32_t b) { return arc[a] < arc[b]; });
    order.insert(order.end(), members.begin(), members.end());
    l = e;
  }
  return order;
}

// WaveThroughParts as written; `continue_wave` false: each part from its lowest id (metis's rule).
std::vector<int32_t> ReferenceWaveThroughParts(const Mesh& m, const std::vector<int32_t>& part,
                                               int32_t parts, bool continue_wave = true) {
  const int32_t n = m.NumVertices();
  std::vector<std::set<int32_t>> pnbr(parts);
  for (int32_t v = 0; v < n; ++v)
    for (int32_t q : Neighbours(m, v))
      if (part[q] != part[v]) pnbr[part[v]].insert(part[q]);
  std::vector<int32_t> porder;
  std::vector<bool> pseen(parts, false);
  for (int32_t s = -1; s < parts; ++s) {
    const int32_t start = s < 0 ? part[0] : s;
    if (pseen[start]) continue;
    std::queue<int32_t> qu;
    qu.push(start);
    pseen[start] = true;
    while (!qu.empty()) {
      const int32_t p = qu.front();
      qu.pop();
      porder.push_back(p);
      for (int32_t r : pnbr[p])
        if (!pseen[r]) pseen[r] = true, qu.push(r);
    }
  }
  std::vector<int32_t> order;
  auto position = [&](int32_t v) {  // a linear scan
    for (size_t i = 0; i < order.size(); ++i)
      if (order[i] == v) return static_cast<int64_t>(i);
    return int64_t{-1};
  };
  for (int32_t p : porder) {
    std::vector<std::pair<int64_t, int32_t>> seeds;
    if (continue_wave)
      for (int32_t v = 0; v < n; ++v) {
        if (part[v] != p) continue;
        int64_t earliest = -1;
        for (int32_t q : Neighbours(m, v)) {
          const int64_t at = position(q);
          if (at >= 0 && (earliest < 0 || at < earliest)) earliest = at;
        }
        if (earliest >= 0) seeds.emplace_back(earliest, v);
      }
    std::sort(seeds.begin(), seeds.end());
    std::queue<int32_t> qu;
    auto place = [&](int32_t v) {
      order.push_back(v);
      qu.push(v);
    };
    auto drain = [&] {
      while (!qu.empty()) {
        const int32_t v = qu.front();
        qu.pop();
        for (int32_t q : Neighbours(m, v))
          if (part[q] == p && position(q) < 0) place(q);
      }
    };
    for (const auto& s : seeds) place(s.second);
    drain();
    for (int32_t v = 0; v < n; ++v)
      if (part[v] == p && position(v) < 0) {
        place(v);
        drain();
      }
  }
  return order;
}

TEST(WaveBlocks, MatchesItsDefinitionAndTheParentRuleMatters) {
  int meshes = 0, differs = 0, not_bfs = 0;
  for (const Mesh& m : testing::MeshCorpus())
    for (int64_t block : {1, 2, 3, 5, 8, 13, 40}) {
      for (int64_t band : {block, 2 * block, 4 * block, 9 * block + 1}) {
        const std::vector<int32_t> got = orderings::WaveBlocksOrder(m, block, band);
        ASSERT_EQ(got, ReferenceWaveBlocks(m, block, band))
            << "mesh " << meshes << " block " << block << " band " << band;
        ++meshes;
        differs += got != ReferenceWaveBlocks(m, block, band, false);
        not_bfs += got != orderings::BfsVisitOrder(m);
      }
    }
  EXPECT_GT(differs, meshes / 4);
  EXPECT_GT(not_bfs, meshes / 3);  // small meshes: many sizes give one band or one arc
}

TEST(WaveBlocks, LimitsArePlainBfs) {
  for (const Mesh& m : testing::MeshCorpus()) {
    const int32_t n = m.NumVertices();
    // One band and one arc per component.
    EXPECT_EQ(orderings::WaveBlocksOrder(m, n, n), orderings::BfsVisitOrder(m));
    // Bands of one level: arcs follow the level's own order.
    EXPECT_EQ(orderings::WaveBlocksOrder(m, 1, 1), orderings::BfsVisitOrder(m));
  }
  // A mesh smaller than the default block (32 KiB): BFS through the registry.
  const Mesh m = testing::TwoInterior();
  EXPECT_EQ(ComputeOrdering("wave-blocks", m).new_to_old(), orderings::BfsVisitOrder(m));
}

TEST(WaveBlocks, HandWorked) {
  // two_interior: 0:{1,5,6} 1:{0,2,6,7} 2:{1,3,7} 3:{2,4,7} 4:{3,5,6,7} 5:{0,4,6}
  // 6:{0,1,4,5,7} 7:{1,2,3,4,6}. BFS 0 | 1 5 6 | 2 7 4 | 3 (parents: 1,5,6 <- 0; 2,7 <- 1;
  // 4 <- 5; 3 <- 2).
  const Mesh m = testing::TwoInterior();
  ASSERT_EQ(orderings::BfsVisitOrder(m), (std::vector<int32_t>{0, 1, 5, 6, 2, 7, 4, 3}));
  // Block 2, band 4: bands {0 | 1 5 6} (4 vertices) and {2 7 4 | 3}, two levels each, so w = 1:
  // every first-level vertex its own arc; 3 follows its parent 2.
  EXPECT_EQ(orderings::WaveBlocksOrder(m, 2, 4), (std::vector<int32_t>{0, 1, 5, 6, 2, 3, 7, 4}));
  // Block 4, band 4: w = 2 in the second band: arcs {2, 7} (with 3) and {4}.
  EXPECT_EQ(orderings::WaveBlocksOrder(m, 4, 4), (std::vector<int32_t>{0, 1, 5, 6, 2, 7, 3, 4}));
}

TEST(WaveBlocks, ArgumentIsBytes) {
  EXPECT_THROW(ParseOrderingSpec("wave-blocks:0"), UsageError);
  EXPECT_THROW(ParseOrderingSpec("wave-blocks:-4K"), UsageError);
  EXPECT_THROW(ParseOrderingSpec("wave-blocks:12Q"), UsageError);
  EXPECT_NO_THROW(ParseOrderingSpec("wave-blocks:48K"));
  EXPECT_THROW(ParseOrderingSpec("wave-blocks:32K/16K"), UsageError);  // a band below a block
  EXPECT_THROW(ParseOrderingSpec("wave-blocks:/64K"), UsageError);
  EXPECT_THROW(ParseOrderingSpec("wave-blocks:32K/"), UsageError);
  EXPECT_EQ(orderings::ParseWaveBlocks(""), std::make_pair(uint64_t{32768}, uint64_t{131072}));
  EXPECT_EQ(orderings::ParseWaveBlocks("8K"), std::make_pair(uint64_t{8192}, uint64_t{32768}));
  EXPECT_EQ(orderings::ParseWaveBlocks("8K/1M"), std::make_pair(uint64_t{8192}, uint64_t{1 << 20}));
  SyntheticOptions o;
  o.nx = 80, o.ny = 60, o.seed = 3;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  const double bpv = orderings::SweepBytesPerVertex(m);
  const int64_t block = std::llround(8192 / bpv);
  EXPECT_EQ(ComputeOrdering("wave-blocks:8K", m).new_to_old(),
            orderings::WaveBlocksOrder(m, block, 4 * block));
  EXPECT_NE(ComputeOrdering("wave-blocks:8K", m).new_to_old(), orderings::BfsVisitOrder(m));
  EXPECT_EQ(ComputeOrdering("wave-blocks:8K/64K", m).new_to_old(),
            orderings::WaveBlocksOrder(m, block, std::llround(65536 / bpv)));
}

TEST(MetisWave, MatchesItsDefinitionAndContinuingTheWaveMatters) {
  int cases = 0, differs = 0;
  for (const Mesh& m : testing::MeshCorpus()) {
    const int32_t n = m.NumVertices();
    for (int32_t stripes : {2, 3, 7}) {  // parts by x (stripes), and by id modulo (scattered)
      std::vector<int32_t> px(n), pm(n);
      double lo = 1e300, hi = -1e300;
      for (int32_t v = 0; v < n; ++v)
        lo = std::min(lo, m.xy[2 * v]), hi = std::max(hi, m.xy[2 * v]);
      for (int32_t v = 0; v < n; ++v) {
        px[v] = std::min(stripes - 1,
                         static_cast<int32_t>((m.xy[2 * v] - lo) / (hi - lo + 1e-300) * stripes));
        pm[v] = v % stripes;
      }
      for (const auto* part : {&px, &pm}) {
        const std::vector<int32_t> got = orderings::WaveThroughParts(m, *part, stripes);
        ASSERT_EQ(got, ReferenceWaveThroughParts(m, *part, stripes)) << "case " << cases;
        ++cases;
        differs += got != ReferenceWaveThroughParts(m, *part, stripes, false);
      }
    }
  }
  EXPECT_GT(differs, cases / 2);
}

TEST(MetisWave, HandWorkedAndMetisPartsReused) {
  const Mesh m = testing::TwoInterior();
  // Parts {0 1 5 6} and {2 3 4 7}. The first part from 0: 0 1 5 6 (positions 0-3). The second
  // part's seeds by their earliest placed neighbour: 2 (1 at 1), 7 (1 at 1), 4 (5 at 2); then 3.
  // (metis's rule, from the lowest id 2: 2 3 7 4.)
  const std::vector<int32_t> part = {0, 0, 1, 1, 1, 0, 0, 1};
  EXPECT_EQ(orderings::WaveThroughParts(m, part, 2),
            (std::vector<int32_t>{0, 1, 5, 6, 2, 7, 4, 3}));
  EXPECT_EQ(ReferenceWaveThroughParts(m, part, 2, false),
            (std::vector<int32_t>{0, 1, 5, 6, 2, 3, 7, 4}));
  // Through the registry: metis's own parts (same seed), laid out by the wave.
  SyntheticOptions o;
  o.nx = 60, o.ny = 50, o.holes = 2, o.seed = 9;
  const Mesh big = BuildMesh(MakeSyntheticMesh(o));
  int32_t parts = 0;
  const std::vector<int32_t> p = orderings::CacheSizedParts(big, 8192, 5, &parts);
  ASSERT_GT(parts, 4);
  const std::vector<int32_t> got = ComputeOrdering("metis-wave:8K", big, 5).new_to_old();
  EXPECT_EQ(got, orderings::WaveThroughParts(big, p, parts));
  // Each part is contiguous in the order, as metis's.
  std::vector<int32_t> first(parts, -1), last(parts, -1);
  for (int32_t i = 0; i < big.NumVertices(); ++i) {
    const int32_t q = p[got[i]];
    if (first[q] < 0) first[q] = i;
    last[q] = i;
  }
  int64_t span = 0;
  for (int32_t q = 0; q < parts; ++q) span += last[q] - first[q] + 1;
  EXPECT_EQ(span, big.NumVertices());
}

// GridParts as written: the cell of each vertex by the formula, the non-empty cells renumbered in
// row-major order by a std::map.
std::vector<int32_t> ReferenceGridParts(const Mesh& m, uint64_t bytes, int32_t* parts) {
  const int32_t n = m.NumVertices();
  const double wanted = n * orderings::SweepBytesPerVertex(m) / static_cast<double>(bytes);
  *parts = 1;
  if (wanted <= 1 || n < 4) return {};
  double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300;
  for (int32_t v = 0; v < n; ++v) {
    xlo = std::min(xlo, m.xy[2 * v]), xhi = std::max(xhi, m.xy[2 * v]);
    ylo = std::min(ylo, m.xy[2 * v + 1]), yhi = std::max(yhi, m.xy[2 * v + 1]);
  }
  const double cells = std::min<double>(std::ceil(wanted), n);
  const int64_t gx =
      std::max<int64_t>(1, std::llround(std::sqrt(cells * (xhi - xlo) / (yhi - ylo))));
  const int64_t gy = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(cells / gx)));
  std::map<int64_t, int32_t> number;
  std::vector<int64_t> cell(n);
  for (int32_t v = 0; v < n; ++v) {
    const int64_t cx =
        std::min<int64_t>(gx - 1, static_cast<int64_t>((m.xy[2 * v] - xlo) / (xhi - xlo) * gx));
    const int64_t cy =
        std::min<int64_t>(gy - 1, static_cast<int64_t>((m.xy[2 * v + 1] - ylo) / (yhi - ylo) * gy));
    cell[v] = cy * gx + cx;
    number[cell[v]] = 0;
  }
  int32_t k = 0;
  for (auto& e : number) e.second = k++;
  *parts = k;
  if (k <= 1) return {};
  std::vector<int32_t> part(n);
  for (int32_t v = 0; v < n; ++v) part[v] = number[cell[v]];
  return part;
}

TEST(GridWave, CellsMatchTheirDefinitionAndTheOrderIsTheWave) {
  int cases = 0;
  for (const Mesh& m : testing::MeshCorpus())
    for (uint64_t bytes : {512, 2048, 8192, 1 << 20}) {
      int32_t parts = 0, want_parts = 0;
      const std::vector<int32_t> got = orderings::GridParts(m, bytes, &parts);
      ASSERT_EQ(got, ReferenceGridParts(m, bytes, &want_parts)) << cases;
      ASSERT_EQ(parts, want_parts);
      const std::vector<int32_t> order =
          ComputeOrdering("grid-wave:" + std::to_string(bytes), m).new_to_old();
      if (got.empty()) {
        EXPECT_EQ(order, orderings::BfsVisitOrder(m));
      } else {
        EXPECT_EQ(order, ReferenceWaveThroughParts(m, got, parts));
        ++cases;
      }
    }
  EXPECT_GT(cases, 40);
}

TEST(GridWave, HandWorked) {
  // The unit square's four corners with 1-byte parts: min(4 cells wanted, 4 vertices) = 4, so a
  // 2 x 2 grid, one vertex a cell: (0,0) cell 0, (1,0) cell 1, (0,1) cell 2, (1,1) cell 3.
  const Mesh m = testing::UnitSquare();
  int32_t parts = 0;
  EXPECT_EQ(orderings::GridParts(m, 1, &parts), (std::vector<int32_t>{0, 1, 2, 3}));
  EXPECT_EQ(parts, 4);
  // Cells by BFS over the cell graph from vertex 0's: 0, then 1, 2, 3 (edges 0-1, 0-3, 0-2, 1-3,
  // 2-3); each a single vertex.
  EXPECT_EQ(ComputeOrdering("grid-wave:1", m).new_to_old(), (std::vector<int32_t>{0, 1, 2, 3}));
  EXPECT_THROW(ParseOrderingSpec("grid-wave:0"), UsageError);
}

}  // namespace
}  // namespace meshreuse
