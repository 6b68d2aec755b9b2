// BuildMesh: validation and O(V + T) adjacency construction (counting sort for v2t, a stamp array
// to collect distinct neighbours and count each edge's triangles for v2v and the boundary).
#include "core/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace meshreuse {

Mesh Mesh::Clone() const {
  Mesh m;
  m.xy = xy;
  m.tri = tri;
  m.boundary = boundary;
  m.v2v = v2v;
  m.v2t = v2t;
  m.interior = interior;
  return m;
}

namespace {

struct Where {
  const RawMesh& raw;
  int64_t TriLine(int64_t t) const {
    return t < static_cast<int64_t>(raw.triangle_line.size()) ? raw.triangle_line[t] : 0;
  }
  int64_t VertexLine(int64_t v) const {
    return v < static_cast<int64_t>(raw.vertex_line.size()) ? raw.vertex_line[v] : 0;
  }
  std::string Tag(int64_t v) const {
    return std::to_string(v < static_cast<int64_t>(raw.vertex_tag.size()) ? raw.vertex_tag[v] : v);
  }
  std::string TriName(int64_t t) const {
    const int64_t line = TriLine(t);
    return line > 0 ? "line " + std::to_string(line) : "triangle " + std::to_string(t);
  }
  [[noreturn]] void TriError(int64_t t, const std::string& what) const {
    throw InputError(raw.triangle_file, TriLine(t), what);
  }
};

// CSR of vertex -> incident triangles by counting sort; rows come out in increasing triangle id.
Csr BuildV2T(int32_t nv, const AlignedVector<int32_t>& tri) {
  Csr c;
  c.off.assign(static_cast<size_t>(nv) + 1, 0);
  for (int32_t v : tri) ++c.off[v + 1];
  for (int32_t v = 0; v < nv; ++v) c.off[v + 1] += c.off[v];
  c.idx.resize(tri.size());
  std::vector<int64_t> fill(c.off.begin(), c.off.end() - 1);
  const int64_t nt = static_cast<int64_t>(tri.size() / 3);
  for (int64_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) c.idx[fill[tri[3 * t + k]]++] = static_cast<int32_t>(t);
  return c;
}

}  // namespace

Mesh BuildMesh(RawMesh raw, BuildReport* report) {
  const Where where{raw};
  if (raw.xy.size() % 2 != 0 || raw.tri.size() % 3 != 0)
    throw InputError(raw.vertex_file, 0, "internal: coordinate or triangle array has a bad length");
  const int64_t nv_raw = static_cast<int64_t>(raw.xy.size() / 2);
  const int64_t nt = static_cast<int64_t>(raw.tri.size() / 3);
  if (nv_raw > INT32_MAX || nt > INT32_MAX)
    throw InputError(raw.vertex_file, 0, "mesh too large: vertex and triangle ids are 32-bit");
  if (nt == 0) throw InputError(raw.triangle_file, 0, "the mesh has no triangles");

  // Coordinates beyond 1e150 would overflow the squared edge lengths (quality, area) to inf and
  // NaN; no mesh needs them, so they are refused where they are read.
  constexpr double kMaxCoordinate = 1e150;
  for (int64_t v = 0; v < nv_raw; ++v)
    for (int k = 0; k < 2; ++k) {
      const double c = raw.xy[2 * v + k];
      if (!std::isfinite(c))
        throw InputError(raw.vertex_file, where.VertexLine(v),
                         "vertex " + where.Tag(v) + " has a non-finite coordinate");
      if (std::fabs(c) > kMaxCoordinate) {
        char num[32];
        std::snprintf(num, sizeof num, "%g", c);
        throw InputError(raw.vertex_file, where.VertexLine(v),
                         "vertex " + where.Tag(v) + " has the coordinate " + num +
                             ", beyond +-1e150 (squared edge lengths would overflow)");
      }
    }

  // Per-triangle checks, and which vertices are used.
  std::vector<uint8_t> used(nv_raw, 0);
  for (int64_t t = 0; t < nt; ++t) {
    const int32_t* c = &raw.tri[3 * t];
    for (int k = 0; k < 3; ++k)
      if (c[k] < 0 || c[k] >= nv_raw)
        where.TriError(t, "triangle corner refers to vertex " + std::to_string(c[k]) +
                              " (0-based)" + " which does not exist (the mesh has " +
                              std::to_string(nv_raw) + " vertices)");
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
      where.TriError(t, "degenerate triangle: vertex " + where.Tag(c[c[0] == c[1] ? 0 : 2]) +
                            " is used twice");
    const double ax = raw.xy[2 * c[0]], ay = raw.xy[2 * c[0] + 1];
    const double cross = (raw.xy[2 * c[1]] - ax) * (raw.xy[2 * c[2] + 1] - ay) -
                         (raw.xy[2 * c[1] + 1] - ay) * (raw.xy[2 * c[2]] - ax);
    if (cross == 0.0)
      where.TriError(t, "degenerate triangle: vertices " + where.Tag(c[0]) + ", " +
                            where.Tag(c[1]) + ", " + where.Tag(c[2]) +
                            " are collinear (zero area)");
    for (int k = 0; k < 3; ++k) used[c[k]] = 1;
  }

  // Drop unused vertices, keeping the order of the rest (the ORI ordering is the file's order).
  std::vector<int32_t> new_id(nv_raw, -1);
  std::vector<int32_t> kept;
  kept.reserve(nv_raw);
  for (int64_t v = 0; v < nv_raw; ++v)
    if (used[v]) {
      new_id[v] = static_cast<int32_t>(kept.size());
      kept.push_back(static_cast<int32_t>(v));
    }
  Mesh m;
  if (report)
    for (std::string& w : raw.warnings) report->warnings.push_back(std::move(w));
  const int32_t nv = static_cast<int32_t>(kept.size());
  if (nv != nv_raw) {
    if (report) {
      std::string msg = raw.vertex_file + ": dropped " + std::to_string(nv_raw - nv) +
                        " vertices that no triangle uses (first: vertex ";
      for (int64_t v = 0; v < nv_raw; ++v)
        if (!used[v]) {
          msg += where.Tag(v);
          if (where.VertexLine(v) > 0) msg += ", line " + std::to_string(where.VertexLine(v));
          break;
        }
      report->warnings.push_back(msg + ")");
    }
    m.xy.resize(2 * static_cast<size_t>(nv));
    for (int32_t v = 0; v < nv; ++v) {
      m.xy[2 * v] = raw.xy[2 * kept[v]];
      m.xy[2 * v + 1] = raw.xy[2 * kept[v] + 1];
    }
    for (int32_t& c : raw.tri) c = new_id[c];
    std::vector<double>().swap(raw.xy);
  } else {
    m.xy.assign(raw.xy.begin(), raw.xy.end());
    std::vector<double>().swap(raw.xy);
  }
  m.tri.assign(raw.tri.begin(), raw.tri.end());
  std::vector<int32_t>().swap(raw.tri);
  m.v2t = BuildV2T(nv, m.tri);

  // One pass over vertices: distinct neighbours (v2v), each edge's triangle count (boundary and
  // non-manifold edges) and duplicate triangles (checked at the triangle's smallest corner).
  auto raw_tag = [&](int32_t v) { return where.Tag(kept[v]); };
  m.boundary.assign(nv, 0);
  m.v2v.off.assign(static_cast<size_t>(nv) + 1, 0);
  m.v2v.idx.reserve(m.tri.size());
  std::vector<int32_t> stamp(nv, -1), count(nv, 0), first_tri(nv, -1), row;
  for (int32_t v = 0; v < nv; ++v) {
    row.clear();
    const int32_t* tb = m.v2t.RowBegin(v);
    const int32_t* te = m.v2t.RowEnd(v);
    for (const int32_t* p = tb; p != te; ++p) {
      const int32_t* c = &m.tri[3 * static_cast<int64_t>(*p)];
      int32_t a = -1, b = -1;  // the other two corners
      for (int k = 0; k < 3; ++k)
        if (c[k] != v) (a < 0 ? a : b) = c[k];
      if (a > b) std::swap(a, b);
      if (v < a) {  // v is the smallest corner: compare with earlier triangles at v of that kind
        for (const int32_t* q = tb; q != p; ++q) {
          const int32_t* d = &m.tri[3 * static_cast<int64_t>(*q)];
          const int32_t lo = std::min({d[0], d[1], d[2]});
          if (lo != v) continue;
          const int32_t hi = std::max({d[0], d[1], d[2]});
          const int32_t mid = d[0] + d[1] + d[2] - lo - hi;
          if (mid == a && hi == b)
            where.TriError(*p, "duplicate triangle: vertices " + raw_tag(v) + ", " + raw_tag(a) +
                                   ", " + raw_tag(b) + " already form a triangle at " +
                                   where.TriName(*q));
        }
      }
      for (int32_t u : {a, b}) {
        if (stamp[u] != v) {
          stamp[u] = v;
          count[u] = 1;
          first_tri[u] = *p;
          row.push_back(u);
        } else if (++count[u] > 2) {
          where.TriError(*p, "non-manifold edge: the edge " + raw_tag(v) + "-" + raw_tag(u) +
                                 " already has two triangles (first at " +
                                 where.TriName(first_tri[u]) + ")");
        }
      }
    }
    std::sort(row.begin(), row.end());
    for (int32_t u : row) {
      if (count[u] == 1) m.boundary[v] = m.boundary[u] = 1;
      m.v2v.idx.push_back(u);
    }
    m.v2v.off[v + 1] = static_cast<int64_t>(m.v2v.idx.size());
  }
  m.v2v.idx.shrink_to_fit();
  for (int32_t v = 0; v < nv; ++v)
    if (!m.boundary[v]) m.interior.push_back(v);
  if (report) report->kept = std::move(kept);
  return m;
}

}  // namespace meshreuse
