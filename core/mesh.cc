// BuildMesh: validation and O(V + T) adjacency construction (counting sort for v2t; per vertex,
// in parallel and without data-dependent branches, its neighbour row, boundary flag and topology
// checks).
#include "core/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/error.h"

namespace meshreuse {

Mesh Mesh::Clone() const {
  Mesh m;
  CopyInto(&m);
  return m;
}

void Mesh::CopyInto(Mesh* out) const {
  out->xy = xy;
  out->tri = tri;
  out->boundary = boundary;
  out->v2v = v2v;
  out->v2t = v2t;
  out->interior = interior;
}

namespace {

bool HasCorner(const int32_t* c, int32_t u) { return c[0] == u || c[1] == u || c[2] == u; }

struct Where {
  const RawMesh& raw;
  int64_t TriLine(int64_t t) const { return raw.triangle_line.At(t); }
  int64_t VertexLine(int64_t v) const { return raw.vertex_line.At(v); }
  std::string Tag(int64_t v) const { return std::to_string(raw.vertex_tag.At(v, v)); }
  std::string TriName(int64_t t) const {
    const int64_t line = TriLine(t);
    return line > 0 ? "line " + std::to_string(line) : "triangle " + std::to_string(t);
  }
  [[noreturn]] void TriError(int64_t t, const std::string& what) const {
    throw InputError(raw.triangle_file, TriLine(t), what);
  }
};

// Coordinates beyond 1e150 would overflow the squared edge lengths (quality, area) to inf and
// NaN; no mesh needs them, so they are refused where they are read.
void CheckCoordinates(const RawMesh& raw, const Where& where, int64_t nv_raw) {
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
}

// Per-triangle checks, in parallel; on a failure the first failing triangle is checked again,
// serially, for the message the serial order gives.
void CheckTriangles(const RawMesh& raw, const Where& where, int64_t nv_raw, int64_t nt) {
  auto check_triangle = [&](int64_t t, bool loud) {
    const int32_t* c = &raw.tri[3 * t];
    for (int k = 0; k < 3; ++k)
      if (c[k] < 0 || c[k] >= nv_raw) {
        if (!loud) return false;
        where.TriError(t, "triangle corner refers to vertex " + std::to_string(c[k]) +
                              " (0-based)" + " which does not exist (the mesh has " +
                              std::to_string(nv_raw) + " vertices)");
      }
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) {
      if (!loud) return false;
      where.TriError(t, "degenerate triangle: vertex " + where.Tag(c[c[0] == c[1] ? 0 : 2]) +
                            " is used twice");
    }
    const double ax = raw.xy[2 * c[0]], ay = raw.xy[2 * c[0] + 1];
    const double cross = (raw.xy[2 * c[1]] - ax) * (raw.xy[2 * c[2] + 1] - ay) -
                         (raw.xy[2 * c[1] + 1] - ay) * (raw.xy[2 * c[2]] - ax);
    if (cross == 0.0) {
      if (!loud) return false;
      where.TriError(t, "degenerate triangle: vertices " + where.Tag(c[0]) + ", " +
                            where.Tag(c[1]) + ", " + where.Tag(c[2]) +
                            " are collinear (zero area)");
    }
    return true;
  };
  int64_t first_bad_tri = nt;
#pragma omp parallel for schedule(static, 8192) reduction(min : first_bad_tri)
  for (int64_t t = 0; t < nt; ++t)
    if (!check_triangle(t, false)) first_bad_tri = std::min(first_bad_tri, t);
  if (first_bad_tri < nt) check_triangle(first_bad_tri, true);  // throws
}

// Drops unused vertices, keeping the order of the rest (the ORI ordering is the file's order);
// returns the kept raw ids (empty when every vertex is used). Only then are the renumbering arrays
// built: a mesh that uses every vertex needs none.
std::vector<int32_t> DropUnused(RawMesh& raw, const Where& where, std::vector<uint8_t>& used,
                                BuildReport* report) {
  const int64_t nv_raw = static_cast<int64_t>(raw.xy.size() / 2);
  int64_t n_used = 0;
  for (uint8_t u : used) n_used += u;
  const int32_t nv = static_cast<int32_t>(n_used);
  std::vector<int32_t> kept;
  if (nv != nv_raw) {
    std::vector<int32_t> new_id(nv_raw, -1);
    kept.reserve(nv);
    for (int64_t v = 0; v < nv_raw; ++v)
      if (used[v]) {
        new_id[v] = static_cast<int32_t>(kept.size());
        kept.push_back(static_cast<int32_t>(v));
      }
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
    for (int32_t v = 0; v < nv; ++v) {  // in place: kept[v] >= v
      raw.xy[2 * int64_t{v}] = raw.xy[2 * int64_t{kept[v]}];
      raw.xy[2 * int64_t{v} + 1] = raw.xy[2 * int64_t{kept[v]} + 1];
    }
    raw.xy.resize(2 * static_cast<size_t>(nv));
    raw.xy.shrink_to_fit();
    for (int32_t& c : raw.tri) c = new_id[c];
  }
  return kept;
}

// v2t by a counting sort: rows in increasing triangle id. The offsets serve as the fill cursors
// (each ends at the next row's start) and are shifted back afterwards.
void BuildV2t(Mesh& m, int32_t nv) {
  m.v2t.off.assign(static_cast<size_t>(nv) + 1, 0);
  for (int32_t c : m.tri) ++m.v2t.off[c + 1];
  for (int32_t v = 0; v < nv; ++v) m.v2t.off[v + 1] += m.v2t.off[v];
  m.v2t.idx.resize(m.tri.size());
  {
    AlignedVector<int64_t>& cur = m.v2t.off;
    const int64_t nt_ = static_cast<int64_t>(m.tri.size() / 3);
    for (int64_t t = 0; t < nt_; ++t)
      for (int k = 0; k < 3; ++k) m.v2t.idx[cur[m.tri[3 * t + k]]++] = static_cast<int32_t>(t);
    for (int32_t v = nv; v > 0; --v) cur[v] = cur[v - 1];
    cur[0] = 0;
  }
}

// Per vertex: its distinct neighbours with each edge's triangle count (boundary and non-manifold
// edges) and duplicate triangles (checked at the triangle's smallest corner). Vertices are
// independent, so this runs in parallel. On an error the first offending vertex is visited
// again, serially, to throw the message the serial order would give.
struct Nbr {
  int32_t u;
  int32_t count;  // triangles on the edge v-u
};
// Fills `row` with v's neighbours, sorted, and says whether v's triangles are sound. Without
// branches on the data: the 2 x deg other corners (a < b per triangle) are ranked, stably, into
// order, runs of equal ids become (id, count), and duplicate triangles are a mask over the
// pairs. With branches (a lookup per corner, an insertion sort) the pass was bound by
// mispredictions: 0.96 s against 0.51 s at 10^7 vertices on two threads. That is O(deg^2) per
// vertex, so above kSmallFan corners the same results come from sorting, O(deg log deg): one
// vertex in 100,000 triangles (a fan) took 20 s the quadratic way.
constexpr int kSmallFan = 128;
struct Scratch {
  std::vector<int32_t> w, sorted;
  std::vector<Nbr> row;
  std::vector<std::pair<int32_t, int32_t>> pairs;
};
bool Neighbours(const Mesh& m, int32_t v, Scratch& s) {
  const int32_t* tb = m.v2t.RowBegin(v);
  const int n = static_cast<int>(2 * m.v2t.RowSize(v));
  s.w.resize(n);
  s.sorted.resize(n);
  int32_t* w = s.w.data();
  for (int j = 0; j < n; j += 2) {
    const int32_t* c = &m.tri[3 * static_cast<int64_t>(tb[j / 2])];
    const int32_t a = c[0] == v ? c[1] : c[0], b = c[2] == v ? c[1] : c[2];
    w[j] = std::min(a, b), w[j + 1] = std::max(a, b);
  }
  bool bad = false;
  if (n <= kSmallFan) {
    for (int i = 0; i < n; ++i) {
      int rank = 0;
      for (int l = 0; l < n; ++l) rank += (w[l] < w[i]) | ((w[l] == w[i]) & (l < i));
      s.sorted[rank] = w[i];
    }
    for (int j = 0; j < n; j += 2)
      for (int q = 0; q < j; q += 2) bad |= (v < w[j]) & (w[q] == w[j]) & (w[q + 1] == w[j + 1]);
  } else {
    std::copy(w, w + n, s.sorted.begin());
    std::sort(s.sorted.begin(), s.sorted.end());
    s.pairs.clear();  // the triangles whose smallest corner is v: a repeated pair is a duplicate
    for (int j = 0; j < n; j += 2)
      if (v < w[j]) s.pairs.emplace_back(w[j], w[j + 1]);
    std::sort(s.pairs.begin(), s.pairs.end());
    bad = std::adjacent_find(s.pairs.begin(), s.pairs.end()) != s.pairs.end();
  }
  std::vector<Nbr>& row = s.row;
  row.resize(static_cast<size_t>(n));
  int k = 0;
  if (n) row[0] = {s.sorted[0], 1};
  for (int i = 1; i < n; ++i) {
    const bool same = s.sorted[i] == s.sorted[i - 1];
    const int32_t c = row[k].count;
    k += !same;
    row[k].u = s.sorted[i];
    row[k].count = same ? c + 1 : 1;
  }
  row.resize(static_cast<size_t>(n ? k + 1 : 0));
  for (const Nbr& x : row) bad |= x.count > 2;
  return !bad;
}

// The first topology error at v, in the order of v's triangles, as a message (thrown).
[[noreturn]] void ThrowTopologyError(const Mesh& m, const Where& where,
                                     const std::vector<int32_t>& kept, int32_t v) {
  auto raw_tag = [&](int32_t x) { return where.Tag(kept.empty() ? x : kept[x]); };
  // Hashed, so that a vertex of any degree is checked in linear time.
  std::unordered_map<int32_t, int32_t> seen;     // neighbour -> triangles on the edge v-u
  std::unordered_map<uint64_t, int32_t> formed;  // (a, b) -> the first triangle v-a-b
  const int32_t* tb = m.v2t.RowBegin(v);
  for (const int32_t* p = tb; p != m.v2t.RowEnd(v); ++p) {
    const int32_t* c = &m.tri[3 * static_cast<int64_t>(*p)];
    const int32_t a0 = c[0] == v ? c[1] : c[0], b0 = c[2] == v ? c[1] : c[2];
    const int32_t a = std::min(a0, b0), b = std::max(a0, b0);
    if (v < a) {  // v is the smallest corner: compare with earlier triangles at v of that kind
      const uint64_t key = uint64_t{static_cast<uint32_t>(a)} << 32 | static_cast<uint32_t>(b);
      const auto [it, fresh] = formed.emplace(key, *p);
      if (!fresh)
        where.TriError(*p, "duplicate triangle: vertices " + raw_tag(v) + ", " + raw_tag(a) + ", " +
                               raw_tag(b) + " already form a triangle at " +
                               where.TriName(it->second));
    }
    for (int32_t u : {a, b}) {
      if (++seen[u] > 2) {
        const int32_t* first = tb;  // the first triangle at v with the edge v-u
        while (!HasCorner(&m.tri[3 * static_cast<int64_t>(*first)], u)) ++first;
        where.TriError(*p, "non-manifold edge: the edge " + raw_tag(v) + "-" + raw_tag(u) +
                               " already has two triangles (first at " + where.TriName(*first) +
                               ")");
      }
    }
  }
  throw InputError(where.raw.triangle_file, 0,
                   "internal: no topology error at vertex " + std::to_string(v));
}

// v2v and the boundary flags, each vertex's row from its triangles (Neighbours), in parallel. One
// pass writes each row at a slot bounded by its triangle count: a vertex whose triangles form one
// fan has at most one neighbour more than triangles, so row v starts at v2t.off[v] + v. The rows
// are then moved down in order (each only ever moves left). A vertex with several fans (a bowtie)
// may not fit: then a second pass fills the sized rows.
void BuildV2v(Mesh& m, const Where& where, const std::vector<int32_t>& kept, int32_t nv) {
  m.boundary.resize(nv);
  m.v2v.off.resize(static_cast<size_t>(nv) + 1);
  m.v2v.off[0] = 0;
  m.v2v.idx.resize(static_cast<size_t>(m.v2t.off[nv] + nv));
  int32_t first_bad = nv;
  bool spill = false;
#pragma omp parallel reduction(min : first_bad) reduction(|| : spill)
  {
    Scratch s;
#pragma omp for schedule(static, 4096)
    for (int32_t v = 0; v < nv; ++v) {
      if (!Neighbours(m, v, s)) first_bad = std::min(first_bad, v);
      bool on_boundary = false;
      for (const Nbr& n : s.row) on_boundary |= n.count == 1;
      m.boundary[v] = on_boundary;
      m.v2v.off[v + 1] = static_cast<int64_t>(s.row.size());
      if (static_cast<int64_t>(s.row.size()) > m.v2t.RowSize(v) + 1) {
        spill = true;
        continue;
      }
      int32_t* out = m.v2v.idx.data() + m.v2t.off[v] + v;
      for (const Nbr& n : s.row) *out++ = n.u;
    }
  }
  if (first_bad < nv) ThrowTopologyError(m, where, kept, first_bad);
  for (int32_t v = 0; v < nv; ++v) m.v2v.off[v + 1] += m.v2v.off[v];
  if (!spill) {
    for (int32_t v = 0; v < nv; ++v)  // off[v] <= v2t.off[v] + v: a forward move never overlaps
      std::memmove(m.v2v.idx.data() + m.v2v.off[v], m.v2v.idx.data() + m.v2t.off[v] + v,
                   sizeof(int32_t) * static_cast<size_t>(m.v2v.RowSize(v)));
    m.v2v.idx.resize(static_cast<size_t>(m.v2v.off[nv]));
  } else {
    m.v2v.idx.resize(static_cast<size_t>(m.v2v.off[nv]));
#pragma omp parallel
    {
      Scratch s;
#pragma omp for schedule(static, 4096)
      for (int32_t v = 0; v < nv; ++v) {
        Neighbours(m, v, s);
        int32_t* out = m.v2v.idx.data() + m.v2v.off[v];
        for (const Nbr& n : s.row) *out++ = n.u;
      }
    }
  }
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
  CheckCoordinates(raw, where, nv_raw);
  CheckTriangles(raw, where, nv_raw, nt);
  std::vector<uint8_t> used(nv_raw, 0);
  for (int32_t c : raw.tri) used[c] = 1;
  Mesh m;
  if (report)
    for (std::string& w : raw.warnings) report->warnings.push_back(std::move(w));
  std::vector<int32_t> kept = DropUnused(raw, where, used, report);
  const int32_t nv = static_cast<int32_t>(raw.xy.size() / 2);
  used = std::vector<uint8_t>();
  m.xy = std::move(raw.xy);
  m.tri = std::move(raw.tri);
  BuildV2t(m, nv);
  BuildV2v(m, where, kept, nv);
  int64_t n_interior = 0;
  for (uint8_t b : m.boundary) n_interior += !b;
  m.interior.resize(static_cast<size_t>(n_interior));
  for (int32_t v = 0, k = 0; v < nv; ++v)
    if (!m.boundary[v]) m.interior[k++] = v;
  if (report) report->kept = std::move(kept);
  return m;
}

}  // namespace meshreuse
