// Quality of triangles, vertices and the whole mesh; see quality.h for the definitions.
#include "core/quality.h"

namespace meshreuse {

std::vector<double> TriangleQualities(const Mesh& m) {
  const int32_t nt = m.NumTriangles();
  std::vector<double> q(nt);
  for (int32_t t = 0; t < nt; ++t) q[t] = TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{t}]);
  return q;
}

std::vector<double> VertexQualities(const Mesh& m) {
  const std::vector<double> tq = TriangleQualities(m);
  const int32_t nv = m.NumVertices();
  std::vector<double> vq(nv, 0.0);
  for (int32_t v = 0; v < nv; ++v) {
    double s = 0.0;
    for (const int32_t* p = m.v2t.RowBegin(v); p != m.v2t.RowEnd(v); ++p) s += tq[*p];
    const int64_t n = m.v2t.RowSize(v);
    vq[v] = n > 0 ? s / static_cast<double>(n) : 0.0;
  }
  return vq;
}

// The same sums as VertexQualities in the same order, so the same bits, without its two arrays
// (24 bytes a vertex at the peak of a smoothing run): each vertex's triangles are evaluated where
// they are summed, in parallel over blocks, and the block's vertex qualities then added in order.
double GlobalQuality(const Mesh& m) {
  const int32_t nv = m.NumVertices();
  if (nv == 0) return 0.0;
  constexpr int32_t kBlock = 1 << 16;
  std::vector<double> vq(std::min(nv, kBlock));
  double s = 0.0;
  for (int32_t b = 0; b < nv; b += kBlock) {
    const int32_t e = std::min(nv, b + kBlock);
#pragma omp parallel for schedule(static, 1024)
    for (int32_t v = b; v < e; ++v) {
      double sum = 0.0;
      for (const int32_t* p = m.v2t.RowBegin(v); p != m.v2t.RowEnd(v); ++p)
        sum += TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{*p}]);
      const int64_t n = m.v2t.RowSize(v);
      vq[v - b] = n > 0 ? sum / static_cast<double>(n) : 0.0;
    }
    for (int32_t v = b; v < e; ++v) s += vq[v - b];
  }
  return s / static_cast<double>(nv);
}

std::vector<double> GlobalQualityWeights(const Mesh& m) {
  const int32_t nt = m.NumTriangles();
  std::vector<double> w(nt);
  for (int32_t t = 0; t < nt; ++t) w[t] = GlobalQualityWeight(m, t);
  return w;
}

QualitySummary SummarizeVertexQuality(const Mesh& m, int bins) {
  QualitySummary s;
  const std::vector<double> vq = VertexQualities(m);
  s.histogram.assign(bins, 0);
  if (vq.empty()) return s;
  s.min = 1.0;
  s.max = 0.0;
  double sum = 0.0;
  for (double q : vq) {
    s.min = std::min(s.min, q);
    s.max = std::max(s.max, q);
    sum += q;
    const int b = std::min(bins - 1, static_cast<int>(q * bins));
    ++s.histogram[std::max(0, b)];
  }
  s.mean = s.global = sum / static_cast<double>(vq.size());
  return s;
}

}  // namespace meshreuse
