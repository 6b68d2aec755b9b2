// Mesh quality as DESIGN.md defines it (paper section "Laplacian Mesh smoothing", Knupp 2001):
// triangle quality = shortest edge / longest edge in [0, 1] (equilateral = 1, degenerate = 0);
// vertex quality = mean quality of its incident triangles; global quality = mean vertex quality.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace meshreuse {

// One square root: min/max of the squared lengths, then sqrt of their ratio. The division's
// operand is guarded (where hi is 0 it divides by 1, and the result is 0 anyway), so a loop of it
// runs as vector lanes: the quality passes of smoother.cc and ranks/halo_smoother.cc.
inline double TriangleQuality(double ax, double ay, double bx, double by, double cx, double cy) {
  const double ab = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
  const double bc = (cx - bx) * (cx - bx) + (cy - by) * (cy - by);
  const double ca = (ax - cx) * (ax - cx) + (ay - cy) * (ay - cy);
  const double lo = std::min(ab, std::min(bc, ca));
  const double hi = std::max(ab, std::max(bc, ca));
  return hi > 0.0 ? std::sqrt(lo / (hi > 0.0 ? hi : 1.0)) : 0.0;
}

inline double TriangleQuality(const double* xy, const int32_t* corners) {
  const double* a = xy + 2 * static_cast<int64_t>(corners[0]);
  const double* b = xy + 2 * static_cast<int64_t>(corners[1]);
  const double* c = xy + 2 * static_cast<int64_t>(corners[2]);
  return TriangleQuality(a[0], a[1], b[0], b[1], c[0], c[1]);
}

// Triangle t's quality, its corners' coordinates read by index: the form GCC vectorises in the
// quality passes' `omp simd` loops (smoother.cc, ranks/halo_smoother.cc); with the pointers of
// the form above it leaves them scalar.
inline double TriangleQualityAt(const double* xy, const int32_t* tri, int64_t t) {
  const int64_t i = 2 * int64_t{tri[3 * t]}, j = 2 * int64_t{tri[3 * t + 1]},
                k = 2 * int64_t{tri[3 * t + 2]};
  return TriangleQuality(xy[i], xy[i + 1], xy[j], xy[j + 1], xy[k], xy[k + 1]);
}

std::vector<double> TriangleQualities(const Mesh& m);
std::vector<double> VertexQualities(const Mesh& m);
// The direct definition (mean over vertices of the mean over incident triangles); the smoother's
// incremental value is tested against it.
double GlobalQuality(const Mesh& m);

// Weight of each triangle in the global quality: sum over its corners of 1 / (V * triangles at the
// corner). Global quality = sum_t weight[t] * q[t], which lets a sweep update it from the moved
// vertex's triangles alone.
std::vector<double> GlobalQualityWeights(const Mesh& m);
// The weight from 1 / V and the triangle counts at its corners, in corner order: the one
// expression every layout uses (a rank that sees only its neighbourhood gets the same bits).
inline double QualityWeightOf(double inv_v, int64_t n0, int64_t n1, int64_t n2) {
  double w = 0.0;
  w += inv_v / static_cast<double>(n0);
  w += inv_v / static_cast<double>(n1);
  w += inv_v / static_cast<double>(n2);
  return w;
}
inline double GlobalQualityWeight(const Mesh& m, int32_t t) {
  const int32_t* c = &m.tri[3 * int64_t{t}];
  return QualityWeightOf(1.0 / static_cast<double>(m.NumVertices()), m.v2t.RowSize(c[0]),
                         m.v2t.RowSize(c[1]), m.v2t.RowSize(c[2]));
}

struct QualitySummary {
  double min = 0, mean = 0, max = 0;  // over vertices
  double global = 0;                  // == mean
  std::vector<int64_t> histogram;     // vertex qualities in equal bins over [0, 1]
};
QualitySummary SummarizeVertexQuality(const Mesh& m, int bins = 10);

}  // namespace meshreuse
