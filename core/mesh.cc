// BuildMesh: validation and O(V + T) adjacency construction (counting sort for v2t, each
// incidence's opposite corners laid out per vertex for the neighbour rows, the boundary and the
// topology checks; the per-vertex work runs in parallel).
#include "core/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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

  // Per-triangle checks, in parallel; on a failure the first failing triangle is checked again,
  // serially, for the message the serial order gives. Then which vertices are used.
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
  std::vector<uint8_t> used(nv_raw, 0);
  for (int32_t c : raw.tri) used[c] = 1;

  // Drop unused vertices, keeping the order of the rest (the ORI ordering is the file's order).
  // Only then are the renumbering arrays built: a mesh that uses every vertex needs none.
  Mesh m;
  if (report)
    for (std::string& w : raw.warnings) report->warnings.push_back(std::move(w));
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
  used = std::vector<uint8_t>();
  m.xy = std::move(raw.xy);
  m.tri = std::move(raw.tri);
  // The neighbour pass below reads, for each vertex, the two other corners of each of its
  // triangles. Read through v2t they lie anywhere in the triangle array (about six scattered
  // lines a vertex: most of the build at 10^7 vertices); so they are first written out per vertex,
  // in v2t's order, by the counting sort v2t uses (`opp`: 8 bytes per incidence, freed before v2t's
  // own entries are written, so the peak stays below the finished mesh plus v2v).
  m.v2t.off.assign(static_cast<size_t>(nv) + 1, 0);
  for (int32_t c : m.tri) ++m.v2t.off[c + 1];
  for (int32_t v = 0; v < nv; ++v) m.v2t.off[v + 1] += m.v2t.off[v];
  AlignedVector<int32_t> opp(2 * m.tri.size());
  {
    AlignedVector<int64_t>& cur = m.v2t.off;  // cursors, shifted back below
    const int64_t nt_ = static_cast<int64_t>(m.tri.size() / 3);
    for (int64_t t = 0; t < nt_; ++t) {
      const int32_t* c = &m.tri[3 * t];
      for (int k = 0; k < 3; ++k) {
        int32_t a = c[(k + 1) % 3], b = c[(k + 2) % 3];
        if (a > b) std::swap(a, b);
        const int64_t pos = cur[c[k]]++;
        opp[2 * pos] = a;
        opp[2 * pos + 1] = b;
      }
    }
    for (int32_t v = nv; v > 0; --v) cur[v] = cur[v - 1];
    cur[0] = 0;
  }
  // Tags of mesh vertices, for messages: the raw vertex's.
  auto raw_of = [&](int32_t v) { return kept.empty() ? v : kept[v]; };

  // Per vertex: its distinct neighbours with each edge's triangle count (boundary and non-manifold
  // edges) and duplicate triangles (checked at the triangle's smallest corner). Vertices are
  // independent, so this runs in parallel. A row's neighbours are a handful, kept in a small local
  // list. On an error the first offending vertex is visited again, serially, through v2t, to throw
  // the message the serial order would give.
  auto raw_tag = [&](int32_t v) { return where.Tag(raw_of(v)); };
  // The first triangle at v that has the edge v-u, for the non-manifold message.
  auto first_with = [&](int32_t v, int32_t u) {
    for (const int32_t* q = m.v2t.RowBegin(v); q != m.v2t.RowEnd(v); ++q) {
      const int32_t* d = &m.tri[3 * static_cast<int64_t>(*q)];
      if (d[0] == u || d[1] == u || d[2] == u) return *q;
    }
    return -1;
  };
  struct Nbr {
    int32_t u;
    int32_t count;  // triangles on the edge v-u
  };
  // The same from `opp`, quietly: false on a topology error (found at the same vertex as `visit`
  // would, which then gives the message).
  auto visit_opp = [&](int32_t v, std::vector<Nbr>& row) {
    row.clear();
    const int64_t b0 = m.v2t.off[v], e0 = m.v2t.off[v + 1];
    for (int64_t j = b0; j < e0; ++j) {
      const int32_t a = opp[2 * j], b = opp[2 * j + 1];
      if (v < a)  // v is the smallest corner: compare with earlier triangles at v of that kind
        for (int64_t q = b0; q < j; ++q)
          if (opp[2 * q] == a && opp[2 * q + 1] == b) return false;
      for (int32_t u : {a, b}) {
        size_t k = 0;
        while (k < row.size() && row[k].u != u) ++k;
        if (k == row.size())
          row.push_back({u, 1});
        else if (++row[k].count > 2)
          return false;
      }
    }
    for (size_t i = 1; i < row.size(); ++i) {
      const Nbr x = row[i];
      size_t j = i;
      for (; j > 0 && row[j - 1].u > x.u; --j) row[j] = row[j - 1];
      row[j] = x;
    }
    return true;
  };
  // visit_opp without branches on the data, for vertices of up to 16 triangles (all but fans): an
  // unpredictable branch per neighbour lookup and per sort step made the pass cost ~250 ns a
  // vertex, mostly mispredictions. The 2 x deg neighbour ids are ranked (stable) into order, runs
  // of equal ids become (id, count), and duplicate triangles are a mask over the pairs.
  constexpr int kFastDeg = 16;
  auto visit_fast = [&](int32_t v, std::vector<Nbr>& row) {
    const int64_t b0 = m.v2t.off[v];
    const int n = static_cast<int>(2 * (m.v2t.off[v + 1] - b0));
    const int32_t* w = &opp[2 * b0];
    int32_t sorted[2 * kFastDeg];
    for (int i = 0; i < n; ++i) {
      int rank = 0;
      for (int l = 0; l < n; ++l) rank += (w[l] < w[i]) | ((w[l] == w[i]) & (l < i));
      sorted[rank] = w[i];
    }
    bool bad = false;
    for (int j = 0; j < n; j += 2)  // a duplicate triangle at its smallest corner v
      for (int q = 0; q < j; q += 2) bad |= (v < w[j]) & (w[q] == w[j]) & (w[q + 1] == w[j + 1]);
    row.resize(static_cast<size_t>(n));
    int k = 0;
    row[0] = {sorted[0], 1};
    for (int i = 1; i < n; ++i) {
      const bool same = sorted[i] == sorted[i - 1];
      const int32_t c = row[k].count;
      k += !same;
      row[k].u = sorted[i];
      row[k].count = same ? c + 1 : 1;
    }
    row.resize(static_cast<size_t>(n ? k + 1 : 0));
    for (const Nbr& x : row) bad |= x.count > 2;
    return !bad;
  };
  // Fills `row` with v's neighbours, sorted; false on a topology error (thrown when `loud`).
  // Without `check` (the second pass, on a mesh already checked) duplicates are not looked for.
  auto visit = [&](int32_t v, std::vector<Nbr>& row, bool loud, bool check = true) {
    row.clear();
    const int32_t* tb = m.v2t.RowBegin(v);
    const int32_t* te = m.v2t.RowEnd(v);
    for (const int32_t* p = tb; p != te; ++p) {
      const int32_t* c = &m.tri[3 * static_cast<int64_t>(*p)];
      int32_t a = -1, b = -1;  // the other two corners
      for (int k = 0; k < 3; ++k)
        if (c[k] != v) (a < 0 ? a : b) = c[k];
      if (a > b) std::swap(a, b);
      if (check &&
          v < a) {  // v is the smallest corner: compare with earlier triangles at v of that kind
        for (const int32_t* q = tb; q != p; ++q) {
          const int32_t* d = &m.tri[3 * static_cast<int64_t>(*q)];
          const int32_t lo = std::min({d[0], d[1], d[2]});
          if (lo != v) continue;
          const int32_t hi = std::max({d[0], d[1], d[2]});
          const int32_t mid = d[0] + d[1] + d[2] - lo - hi;
          if (mid != a || hi != b) continue;
          if (!loud) return false;
          where.TriError(*p, "duplicate triangle: vertices " + raw_tag(v) + ", " + raw_tag(a) +
                                 ", " + raw_tag(b) + " already form a triangle at " +
                                 where.TriName(*q));
        }
      }
      for (int32_t u : {a, b}) {
        size_t k = 0;
        while (k < row.size() && row[k].u != u) ++k;
        if (k == row.size()) {
          row.push_back({u, 1});
        } else if (++row[k].count > 2) {
          if (!loud) return false;
          where.TriError(*p, "non-manifold edge: the edge " + raw_tag(v) + "-" + raw_tag(u) +
                                 " already has two triangles (first at " +
                                 where.TriName(first_with(v, u)) + ")");
        }
      }
    }
    for (size_t i = 1; i < row.size(); ++i) {  // insertion: a handful of neighbours
      const Nbr x = row[i];
      size_t j = i;
      for (; j > 0 && row[j - 1].u > x.u; --j) row[j] = row[j - 1];
      row[j] = x;
    }
    return true;
  };
  // A vertex's triangles lie anywhere in the triangle array: fetched ahead, their misses overlap
  // (a third of the time of each pass).
  constexpr int32_t kAhead = 16;
  auto prefetch_triangles = [&](int32_t v) {
    if (v >= nv) return;
    for (const int32_t* q = m.v2t.RowBegin(v); q != m.v2t.RowEnd(v); ++q)
      __builtin_prefetch(&m.tri[3 * static_cast<int64_t>(*q)]);
  };
  m.boundary.resize(nv);
  m.v2v.off.resize(static_cast<size_t>(nv) + 1);
  m.v2v.off[0] = 0;
  // One pass writes each row at a slot bounded by its triangle count: a vertex whose triangles
  // form one fan has at most one neighbour more than triangles, so row v starts at
  // v2t.off[v] + v. The rows are then moved down in order (each only ever moves left), which
  // costs a sequential pass where a second visit would repeat every scattered triangle read.
  // A vertex with several fans (a bowtie) may not fit: then rows are sized first, and filled.
  const int64_t bound = m.v2t.off[nv] + nv;
  m.v2v.idx.resize(static_cast<size_t>(bound));
  int32_t first_bad = nv;
  bool spill = false;
#pragma omp parallel reduction(min : first_bad) reduction(|| : spill)
  {
    std::vector<Nbr> row;
#pragma omp for schedule(static, 4096)
    for (int32_t v = 0; v < nv; ++v) {
      const bool fast = m.v2t.RowSize(v) <= kFastDeg && m.v2t.RowSize(v) > 0;
      if (!(fast ? visit_fast(v, row) : visit_opp(v, row))) {
        first_bad = std::min(first_bad, v);
        row.clear();
      }
      bool on_boundary = false;
      for (const Nbr& n : row) on_boundary |= n.count == 1;
      m.boundary[v] = on_boundary;
      m.v2v.off[v + 1] = static_cast<int64_t>(row.size());
      if (static_cast<int64_t>(row.size()) > m.v2t.RowSize(v) + 1) {
        spill = true;
        continue;
      }
      int32_t* out = m.v2v.idx.data() + m.v2t.off[v] + v;
      for (const Nbr& n : row) *out++ = n.u;
    }
  }
  opp = AlignedVector<int32_t>();
  // v2t's entries: the same counting sort, now that `opp` is gone.
  m.v2t.idx.resize(m.tri.size());
  {
    AlignedVector<int64_t>& cur = m.v2t.off;
    const int64_t nt_ = static_cast<int64_t>(m.tri.size() / 3);
    for (int64_t t = 0; t < nt_; ++t)
      for (int k = 0; k < 3; ++k) m.v2t.idx[cur[m.tri[3 * t + k]]++] = static_cast<int32_t>(t);
    for (int32_t v = nv; v > 0; --v) cur[v] = cur[v - 1];
    cur[0] = 0;
  }
  if (first_bad < nv) {
    std::vector<Nbr> row;
    visit(first_bad, row, true);  // throws
  }
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
      std::vector<Nbr> row;
#pragma omp for schedule(static, 4096)
      for (int32_t v = 0; v < nv; ++v) {
        prefetch_triangles(v + kAhead);
        visit(v, row, false, false);
        int32_t* out = m.v2v.idx.data() + m.v2v.off[v];
        for (const Nbr& n : row) *out++ = n.u;
      }
    }
  }
  int64_t n_interior = 0;
  for (uint8_t b : m.boundary) n_interior += !b;
  m.interior.resize(static_cast<size_t>(n_interior));
  for (int32_t v = 0, k = 0; v < nv; ++v)
    if (!m.boundary[v]) m.interior[k++] = v;
  if (report) report->kept = std::move(kept);
  return m;
}

}  // namespace meshreuse
