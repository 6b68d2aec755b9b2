// Uniform refinement (core/refine.h): sizes by formula; a conforming mesh (BuildMesh accepts it:
// every edge in one or two triangles, no duplicate vertex) with the coarse Euler characteristic,
// the coarse boundary length and area, and positive areas, jittered or not; shared-edge points
// bit for bit the same from both sides; pieces of any split equal to the whole (what ranks rely
// on); refining once twice has the same size and area as refining twice; hand-worked ids on
// the unit square; sizes beyond 32-bit ids refused. The pieces layout: a permutation with every
// vertex in the block a naive owner search gives it, and every range's sections equal to the
// whole mesh's (built from scratch by BuildMesh) at every split, either orientation.
#include "core/refine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>

#include "core/error.h"
#include "core/mesh_file.h"
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

// The coarse meshes turned clockwise (every triangle's corners reversed): orientation is kept, so
// the pieces' area check must read it per coarse triangle.
Mesh Mirrored(const Mesh& m) {
  RawMesh raw;
  raw.xy = m.xy;
  raw.tri = m.tri;
  for (size_t t = 0; t < raw.tri.size(); t += 3) std::swap(raw.tri[t + 1], raw.tri[t + 2]);
  return BuildMesh(std::move(raw));
}

std::vector<Mesh> LaidOutCoarse() {
  std::vector<Mesh> ms;
  for (Mesh& c : Coarse()) {
    LayOutForRanks(&c);
    ms.push_back(Mirrored(c));
    ms.push_back(std::move(c));
  }
  return ms;
}

// The block (coarse triangle) a fine vertex belongs to, from its lattice position alone: a
// coarse vertex's lowest-id triangle, a coarse edge's lower-id triangle, an interior point's own.
std::vector<int32_t> NaiveOwners(const Mesh& c, const RefineOptions& o) {
  const RawMesh whole = RefineMesh(c, o);
  const int64_t n = int64_t{1} << o.levels;
  std::vector<int32_t> owner(whole.xy.size() / 2, INT32_MAX);
  for (int32_t t = 0; t < c.NumTriangles(); ++t)
    for (int64_t i = 0; i < n * n; ++i) {  // coarse triangle t's fine triangles
      const int32_t* f = &whole.tri[3 * (t * n * n + i)];
      // A point lies in the fine triangles of exactly the coarse triangles whose lattice holds
      // it: the lowest of them owns it.
      for (int k = 0; k < 3; ++k) owner[f[k]] = std::min(owner[f[k]], t);
    }
  return owner;
}

TEST(Refine, PiecesLayoutIsABlockedPermutation) {
  for (const Mesh& c : LaidOutCoarse())
    for (int k : {0, 1, 2, 3}) {
      SCOPED_TRACE("K " + std::to_string(k));
      RefineOptions o;
      o.levels = k;
      const PiecesLayout layout(c, o);
      const RefinedSize size = RefinedSizeOf(c, o);
      ASSERT_EQ(layout.vertices(), size.vertices);
      ASSERT_EQ(layout.triangles(), size.triangles);
      const std::vector<int32_t> owner = NaiveOwners(c, o);
      std::vector<int> seen(static_cast<size_t>(size.vertices), 0);
      for (int32_t g = 0; g < size.vertices; ++g) {
        const int32_t v = layout.NewId(g);
        ASSERT_GE(v, 0);
        ASSERT_LT(v, size.vertices);
        ++seen[v];
        EXPECT_GE(v, layout.BlockStart(owner[g])) << g;  // in its owner's block
        EXPECT_LT(v, layout.BlockStart(owner[g] + 1)) << g;
      }
      EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), size.vertices);  // a permutation
      for (int32_t P : {1, 2, 3, 7}) {
        EXPECT_EQ(layout.Split(0, P), 0);
        EXPECT_EQ(layout.Split(P, P), c.NumTriangles());
        for (int32_t r = 0; r < P; ++r) {
          EXPECT_LE(layout.Split(r, P), layout.Split(r + 1, P));
          // The first block at or after V r / P.
          EXPECT_GE(layout.BlockStart(layout.Split(r, P)), size.vertices * r / P);
          if (layout.Split(r, P) > 0) {
            EXPECT_LT(layout.BlockStart(layout.Split(r, P) - 1), size.vertices * r / P);
          }
        }
      }
    }
}

TEST(Refine, RangesAreTheWholePiecesMeshSectionBySection) {
  for (const Mesh& c : LaidOutCoarse())
    for (int k : {0, 1, 2, 3})
      for (double jitter : {0.0, 0.4}) {
        SCOPED_TRACE("K " + std::to_string(k) + " jitter " + std::to_string(jitter));
        RefineOptions o;
        o.levels = k, o.jitter = jitter, o.seed = 11;
        const PiecesLayout layout(c, o);
        // The reference: the whole refinement renumbered, its rows and flags built from scratch.
        const Mesh f = BuildMesh(RefineMeshPieces(c, o));
        const int64_t n = int64_t{1} << k;
        for (int32_t P : {1, 2, 3, 5}) {
          int64_t vertices = 0, triangles = 0;
          for (int32_t r = 0; r < P; ++r) {
            const int32_t tb = layout.Split(r, P), te = layout.Split(r + 1, P);
            const RefinedRange g = RefineRange(c, o, layout, tb, te);
            const int64_t a = g.first_vertex, nv = static_cast<int64_t>(g.boundary.size());
            ASSERT_EQ(a, vertices);  // ranges follow each other
            ASSERT_EQ(g.first_triangle, triangles);
            ASSERT_EQ(g.first_triangle, tb * n * n);
            for (int64_t i = 0; i < 2 * nv; ++i)
              ASSERT_EQ(std::memcmp(&g.xy[i], &f.xy[2 * a + i], 8), 0) << "xy " << a << "+" << i;
            for (int64_t i = 0; i < nv; ++i) ASSERT_EQ(g.boundary[i], f.boundary[a + i]) << a + i;
            ASSERT_EQ(g.v2t_off.size(), static_cast<size_t>(nv + 1));
            for (int64_t i = 0; i <= nv; ++i) ASSERT_EQ(g.v2t_off[i], f.v2t.off[a + i]) << a + i;
            for (size_t i = 0; i < g.v2t.size(); ++i)
              ASSERT_EQ(g.v2t[i], f.v2t.idx[g.v2t_off[0] + i]);
            double smallest = std::numeric_limits<double>::infinity();
            for (size_t i = 0; i < g.tri.size(); ++i)
              ASSERT_EQ(g.tri[i], f.tri[3 * g.first_triangle + i]);
            for (int64_t t = g.first_triangle; t < g.first_triangle + int64_t(g.tri.size() / 3);
                 ++t) {
              const double sign = SignedArea2(c.xy, &c.tri[3 * (t / (n * n))]) < 0 ? -1 : 1;
              smallest = std::min(smallest, sign * SignedArea2(f.xy, &f.tri[3 * t]));
            }
            EXPECT_EQ(g.min_area2, smallest);
            if (!g.tri.empty()) {
              EXPECT_GT(g.min_area2, 0);
            }
            vertices += nv, triangles += static_cast<int64_t>(g.tri.size() / 3);
          }
          EXPECT_EQ(vertices, f.NumVertices());
          EXPECT_EQ(triangles, f.NumTriangles());
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
