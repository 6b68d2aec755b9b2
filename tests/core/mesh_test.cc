// BuildMesh: adjacency and boundary against a naive construction (std::set / std::map), dropped
// vertices, and the topology errors that name a line.
#include "core/mesh.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <type_traits>

#include "core/error.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

static_assert(!std::is_copy_constructible_v<Mesh>, "Mesh is move-only");
static_assert(std::is_nothrow_move_constructible_v<Mesh>, "Mesh moves cheaply");

// The naive reference: neighbour sets and edge -> triangle counts from maps.
void ExpectMatchesNaive(const Mesh& m) {
  const int32_t nv = m.NumVertices();
  std::vector<std::set<int32_t>> nbr(nv), tris(nv);
  std::map<std::pair<int32_t, int32_t>, int> edges;
  for (int32_t t = 0; t < m.NumTriangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.tri[3 * t + k], b = m.tri[3 * t + (k + 1) % 3];
      nbr[a].insert(b);
      nbr[b].insert(a);
      tris[a].insert(t);
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<uint8_t> boundary(nv, 0);
  for (const auto& [e, n] : edges)
    if (n == 1) boundary[e.first] = boundary[e.second] = 1;
  std::vector<int32_t> interior;
  for (int32_t v = 0; v < nv; ++v) {
    ASSERT_EQ(std::vector<int32_t>(m.v2v.RowBegin(v), m.v2v.RowEnd(v)),
              std::vector<int32_t>(nbr[v].begin(), nbr[v].end()))
        << "v2v row " << v;
    ASSERT_EQ(std::vector<int32_t>(m.v2t.RowBegin(v), m.v2t.RowEnd(v)),
              std::vector<int32_t>(tris[v].begin(), tris[v].end()))
        << "v2t row " << v;
    if (!boundary[v]) interior.push_back(v);
  }
  EXPECT_EQ(m.boundary, boundary);
  EXPECT_EQ(std::vector<int32_t>(m.interior.begin(), m.interior.end()), interior);
}

TEST(BuildMesh, TinyMeshBoundaryAndNeighbours) {
  const Mesh m = testing::TwoInterior();
  EXPECT_EQ(m.NumVertices(), 8);
  EXPECT_EQ(m.NumTriangles(), 8);
  EXPECT_EQ(std::vector<int32_t>(m.interior.begin(), m.interior.end()),
            (std::vector<int32_t>{6, 7}));
  EXPECT_EQ(m.NumBoundary(), 6);
  EXPECT_EQ(std::vector<int32_t>(m.v2v.RowBegin(6), m.v2v.RowEnd(6)),
            (std::vector<int32_t>{0, 1, 4, 5, 7}));
  EXPECT_EQ(std::vector<int32_t>(m.v2v.RowBegin(7), m.v2v.RowEnd(7)),
            (std::vector<int32_t>{1, 2, 3, 4, 6}));
  ExpectMatchesNaive(m);
}

TEST(BuildMesh, MatchesNaiveOnManySyntheticMeshes) {
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    SyntheticOptions o;
    o.nx = 3 + static_cast<int>(seed % 17);
    o.ny = 2 + static_cast<int>(seed % 11);
    o.holes = static_cast<int>(seed % 4);
    o.seed = seed;
    RawMesh raw = MakeSyntheticMesh(o);
    if (raw.tri.empty()) continue;  // a hole may swallow a tiny grid
    SCOPED_TRACE("seed " + std::to_string(seed));
    ExpectMatchesNaive(BuildMesh(std::move(raw)));
  }
}

// Bowties: vertex 0 is the apex of two (then three) fans that share no edge, so it has more
// neighbours than triangles + 1 -- the case the single-pass row layout cannot hold, built by the
// sizing pass instead. Rows and boundary as the naive construction gives them.
TEST(BuildMesh, VertexWithSeveralFans) {
  RawMesh raw;
  raw.xy = {0, 0, 1, 0, 1, 1, -1, 0, -1, -1, 0, 1, -1, 1};
  raw.tri = {0, 1, 2, 0, 3, 4};
  const Mesh two = BuildMesh(raw);
  EXPECT_EQ(two.v2v.RowSize(0), 4);
  EXPECT_EQ(std::vector<int32_t>(two.v2v.RowBegin(0), two.v2v.RowEnd(0)),
            (std::vector<int32_t>{1, 2, 3, 4}));
  raw.tri.insert(raw.tri.end(), {0, 5, 6});
  const Mesh three = BuildMesh(raw);
  EXPECT_EQ(std::vector<int32_t>(three.v2v.RowBegin(0), three.v2v.RowEnd(0)),
            (std::vector<int32_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(std::vector<int32_t>(three.v2v.RowBegin(6), three.v2v.RowEnd(6)),
            (std::vector<int32_t>{0, 5}));
  EXPECT_EQ(three.v2v.off.back(), 18);  // 9 edges, both ways
  ExpectMatchesNaive(two);
  ExpectMatchesNaive(three);
  EXPECT_EQ(three.NumBoundary(), 7);
}

TEST(BuildMesh, BoundaryIsTopologicalNotFromMarkers) {
  // two_interior.node marks vertices 7 and 8 with marker 0 and the rest 1; two_interior0.node has
  // no markers at all. Both give the same boundary.
  const Mesh a = testing::TwoInterior();
  const Mesh b = ReadMesh(testing::DataPath("two_interior0.node"));
  EXPECT_EQ(a.boundary, b.boundary);
}

TEST(BuildMesh, DropsUnusedVerticesKeepingOrder) {
  RawMesh raw;
  raw.vertex_file = "v.node";
  raw.xy = {0, 0, 9, 9, 1, 0, 0, 1, 1, 1};  // vertex 1 is not used
  raw.tri = {0, 2, 3, 2, 4, 3};
  BuildReport report;
  const Mesh m = BuildMesh(std::move(raw), &report);
  EXPECT_EQ(m.NumVertices(), 4);
  EXPECT_EQ(std::vector<double>(m.xy.begin(), m.xy.end()),
            (std::vector<double>{0, 0, 1, 0, 0, 1, 1, 1}));
  EXPECT_EQ(std::vector<int32_t>(m.tri.begin(), m.tri.end()),
            (std::vector<int32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(report.kept, (std::vector<int32_t>{0, 2, 3, 4}));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("dropped 1 vertices"), std::string::npos) << report.warnings[0];
}

TEST(BuildMesh, CloneIsEqualAndIndependent) {
  Mesh a = testing::TwoInterior();
  Mesh b = a.Clone();
  EXPECT_EQ(a.xy, b.xy);
  EXPECT_EQ(a.v2v.idx, b.v2v.idx);
  b.xy[12] = 42;
  EXPECT_NE(a.xy[12], 42);
}

TEST(BuildMesh, RejectsOutOfRangeCorner) {
  RawMesh raw;
  raw.triangle_file = "t.ele";
  raw.triangle_line = {5};
  raw.xy = {0, 0, 1, 0, 0, 1};
  raw.tri = {0, 1, 3};
  try {
    BuildMesh(std::move(raw));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "t.ele");
    EXPECT_EQ(e.line(), 5);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

TEST(BuildMesh, RejectsEmptyAndNonFinite) {
  RawMesh none;
  none.xy = {0, 0};
  EXPECT_THROW(BuildMesh(std::move(none)), InputError);
  RawMesh inf;
  inf.xy = {0, 0, 1, 0, 0, std::numeric_limits<double>::infinity()};
  inf.tri = {0, 1, 2};
  EXPECT_THROW(BuildMesh(std::move(inf)), InputError);
}

}  // namespace
}  // namespace meshreuse

namespace meshreuse {
namespace {

TEST(Mesh, TracedArraysStartOnACacheLine) {
  for (int k = 0; k < 20; ++k) {  // a few allocations of different sizes
    SyntheticOptions o;
    o.nx = 3 + k, o.ny = 2 + k, o.seed = static_cast<uint64_t>(k + 1);
    const Mesh m = BuildMesh(MakeSyntheticMesh(o));
    EXPECT_EQ(reinterpret_cast<uintptr_t>(m.xy.data()) % 64, 0u);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(m.v2v.off.data()) % 64, 0u);
    const Mesh c = m.Clone();
    EXPECT_EQ(reinterpret_cast<uintptr_t>(c.xy.data()) % 64, 0u);
  }
}

}  // namespace
}  // namespace meshreuse
