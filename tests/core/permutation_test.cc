// Permutation: validation, inverse, and applying it to a mesh (vertices, triangles re-sorted).
#include "core/permutation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/quality.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

TEST(Permutation, ValidatesBijection) {
  EXPECT_NO_THROW(Permutation::FromNewToOld({2, 0, 1}));
  EXPECT_THROW(Permutation::FromNewToOld({0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(Permutation::FromNewToOld({0, 3, 1}), std::invalid_argument);
  EXPECT_THROW(Permutation::FromNewToOld({0, -1, 1}), std::invalid_argument);
  try {
    Permutation::FromNewToOld({1, 2, 1});
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "id 1 appears at positions 0 and 2");
  }
}

TEST(Permutation, BothDirectionsAndInverse) {
  const Permutation p = Permutation::FromNewToOld({2, 0, 3, 1});
  EXPECT_EQ(p.old_to_new(), (std::vector<int32_t>{1, 3, 0, 2}));
  for (int32_t i = 0; i < 4; ++i) EXPECT_EQ(p.NewOf(p.OldOf(i)), i);
  const Permutation q = p.Inverse();
  EXPECT_EQ(q.new_to_old(), p.old_to_new());
  EXPECT_EQ(q.old_to_new(), p.new_to_old());
  EXPECT_EQ(Permutation::Identity(3).new_to_old(), (std::vector<int32_t>{0, 1, 2}));
}

// One triangle policy for every ordering: kFile keeps the file's triangle order (identity + kFile
// = the mesh as read), kSorted sorts by smallest new corner for the identity too.
TEST(ApplyPermutation, TriangleOrderPolicy) {
  SyntheticOptions so;
  so.nx = 9, so.ny = 7, so.seed = 3;
  RawMesh raw = MakeSyntheticMesh(so);
  // Shuffle the triangles so the file's order is not already sorted.
  const int32_t nt = static_cast<int32_t>(raw.tri.size() / 3);
  for (int32_t t = 0; t + 1 < nt; t += 2)
    for (int k = 0; k < 3; ++k) std::swap(raw.tri[3 * t + k], raw.tri[3 * (nt - 1 - t) + k]);
  const Mesh m = BuildMesh(std::move(raw));
  const Permutation id = Permutation::Identity(m.NumVertices());
  const Mesh file = ApplyPermutation(m, id, TriangleOrder::kFile);
  EXPECT_TRUE(std::equal(file.tri.begin(), file.tri.end(), m.tri.begin(), m.tri.end()));
  const Mesh sorted = ApplyPermutation(m, id, TriangleOrder::kSorted);
  EXPECT_FALSE(std::equal(sorted.tri.begin(), sorted.tri.end(), m.tri.begin(), m.tri.end()));
  int32_t prev = -1;
  for (int32_t t = 0; t < sorted.NumTriangles(); ++t) {
    const int32_t lo = std::min({sorted.tri[3 * t], sorted.tri[3 * t + 1], sorted.tri[3 * t + 2]});
    EXPECT_GE(lo, prev);
    prev = lo;
  }
  // kFile under a real permutation: the same triangles, in the file's positions, renumbered.
  std::vector<int32_t> rev(m.NumVertices());
  for (int32_t i = 0; i < m.NumVertices(); ++i) rev[i] = m.NumVertices() - 1 - i;
  const Permutation p = Permutation::FromNewToOld(rev);
  const Mesh pf = ApplyPermutation(m, p, TriangleOrder::kFile);
  for (size_t i = 0; i < m.tri.size(); ++i) EXPECT_EQ(pf.tri[i], p.NewOf(m.tri[i]));
  EXPECT_EQ(ParseTriangleOrder("file"), TriangleOrder::kFile);
  EXPECT_EQ(ParseTriangleOrder("sorted"), TriangleOrder::kSorted);
  EXPECT_THROW(ParseTriangleOrder("random"), std::invalid_argument);
}

TEST(ApplyPermutation, MovesVerticesRenumbersAndResortsTriangles) {
  const Mesh m = testing::TwoInterior();
  // Reverse the vertices: new i = old 7 - i.
  const Permutation p = Permutation::FromNewToOld({7, 6, 5, 4, 3, 2, 1, 0});
  const Mesh r = ApplyPermutation(m, p);
  ASSERT_EQ(r.NumVertices(), 8);
  for (int32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(r.xy[2 * i], m.xy[2 * (7 - i)]);
    EXPECT_EQ(r.xy[2 * i + 1], m.xy[2 * (7 - i) + 1]);
    EXPECT_EQ(r.boundary[i], m.boundary[7 - i]);
  }
  EXPECT_EQ(std::vector<int32_t>(r.interior.begin(), r.interior.end()),
            (std::vector<int32_t>{0, 1}));
  // Triangles, as sets of old vertices, are the same; their smallest new corners are sorted.
  std::multiset<std::set<int32_t>> a, b;
  int32_t prev = -1;
  for (int32_t t = 0; t < m.NumTriangles(); ++t) {
    a.insert({m.tri[3 * t], m.tri[3 * t + 1], m.tri[3 * t + 2]});
    b.insert({p.OldOf(r.tri[3 * t]), p.OldOf(r.tri[3 * t + 1]), p.OldOf(r.tri[3 * t + 2])});
    const int32_t lo = std::min({r.tri[3 * t], r.tri[3 * t + 1], r.tri[3 * t + 2]});
    EXPECT_GE(lo, prev);
    prev = lo;
  }
  EXPECT_EQ(a, b);
  // Old triangle 0 is (0 1 6): new (7 6 1), corner order kept.
  bool found = false;
  for (int32_t t = 0; t < r.NumTriangles(); ++t)
    found |= r.tri[3 * t] == 7 && r.tri[3 * t + 1] == 6 && r.tri[3 * t + 2] == 1;
  EXPECT_TRUE(found);
  EXPECT_NEAR(GlobalQuality(r), GlobalQuality(m), 1e-15);
  EXPECT_THROW(ApplyPermutation(m, Permutation::Identity(3)), std::invalid_argument);
}

}  // namespace
}  // namespace meshreuse

namespace meshreuse {
namespace {

void ExpectSameMesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.xy, b.xy);
  EXPECT_EQ(a.tri, b.tri);
  EXPECT_EQ(a.boundary, b.boundary);
  EXPECT_EQ(a.interior, b.interior);
  EXPECT_EQ(a.v2v.off, b.v2v.off);
  EXPECT_EQ(a.v2v.idx, b.v2v.idx);
  EXPECT_EQ(a.v2t.off, b.v2t.off);
  EXPECT_EQ(a.v2t.idx, b.v2t.idx);
}

// Applying by permuting every array equals rebuilding the mesh from the permuted vertices and
// triangles, array for array: the 26 corpus meshes (holes, graded cells, two components) x every
// registered ordering x both triangle policies.
TEST(ApplyPermutation, DirectEqualsRebuild) {
  const std::vector<Mesh> meshes = testing::MeshCorpus();
  int compared = 0;
  for (size_t k = 0; k < meshes.size(); ++k)
    for (const OrderingInfo& o : Orderings()) {
      if (o.takes_argument()) continue;  // file: is a permutation like any other (random covers it)
      const Permutation p = ComputeOrdering(o.name, meshes[k], 3);
      for (TriangleOrder t : {TriangleOrder::kSorted, TriangleOrder::kFile}) {
        SCOPED_TRACE("mesh " + std::to_string(k) + " " + o.name + " " + TriangleOrderName(t));
        ExpectSameMesh(ApplyPermutation(meshes[k], p, t),
                       ApplyPermutationByRebuild(meshes[k], p, t));
        ++compared;
      }
    }
  EXPECT_GE(compared, 26 * 12 * 2);  // 26 meshes x 12 orderings (file: aside) x 2
}

// A working copy reused across meshes and orderings (as compare does): whatever it held before --
// a bigger mesh, a smaller one, the same mesh in another order -- the result is the fresh one.
TEST(ApplyPermutation, IntoAReusedWorkingCopyOrInPlaceEqualsFresh) {
  const std::vector<Mesh> meshes = testing::MeshCorpus();
  Mesh work;
  int compared = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (size_t k = 0; k < meshes.size(); ++k) {
      const size_t j = pass == 0 ? k : meshes.size() - 1 - k;  // sizes grow, then shrink
      for (const char* name : {"random", "bfs", "rdr", "ori"})
        for (TriangleOrder t : {TriangleOrder::kSorted, TriangleOrder::kFile}) {
          SCOPED_TRACE("mesh " + std::to_string(j) + " " + name + " " + TriangleOrderName(t));
          const Permutation p = ComputeOrdering(name, meshes[j], 5);
          ApplyPermutationInto(meshes[j], p, t, &work);
          ExpectSameMesh(work, ApplyPermutationByRebuild(meshes[j], p, t));
          ++compared;
        }
    }
  EXPECT_EQ(compared, 2 * 26 * 4 * 2);
  // In place, from a clone of each mesh: the same result.
  for (size_t k = 0; k < meshes.size(); ++k)
    for (const char* name : {"random", "rdr"})
      for (TriangleOrder t : {TriangleOrder::kSorted, TriangleOrder::kFile}) {
        SCOPED_TRACE(std::string("in place: mesh ") + std::to_string(k) + " " + name);
        const Permutation p = ComputeOrdering(name, meshes[k], 7);
        Mesh m = meshes[k].Clone();
        ApplyPermutationInPlace(&m, p, t);
        ExpectSameMesh(m, ApplyPermutationByRebuild(meshes[k], p, t));
      }
  Mesh& self = work;
  EXPECT_THROW(ApplyPermutationInto(self, Permutation::Identity(self.NumVertices()),
                                    TriangleOrder::kSorted, &self),
               std::invalid_argument);
}

// A fan: vertex 0 at the centre of 300 triangles, so under the identity it is the smallest corner
// (the sort key) of all of them -- past the one-byte rank the fast placement uses; the wide path
// must give the same mesh. Reversed, the ranks are small again.
TEST(ApplyPermutation, AFanOfThreeHundredTrianglesAtOneVertex) {
  RawMesh raw;
  const int kRing = 300;
  raw.xy = {0.0, 0.0};
  for (int k = 0; k < kRing; ++k) {
    const double a = 2 * M_PI * k / kRing;
    raw.xy.push_back(std::cos(a));
    raw.xy.push_back(std::sin(a));
  }
  for (int k = 0; k < kRing; ++k) {
    raw.tri.push_back(0);
    raw.tri.push_back(1 + k);
    raw.tri.push_back(1 + (k + 1) % kRing);
  }
  const Mesh fan = BuildMesh(std::move(raw));
  ASSERT_EQ(fan.v2t.RowSize(0), kRing);
  std::vector<int32_t> reversed(fan.NumVertices());
  for (int32_t i = 0; i < fan.NumVertices(); ++i) reversed[i] = fan.NumVertices() - 1 - i;
  for (const Permutation& p :
       {Permutation::Identity(fan.NumVertices()), Permutation::FromNewToOld(reversed),
        ComputeOrdering("random", fan, 2)})
    for (TriangleOrder t : {TriangleOrder::kSorted, TriangleOrder::kFile}) {
      ExpectSameMesh(ApplyPermutation(fan, p, t), ApplyPermutationByRebuild(fan, p, t));
      Mesh m = fan.Clone();
      ApplyPermutationInPlace(&m, p, t);
      ExpectSameMesh(m, ApplyPermutationByRebuild(fan, p, t));
    }
}

TEST(EdgeSpan, ExactOnTheTinyMesh) {
  // Identity order; the 15 edges have spans 1 x7, 2, 3, 4, 5 x3, 6 x2 (see mesh_test's rows).
  const Mesh m = testing::TwoInterior();
  const EdgeSpan e = MeasureEdgeSpan(m, Permutation::Identity(8));
  EXPECT_EQ(e.median, 2);  // the 8th of 15
  EXPECT_EQ(e.p90, 6);     // the 14th
  EXPECT_EQ(e.p99, 6);
  EXPECT_EQ(e.max, 6);
  EXPECT_DOUBLE_EQ(e.mean, 43.0 / 15);
  // Reversing the order keeps every span.
  const EdgeSpan r = MeasureEdgeSpan(m, Permutation::FromNewToOld({7, 6, 5, 4, 3, 2, 1, 0}));
  EXPECT_EQ(r.median, 2);
  EXPECT_DOUBLE_EQ(r.mean, e.mean);
}

}  // namespace
}  // namespace meshreuse
