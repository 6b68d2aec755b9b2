// Quality of known triangles (exact values), vertex and global quality on the tiny mesh.
#include "core/quality.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/test_util.h"

namespace meshreuse {
namespace {

TEST(TriangleQuality, EquilateralIsOne) {
  EXPECT_DOUBLE_EQ(TriangleQuality(0, 0, 1, 0, 0.5, std::sqrt(3.0) / 2), 1.0);
}

TEST(TriangleQuality, ExactRatios) {
  EXPECT_DOUBLE_EQ(TriangleQuality(0, 0, 3, 0, 0, 4), 3.0 / 5.0);                // 3-4-5
  EXPECT_DOUBLE_EQ(TriangleQuality(0, 0, 1, 0, 0, 1), 1.0 / std::sqrt(2.0));     // right isosceles
  EXPECT_DOUBLE_EQ(TriangleQuality(0, 0, 2, 0, 1, 10), 2.0 / std::sqrt(101.0));  // tall isosceles
}

TEST(TriangleQuality, InvariantUnderCornerOrderAndSimilarity) {
  const double q = TriangleQuality(0.1, 0.2, 3.7, 0.4, 1.3, 2.9);
  EXPECT_DOUBLE_EQ(TriangleQuality(3.7, 0.4, 1.3, 2.9, 0.1, 0.2), q);
  EXPECT_DOUBLE_EQ(TriangleQuality(1.3, 2.9, 3.7, 0.4, 0.1, 0.2), q);
  EXPECT_NEAR(TriangleQuality(10.1, 20.2, 13.7, 20.4, 11.3, 22.9), q, 1e-12);  // translated
  EXPECT_NEAR(TriangleQuality(0.2, 0.4, 7.4, 0.8, 2.6, 5.8), q, 1e-15);        // scaled by 2
}

TEST(TriangleQuality, DegenerateIsZero) {
  EXPECT_EQ(TriangleQuality(1, 1, 1, 1, 1, 1), 0.0);
  EXPECT_EQ(TriangleQuality(0, 0, 0, 0, 1, 0), 0.0);  // a zero-length edge
}

TEST(VertexQuality, MeanOfIncidentTriangles) {
  const Mesh m = testing::TwoInterior();
  const std::vector<double> tq = TriangleQualities(m);
  const std::vector<double> vq = VertexQualities(m);
  // Vertex 0 (corner (0,0)) lies in triangles 0 (1 2 7) and 4 (7 6 1) of the .ele file.
  EXPECT_DOUBLE_EQ(vq[0], (tq[0] + tq[4]) / 2);
  double naive = 0;
  for (int32_t v = 0; v < m.NumVertices(); ++v) {
    double s = 0;
    int n = 0;
    for (int32_t t = 0; t < m.NumTriangles(); ++t)
      for (int k = 0; k < 3; ++k)
        if (m.tri[3 * t + k] == v) s += tq[t], ++n;
    EXPECT_DOUBLE_EQ(vq[v], s / n) << "vertex " << v;
    naive += s / n;
  }
  EXPECT_DOUBLE_EQ(GlobalQuality(m), naive / m.NumVertices());
}

TEST(GlobalQuality, WeightsReproduceTheDefinition) {
  const Mesh m = testing::TwoInterior();
  const std::vector<double> w = GlobalQualityWeights(m);
  const std::vector<double> tq = TriangleQualities(m);
  double q = 0, wsum = 0;
  for (size_t t = 0; t < w.size(); ++t) q += w[t] * tq[t], wsum += w[t];
  EXPECT_NEAR(q, GlobalQuality(m), 1e-15);
  EXPECT_NEAR(wsum, 1.0, 1e-15);  // the weights of a mean sum to one
}

TEST(QualitySummary, HistogramCountsEveryVertex) {
  const Mesh m = testing::TwoInterior();
  const QualitySummary s = SummarizeVertexQuality(m, 10);
  int64_t n = 0;
  for (int64_t c : s.histogram) n += c;
  EXPECT_EQ(n, m.NumVertices());
  EXPECT_LE(s.min, s.mean);
  EXPECT_LE(s.mean, s.max);
  EXPECT_DOUBLE_EQ(s.mean, GlobalQuality(m));
}

}  // namespace
}  // namespace meshreuse
