// Uniform refinement (core/refine.h): sizes by formula; a conforming mesh (BuildMesh accepts it:
// every edge in one or two triangles, no duplicate vertex) with the coarse Euler characteristic,
// the coarse boundary length and area, and positive areas, jittered or not; shared-edge points
// bit for bit the same from both sides; pieces of any split equal to the whole (what ranks rely
// on); refining once twice has the same size and area as refining twice; hand-worked ids on
// the unit square; sizes beyond 32-bit ids refused.
#include "core/refine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "core/error.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

double SignedArea2(const AlignedVector<double>& xy, const int32_t* c) {
  auto X = [&](int32_t v) { return xy[2 * int64_t{v}]; };
  auto Y = [&](int32_t v) { return xy[2 * int64_t{v} + 1]; };
  return (X(c[1]) - X(c[0])) * (Y(c[2]) - Y(c[0])) - (X(c[2]) - X(c[0])) * (Y(c[1]) - Y(c[0]));
}

int64_t Edges(const Mesh& m) { return static_cast<int64_t>(m.v2v.idx.size()) / 2; }

int64_t BoundaryEdges(const Mesh& m) {
  std::map<std::pair<int32_t, int32_t>, int> count;
  for (int32_t t = 0; t < m.NumTriangles(); ++t)
    for (int i = 0; i < 3; ++i) {
      int32_t a = m.tri[3 * t + i], b = m.tri[3 * t + (i + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  int64_t b = 0;
  for (const auto& e : count) b += e.second == 1;
  return b;
}

double Area(const Mesh& m) {
  double a = 0;
  for (int32_t t = 0; t < m.NumTriangles(); ++t) a += SignedArea2(m.xy, &m.tri[3 * t]);
  return a / 2;
}

std::vector<Mesh> Coarse() {
  std::vector<Mesh> ms;
  for (uint64_t seed : {1, 2, 5}) {
    SyntheticOptions o;
    o.nx = 6 + static_cast<int>(seed), o.ny = 5, o.holes = static_cast<int>(seed % 3),
    o.seed = seed;
    ms.push_back(BuildMesh(MakeSyntheticMesh(o)));
  }
  ms.push_back(testing::TwoInterior());
  ms.push_back(ReadMesh(testing::DataPath("two_components.node")));
  return ms;
}

TEST(Refine, ConformingMeshOfTheRightSizeAndShape) {
  for (const Mesh& c : Coarse())
    for (int k : {0, 1, 2, 3})
      for (double jitter : {0.0, 0.5}) {
        SCOPED_TRACE("K " + std::to_string(k) + " jitter " + std::to_string(jitter));
        RefineOptions o;
        o.levels = k, o.jitter = jitter, o.seed = 7;
        const int64_t n = int64_t{1} << k;
        const Mesh f = BuildMesh(RefineMesh(c, o));  // refuses a non-conforming mesh
        EXPECT_EQ(f.NumTriangles(), c.NumTriangles() * n * n);
        EXPECT_EQ(f.NumVertices(),
                  c.NumVertices() + Edges(c) * (n - 1) + c.NumTriangles() * (n - 1) * (n - 2) / 2);
        EXPECT_EQ(f.NumVertices() - Edges(f) + f.NumTriangles(),
                  c.NumVertices() - Edges(c) + c.NumTriangles());  // Euler characteristic
        EXPECT_EQ(BoundaryEdges(f), BoundaryEdges(c) * n);
        double smallest = 1e300;
        for (int32_t t = 0; t < f.NumTriangles(); ++t)
          smallest = std::min(smallest, SignedArea2(f.xy, &f.tri[3 * t]));
        EXPECT_GT(smallest, 0);  // orientation kept (the coarse meshes are counter-clockwise)
        // Jitter moves no boundary vertex, so the area is the coarse area (to rounding).
        EXPECT_NEAR(Area(f), Area(c), 1e-9 * std::abs(Area(c)));
        std::set<std::pair<double, double>> points;
        for (int32_t v = 0; v < f.NumVertices(); ++v) points.insert({f.xy[2 * v], f.xy[2 * v + 1]});
        EXPECT_EQ(static_cast<int32_t>(points.size()), f.NumVertices());  // no point twice
      }
}

TEST(Refine, PiecesEqualTheWholeBitForBit) {
  for (const Mesh& c : Coarse()) {
    RefineOptions o;
    o.levels = 2, o.jitter = 0.3, o.seed = 3;
    const RawMesh whole = RefineMesh(c, o);
    for (int ranks : {1, 2, 3, 4}) {
      std::vector<int32_t> tri;
      std::map<int32_t, std::pair<double, double>> xy;
      for (int r = 0; r < ranks; ++r) {
        const int32_t b = static_cast<int32_t>(int64_t{c.NumTriangles()} * r / ranks);
        const int32_t e = static_cast<int32_t>(int64_t{c.NumTriangles()} * (r + 1) / ranks);
        const RefinedPiece p = RefinePiece(c, o, b, e);
        tri.insert(tri.end(), p.tri.begin(), p.tri.end());
        for (size_t i = 0; i < p.ids.size(); ++i) {
          const std::pair<double, double> at{p.xy[2 * i], p.xy[2 * i + 1]};
          auto [it, fresh] = xy.emplace(p.ids[i], at);
          // A vertex two pieces share (on a coarse edge or corner): the same bits from both.
          if (!fresh) {
            EXPECT_EQ(std::memcmp(&it->second, &at, sizeof at), 0) << p.ids[i];
          }
        }
      }
      AlignedVector<double> all(whole.xy.size());
      ASSERT_EQ(xy.size() * 2, all.size());
      for (const auto& [id, p] : xy) all[2 * id] = p.first, all[2 * id + 1] = p.second;
      EXPECT_EQ(MeshContentHash(all, AlignedVector<int32_t>(tri.begin(), tri.end())),
                MeshContentHash(whole.xy, whole.tri))
          << ranks << " pieces";
    }
  }
}

TEST(Refine, HandWorkedUnitSquare) {
  // Corners 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1); triangles (0 1 3), (0 3 2); edges by (lo, hi):
  // 0-1, 0-2, 0-3, 1-3, 2-3 -> their midpoints are 4..8. K = 1: no interior points.
  RefineOptions o;
  const RawMesh r = RefineMesh(testing::UnitSquare(), o);
  EXPECT_EQ(r.xy, (AlignedVector<double>{0, 0, 1, 0, 0, 1, 1, 1, 0.5, 0, 0, 0.5, 0.5, 0.5, 1, 0.5,
                                         0.5, 1}));
  // Triangle (0 1 3): lattice (0,0)=0 (1,0)=m01=4 (2,0)=1 (0,1)=m03=6 (1,1)=m13=7 (0,2)=3.
  // Row 0: up 0 4 6, down 4 7 6, up 4 1 7; row 1: up 6 7 3. Then (0 3 2) likewise.
  EXPECT_EQ(r.tri, (AlignedVector<int32_t>{0, 4, 6, 4, 7, 6, 4, 1, 7, 6, 7, 3,  //
                                           0, 6, 5, 6, 8, 5, 6, 3, 8, 5, 8, 2}));
}

TEST(Refine, RefusedSizesAndOptions) {
  const Mesh m = testing::TwoInterior();
  RefineOptions o;
  o.levels = 15;  // 8 triangles x 4^15 = 2^33
  EXPECT_THROW(RefinedSizeOf(m, o), UsageError);
  o.levels = -1;
  EXPECT_THROW(RefineMesh(m, o), UsageError);
  o.levels = 1, o.jitter = 0.6;
  EXPECT_THROW(RefineMesh(m, o), UsageError);
  o.jitter = 0;
  EXPECT_EQ(RefinedSizeOf(m, o).triangles, 4 * m.NumTriangles());
}

}  // namespace
}  // namespace meshreuse
