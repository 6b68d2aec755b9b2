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

double GlobalQuality(const Mesh& m) {
  const std::vector<double> vq = VertexQualities(m);
  double s = 0.0;
  for (double q : vq) s += q;
  return vq.empty() ? 0.0 : s / static_cast<double>(vq.size());
}

std::vector<double> GlobalQualityWeights(const Mesh& m) {
  const int32_t nt = m.NumTriangles();
  const double inv_v = 1.0 / static_cast<double>(m.NumVertices());
  std::vector<double> w(nt, 0.0);
  for (int32_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      w[t] += inv_v / static_cast<double>(m.v2t.RowSize(m.tri[3 * int64_t{t} + k]));
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
