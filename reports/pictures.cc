// The report's mesh pictures' data; see pictures.h.
#include "reports/pictures.h"

#include <algorithm>
#include <cstdio>
#include <deque>
#include <limits>
#include <utility>
#include <vector>

namespace meshreuse {

namespace {

std::string Coord(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.7g", v);
  return b;
}

int32_t Stride(int32_t n, int max) { return std::max<int32_t>(1, (n + max - 1) / max); }

}  // namespace

Table MeshDrawingTable() { return Table({"mesh", "kind", "x1", "y1", "x2", "y2"}); }

void AppendMeshDrawing(const std::string& name, const Mesh& m, Table* t, int max_vertices) {
  // Boundary edges: the edges of one triangle, found by sorting every triangle's edges.
  std::vector<std::pair<int32_t, int32_t>> edges;
  edges.reserve(3 * static_cast<size_t>(m.NumTriangles()));
  for (int32_t k = 0; k < m.NumTriangles(); ++k)
    for (int j = 0; j < 3; ++j) {
      const int32_t a = m.tri[3 * int64_t{k} + j], b = m.tri[3 * int64_t{k} + (j + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) {
      const auto [a, b] = edges[i];
      t->AddRow({name, "edge", Coord(m.xy[2 * int64_t{a}]), Coord(m.xy[2 * int64_t{a} + 1]),
                 Coord(m.xy[2 * int64_t{b}]), Coord(m.xy[2 * int64_t{b} + 1])});
    }
    i = j;
  }
  const int32_t step = Stride(m.NumVertices(), max_vertices);
  for (int32_t v = 0; v < m.NumVertices(); v += step)
    t->AddRow(
        {name, "vertex", Coord(m.xy[2 * int64_t{v}]), Coord(m.xy[2 * int64_t{v} + 1]), "", ""});
}

Table SmoothingWindowTable() {
  return Table({"mesh", "stage", "triangle", "x1", "y1", "x2", "y2", "x3", "y3"});
}

void AppendSmoothingWindow(const std::string& name, const Mesh& m, const SmoothOptions& smooth,
                           Table* t, int triangles) {
  if (m.interior.empty()) return;
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  for (int32_t v = 0; v < m.NumVertices(); ++v)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], m.xy[2 * int64_t{v} + k]);
      hi[k] = std::max(hi[k], m.xy[2 * int64_t{v} + k]);
    }
  const double cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2;
  int32_t seed = m.interior[0];
  double best = std::numeric_limits<double>::max();
  for (int32_t v : m.interior) {
    const double dx = m.xy[2 * int64_t{v}] - cx, dy = m.xy[2 * int64_t{v} + 1] - cy;
    if (dx * dx + dy * dy < best) best = dx * dx + dy * dy, seed = v;
  }
  // Triangles by breadth-first rings of vertices from the seed: a compact window.
  std::vector<char> seen_v(m.NumVertices(), 0), seen_t(m.NumTriangles(), 0);
  std::vector<int32_t> window;
  std::deque<int32_t> queue = {seed};
  seen_v[seed] = 1;
  while (!queue.empty() && static_cast<int>(window.size()) < triangles) {
    const int32_t v = queue.front();
    queue.pop_front();
    for (const int32_t* p = m.v2t.RowBegin(v); p != m.v2t.RowEnd(v); ++p)
      if (!seen_t[*p]) seen_t[*p] = 1, window.push_back(*p);
    for (const int32_t* p = m.v2v.RowBegin(v); p != m.v2v.RowEnd(v); ++p)
      if (!seen_v[*p]) seen_v[*p] = 1, queue.push_back(*p);
  }
  Mesh after = m.Clone();
  Smooth(after, smooth);
  for (const auto& [stage, mesh] :
       {std::pair<const char*, const Mesh*>{"before", &m}, {"after", &after}})
    for (int32_t k : window) {
      std::vector<std::string> row = {name, stage, std::to_string(k)};
      for (int j = 0; j < 3; ++j) {
        const int32_t c = mesh->tri[3 * int64_t{k} + j];
        row.push_back(Coord(mesh->xy[2 * int64_t{c}]));
        row.push_back(Coord(mesh->xy[2 * int64_t{c} + 1]));
      }
      t->AddRow(row);
    }
}

Table OrderPositionsTable() { return Table({"mesh", "ordering", "x", "y", "position"}); }

void AppendOrderPositions(const std::string& name, const std::string& ordering, const Mesh& m,
                          const Permutation& p, Table* t, int max_vertices) {
  const int32_t n = m.NumVertices(), step = Stride(n, max_vertices);
  const double last = std::max(1, n - 1);
  char pos[32];
  for (int32_t v = 0; v < n; v += step) {
    std::snprintf(pos, sizeof pos, "%.5f", p.NewOf(v) / last);
    t->AddRow({name, ordering, Coord(m.xy[2 * int64_t{v}]), Coord(m.xy[2 * int64_t{v} + 1]), pos});
  }
}

}  // namespace meshreuse
