// The built-in generator: deterministic per seed, positive areas, holes, poor-quality triangles.
#include "core/synthetic.h"

#include <gtest/gtest.h>

#include "core/quality.h"

namespace meshreuse {
namespace {

TEST(Synthetic, SameSeedSameMesh) {
  SyntheticOptions o;
  o.seed = 99;
  const RawMesh a = MakeSyntheticMesh(o), b = MakeSyntheticMesh(o);
  EXPECT_EQ(a.xy, b.xy);
  EXPECT_EQ(a.tri, b.tri);
  o.seed = 100;
  EXPECT_NE(MakeSyntheticMesh(o).xy, a.xy);
}

TEST(Synthetic, EveryTriangleHasPositiveAreaEvenAtMaximumJitter) {
  for (uint64_t seed = 1; seed <= 30; ++seed) {
    SyntheticOptions o;
    o.nx = 25, o.ny = 20, o.jitter = 1.0 /* capped at 0.24 */, o.holes = 3, o.seed = seed;
    const RawMesh r = MakeSyntheticMesh(o);
    for (size_t t = 0; t < r.tri.size() / 3; ++t) {
      const int32_t* c = &r.tri[3 * t];
      const double* a = &r.xy[2 * c[0]];
      const double* b = &r.xy[2 * c[1]];
      const double* d = &r.xy[2 * c[2]];
      const double cross = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
      ASSERT_GT(cross, 0.0) << "seed " << seed << " triangle " << t;
    }
  }
}

TEST(Synthetic, HolesAndPoorQuality) {
  SyntheticOptions o;
  o.nx = 30, o.ny = 20, o.holes = 2, o.seed = 5;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  EXPECT_LT(m.NumTriangles(), 2 * 30 * 20);  // cells were cut out
  // Boundary vertices beyond the outer rectangle's 2 * (30 + 20): the holes' rims.
  EXPECT_GT(m.NumBoundary(), 2 * (30 + 20));
  const QualitySummary s = SummarizeVertexQuality(m);
  EXPECT_LT(s.min, 0.3);
}

}  // namespace
}  // namespace meshreuse
