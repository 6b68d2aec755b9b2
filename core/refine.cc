// Uniform refinement; see refine.h.
#include "core/refine.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/mix.h"
#include "core/progress.h"

namespace meshreuse {

namespace {

// The coarse mesh's edges and what every fine vertex's coordinates need, shared by the whole and
// the pieces.
class Lattice {
 public:
  Lattice(const Mesh& m, const RefineOptions& o) : m_(m), o_(o) {
    if (o.levels < 0 || o.levels > 15) throw UsageError("--levels must be 0..15");
    if (!(o.jitter >= 0 && o.jitter <= 0.5)) throw UsageError("--jitter must be 0..0.5");
    n_ = int64_t{1} << o.levels;
    const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
    // Edges (a, b), a < b, in increasing (a, b): the v2v rows are sorted, so edge index =
    // edges of lower vertices + rank of b among a's higher neighbours.
    first_.assign(static_cast<size_t>(nv) + 1, 0);
    for (int32_t a = 0; a < nv; ++a) {
      int64_t higher = 0;
      for (const int32_t* q = m.v2v.RowBegin(a); q != m.v2v.RowEnd(a); ++q) higher += *q > a;
      first_[a + 1] = first_[a] + higher;
    }
    edges_ = first_[nv];
    lo_.resize(edges_), hi_.resize(edges_);
    for (int32_t a = 0; a < nv; ++a) {
      int64_t e = first_[a];
      for (const int32_t* q = m.v2v.RowBegin(a); q != m.v2v.RowEnd(a); ++q)
        if (*q > a) lo_[e] = a, hi_[e] = *q, ++e;
    }
    interior_ = (n_ - 1) * (n_ - 2) / 2;
    // Sizes, checked against 32-bit ids.
    const int64_t limit = std::numeric_limits<int32_t>::max();
    auto fits = [&](double x) { return x <= static_cast<double>(limit); };
    const double v = nv + static_cast<double>(edges_) * static_cast<double>(n_ - 1) +
                     static_cast<double>(nt) * static_cast<double>(interior_);
    const double t = static_cast<double>(nt) * static_cast<double>(n_) * static_cast<double>(n_);
    if (!fits(v) || !fits(t) || !fits(3 * t))
      throw UsageError("refining " + std::to_string(nt) + " triangles " + std::to_string(o.levels) +
                       " times gives " + std::to_string(static_cast<long long>(t)) +
                       " triangles and " + std::to_string(static_cast<long long>(v)) +
                       " vertices: more than 32-bit ids hold (2^31 - 1)");
    vertices_ = static_cast<int64_t>(v);
    triangles_ = static_cast<int64_t>(t);
    edge_base_ = nv;
    tri_base_ = nv + edges_ * (n_ - 1);
    // Jitter: the local fine spacing h (smallest altitude / n) per triangle and per edge, and
    // whether an edge is on the boundary (one triangle).
    if (o.jitter > 0) {
      tri_h_.resize(nt);
      edge_h_.assign(edges_, std::numeric_limits<double>::infinity());
      edge_count_.assign(edges_, 0);
      for (int32_t k = 0; k < nt; ++k) {
        const int32_t* c = &m.tri[3 * int64_t{k}];
        double longest = 0;
        for (int i = 0; i < 3; ++i) {
          const double dx = X(c[(i + 1) % 3]) - X(c[i]), dy = Y(c[(i + 1) % 3]) - Y(c[i]);
          longest = std::max(longest, std::hypot(dx, dy));
        }
        const double area2 = std::abs((X(c[1]) - X(c[0])) * (Y(c[2]) - Y(c[0])) -
                                      (X(c[2]) - X(c[0])) * (Y(c[1]) - Y(c[0])));
        tri_h_[k] = area2 / longest / static_cast<double>(n_);
        for (int i = 0; i < 3; ++i) {
          const int64_t e = Edge(c[i], c[(i + 1) % 3]);
          edge_h_[e] = std::min(edge_h_[e], tri_h_[k]);
          ++edge_count_[e];
        }
      }
    }
  }

  int64_t vertices() const { return vertices_; }
  int64_t triangles() const { return triangles_; }
  int64_t edges() const { return edges_; }
  int64_t n() const { return n_; }
  int64_t interior() const { return interior_; }
  int64_t edge_base() const { return edge_base_; }
  int64_t tri_base() const { return tri_base_; }

  int64_t Edge(int32_t a, int32_t b) const {
    if (a > b) std::swap(a, b);
    const int32_t* row = m_.v2v.RowBegin(a);
    const int32_t* end = m_.v2v.RowEnd(a);
    const int32_t* higher = std::upper_bound(row, end, a);
    return first_[a] + (std::lower_bound(higher, end, b) - higher);
  }

  // The global id of lattice point (j, k) of coarse triangle t (weights n-j-k, j, k on its
  // corners in file order).
  int32_t Id(int32_t t, int64_t j, int64_t k) const {
    const int32_t* c = &m_.tri[3 * int64_t{t}];
    if (j == 0 && k == 0) return c[0];
    if (j == n_) return c[1];
    if (k == n_) return c[2];
    if (k == 0) return OnEdge(c[0], c[1], j);
    if (j == 0) return OnEdge(c[0], c[2], k);
    if (j + k == n_) return OnEdge(c[1], c[2], k);
    // Row k (1..n-2) holds n-1-k interior points; rows 1..k-1 come first.
    const int64_t before = (k - 1) * (n_ - 1) - (k - 1) * k / 2;
    return static_cast<int32_t>(tri_base_ + t * interior_ + before + (j - 1));
  }

  void Coord(int32_t id, double* x, double* y) const {
    if (id < edge_base_) {
      *x = X(id), *y = Y(id);
      return;
    }
    if (id < tri_base_) {
      EdgeCoord((id - edge_base_) / (n_ - 1), (id - edge_base_) % (n_ - 1) + 1, x, y);
      return;
    }
    const int64_t local = (id - tri_base_) % interior_;
    const int32_t t = static_cast<int32_t>((id - tri_base_) / interior_);
    int64_t k = 1, left = local;
    while (left >= n_ - 1 - k) left -= n_ - 1 - k, ++k;
    InteriorCoord(t, left + 1, k, x, y);
  }

  // The coordinates of lattice point (j, k) of coarse triangle t: Coord(Id(t, j, k)) in O(1).
  void Point(int32_t t, int64_t j, int64_t k, double* x, double* y) const {
    const int32_t id = Id(t, j, k);
    if (id < edge_base_)
      *x = X(id), *y = Y(id);
    else if (id < tri_base_)
      EdgeCoord((id - edge_base_) / (n_ - 1), (id - edge_base_) % (n_ - 1) + 1, x, y);
    else
      InteriorCoord(t, j, k, x, y);
  }

  // Point s (1..n-1, from the lower-id end) of edge e.
  void EdgeCoord(int64_t e, int64_t s, double* x, double* y) const {
    const double f = static_cast<double>(s) / static_cast<double>(n_);
    *x = X(lo_[e]) + (X(hi_[e]) - X(lo_[e])) * f;
    *y = Y(lo_[e]) + (Y(hi_[e]) - Y(lo_[e])) * f;
    if (o_.jitter > 0 && edge_count_[e] > 1)
      Jitter(static_cast<int32_t>(edge_base_ + e * (n_ - 1) + (s - 1)), edge_h_[e], x, y);
  }

  // Interior point (j, k) of coarse triangle t.
  void InteriorCoord(int32_t t, int64_t j, int64_t k, double* x, double* y) const {
    const int32_t* c = &m_.tri[3 * int64_t{t}];
    const double fj = static_cast<double>(j) / static_cast<double>(n_);
    const double fk = static_cast<double>(k) / static_cast<double>(n_);
    *x = X(c[0]) + (X(c[1]) - X(c[0])) * fj + (X(c[2]) - X(c[0])) * fk;
    *y = Y(c[0]) + (Y(c[1]) - Y(c[0])) * fj + (Y(c[2]) - Y(c[0])) * fk;
    if (o_.jitter > 0) Jitter(Id(t, j, k), tri_h_[t], x, y);
  }

  // The coarse vertex whose part fine vertex `id` inherits: itself, its edge's lower-id end, its
  // triangle's smallest corner.
  int32_t Responsible(int32_t id) const {
    if (id < edge_base_) return id;
    if (id < tri_base_) return lo_[(id - edge_base_) / (n_ - 1)];
    const int32_t* c = &m_.tri[3 * ((id - tri_base_) / interior_)];
    return std::min({c[0], c[1], c[2]});
  }

  // Fine triangles of coarse triangle t, by lattice row: up (j,k) (j+1,k) (j,k+1), then down
  // (j+1,k) (j+1,k+1) (j,k+1); both keep the coarse orientation.
  template <typename F>
  void Triangles(int32_t t, F&& emit) const {
    for (int64_t k = 0; k < n_; ++k)
      for (int64_t j = 0; j + k < n_; ++j) {
        emit(Id(t, j, k), Id(t, j + 1, k), Id(t, j, k + 1));
        if (j + k + 2 <= n_) emit(Id(t, j + 1, k), Id(t, j + 1, k + 1), Id(t, j, k + 1));
      }
  }

 private:
  void Jitter(int32_t id, double h, double* x, double* y) const {
    if (!(h > 0)) return;
    const uint64_t r = Mix64(static_cast<uint64_t>(id) ^ Mix64(o_.seed));
    const double u = static_cast<double>(r >> 32) * 0x1.0p-32 - 0.5;
    const double v = static_cast<double>(r & 0xffffffffu) * 0x1.0p-32 - 0.5;
    *x += o_.jitter * h * u;
    *y += o_.jitter * h * v;
  }
  double X(int32_t v) const { return m_.xy[2 * int64_t{v}]; }
  double Y(int32_t v) const { return m_.xy[2 * int64_t{v} + 1]; }
  int32_t OnEdge(int32_t a, int32_t b, int64_t from_a) const {
    const int64_t e = Edge(a, b);
    const int64_t s = a < b ? from_a : n_ - from_a;
    return static_cast<int32_t>(edge_base_ + e * (n_ - 1) + (s - 1));
  }

  const Mesh& m_;
  RefineOptions o_;
  int64_t n_ = 1, edges_ = 0, interior_ = 0, vertices_ = 0, triangles_ = 0;
  int64_t edge_base_ = 0, tri_base_ = 0;
  std::vector<int64_t> first_;
  std::vector<int32_t> lo_, hi_;
  std::vector<double> tri_h_, edge_h_;
  std::vector<uint8_t> edge_count_;
};

}  // namespace

RefinedSize RefinedSizeOf(const Mesh& coarse, const RefineOptions& o) {
  const Lattice l(coarse, o);
  return {l.vertices(), l.triangles(), l.edges()};
}

RefinedPiece RefinePiece(const Mesh& coarse, const RefineOptions& o, int32_t tri_begin,
                         int32_t tri_end) {
  const Lattice l(coarse, o);
  tri_begin = std::clamp(tri_begin, 0, coarse.NumTriangles());
  tri_end = std::clamp(tri_end, tri_begin, coarse.NumTriangles());
  RefinedPiece p;
  for (int32_t t = tri_begin; t < tri_end; ++t)
    l.Triangles(t, [&](int32_t a, int32_t b, int32_t c) {
      p.tri.push_back(a), p.tri.push_back(b), p.tri.push_back(c);
    });
  p.ids = p.tri;
  std::sort(p.ids.begin(), p.ids.end());
  p.ids.erase(std::unique(p.ids.begin(), p.ids.end()), p.ids.end());
  p.xy.resize(2 * p.ids.size());
  for (size_t i = 0; i < p.ids.size(); ++i) l.Coord(p.ids[i], &p.xy[2 * i], &p.xy[2 * i + 1]);
  return p;
}

RawMesh RefineMesh(const Mesh& coarse, const RefineOptions& o) {
  const Lattice l(coarse, o);
  RawMesh r;
  r.vertex_file = r.triangle_file = "<refined>";
  r.xy.resize(2 * static_cast<size_t>(l.vertices()));
  // Progress in fine vertices, then fine triangles (each counted as one unit of the total).
  const uint64_t total = static_cast<uint64_t>(l.vertices()) + l.triangles();
  for (int64_t v = 0; v < l.vertices(); ++v) {
    l.Coord(static_cast<int32_t>(v), &r.xy[2 * v], &r.xy[2 * v + 1]);
    if ((v & 0xffff) == 0) ReportProgress(static_cast<uint64_t>(v), total);
  }
  r.tri.resize(3 * static_cast<size_t>(l.triangles()));
  size_t at = 0;
  for (int32_t t = 0; t < coarse.NumTriangles(); ++t) {
    l.Triangles(t, [&](int32_t a, int32_t b, int32_t c) {
      r.tri[at++] = a, r.tri[at++] = b, r.tri[at++] = c;
    });
    if ((t & 0xff) == 0) ReportProgress(static_cast<uint64_t>(l.vertices()) + at / 3, total);
  }
  return r;
}

PiecesLayout::PiecesLayout(const Mesh& m, const RefineOptions& o) {
  const Lattice l(m, o);
  nv_ = m.NumVertices(), nt_ = m.NumTriangles();
  n_ = l.n(), interior_ = l.interior(), edge_base_ = l.edge_base(), tri_base_ = l.tri_base();
  vertex_owner_.assign(static_cast<size_t>(nv_), -1);
  vertex_slot_.assign(static_cast<size_t>(nv_), 0);
  edge_owner_.assign(static_cast<size_t>(l.edges()), -1);
  edge_slot_.assign(static_cast<size_t>(l.edges()), 0);
  edge_count_.assign(static_cast<size_t>(l.edges()), 0);
  corners_.assign(static_cast<size_t>(nt_), 0);
  edges_.assign(static_cast<size_t>(nt_), 0);
  for (int32_t t = 0; t < nt_; ++t) {  // increasing t: the first triangle met is the lowest id
    const int32_t* c = &m.tri[3 * int64_t{t}];
    for (int i = 0; i < 3; ++i)
      if (vertex_owner_[c[i]] < 0) vertex_owner_[c[i]] = t, vertex_slot_[c[i]] = corners_[t]++;
    for (const int64_t e : {l.Edge(c[0], c[1]), l.Edge(c[0], c[2]), l.Edge(c[1], c[2])}) {
      ++edge_count_[e];
      if (edge_owner_[e] < 0) edge_owner_[e] = t, edge_slot_[e] = edges_[t]++;
    }
  }
  // Block sizes, and each block's v2t entries: a fine vertex at a coarse vertex lies in one fine
  // triangle per coarse triangle there, a point of a coarse edge in three per triangle of the
  // edge, an interior point in six.
  block_.assign(static_cast<size_t>(nt_) + 1, 0);
  row_.assign(static_cast<size_t>(nt_) + 1, 0);
  for (int32_t t = 0; t < nt_; ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    int64_t entries = 6 * interior_;
    for (int i = 0; i < 3; ++i)
      if (vertex_owner_[c[i]] == t) entries += m.v2t.RowEnd(c[i]) - m.v2t.RowBegin(c[i]);
    for (const int64_t e : {l.Edge(c[0], c[1]), l.Edge(c[0], c[2]), l.Edge(c[1], c[2])})
      if (edge_owner_[e] == t) entries += 3 * (n_ - 1) * edge_count_[e];
    block_[t + 1] = block_[t] + corners_[t] + edges_[t] * (n_ - 1) + interior_;
    row_[t + 1] = row_[t] + entries;
  }
  if (block_[nt_] != l.vertices() || row_[nt_] != 3 * l.triangles())
    throw std::logic_error("PiecesLayout: blocks do not add up to the fine mesh");
}

int64_t PiecesLayout::triangles() const { return int64_t{nt_} * n_ * n_; }

int32_t PiecesLayout::NewId(int32_t g) const {
  if (g < edge_base_) return static_cast<int32_t>(block_[vertex_owner_[g]] + vertex_slot_[g]);
  if (g < tri_base_) {
    const int64_t e = (g - edge_base_) / (n_ - 1), s = (g - edge_base_) % (n_ - 1) + 1;
    const int32_t t = edge_owner_[e];
    return static_cast<int32_t>(block_[t] + corners_[t] + edge_slot_[e] * (n_ - 1) + (s - 1));
  }
  const int32_t t = static_cast<int32_t>((g - tri_base_) / interior_);
  return static_cast<int32_t>(block_[t] + corners_[t] + edges_[t] * (n_ - 1) +
                              (g - tri_base_) % interior_);
}

int32_t PiecesLayout::Split(int32_t r, int32_t parts) const {
  if (r >= parts) return nt_;  // the last rank also takes trailing empty blocks' triangles
  const int64_t target = vertices() * r / parts;
  return static_cast<int32_t>(std::lower_bound(block_.begin(), block_.end(), target) -
                              block_.begin());
}

namespace {

// Coarse triangle t's fine triangles in Lattice::Triangles' order, with pieces ids and (when
// `coords`) their corners' coordinates: emit(a, b, c, xa, xb, xc), x* pointing to (x, y). Two
// lattice rows at a time, so a coarse triangle of any size needs O(n) memory.
template <class F>
void FineTriangles(const Lattice& l, const PiecesLayout& layout, int32_t t, bool coords, F&& emit) {
  const int64_t n = l.n();
  std::vector<int32_t> id0(n + 1), id1(n + 1);
  std::vector<double> xy0(coords ? 2 * (n + 1) : 0), xy1(xy0.size());
  auto row = [&](int64_t k, std::vector<int32_t>& id, std::vector<double>& xy) {
    for (int64_t j = 0; j + k <= n; ++j) {
      id[j] = layout.NewId(l.Id(t, j, k));
      if (coords) l.Point(t, j, k, &xy[2 * j], &xy[2 * j + 1]);
    }
  };
  static const double kNone[2] = {0, 0};
  auto at = [&](const std::vector<double>& xy, int64_t j) { return coords ? &xy[2 * j] : kNone; };
  row(0, id0, xy0);
  for (int64_t k = 0; k < n; ++k) {
    row(k + 1, id1, xy1);
    for (int64_t j = 0; j + k < n; ++j) {
      emit(id0[j], id0[j + 1], id1[j], at(xy0, j), at(xy0, j + 1), at(xy1, j));
      if (j + k + 2 <= n)
        emit(id0[j + 1], id1[j + 1], id1[j], at(xy0, j + 1), at(xy1, j + 1), at(xy1, j));
    }
    id0.swap(id1), xy0.swap(xy1);
  }
}

}  // namespace

RefinedRange RefineRange(const Mesh& coarse, const RefineOptions& o, const PiecesLayout& layout,
                         int32_t tri_begin, int32_t tri_end) {
  const Lattice l(coarse, o);
  const PiecesLayout& L = layout;
  tri_begin = std::clamp(tri_begin, 0, coarse.NumTriangles());
  tri_end = std::clamp(tri_end, tri_begin, coarse.NumTriangles());
  const int64_t n = l.n();
  RefinedRange r;
  r.first_vertex = L.block_[tri_begin];
  r.first_triangle = int64_t{tri_begin} * n * n;
  const int64_t count = L.block_[tri_end] - r.first_vertex;
  // The blocks' vertices, in block order (PiecesLayout).
  r.xy.reserve(2 * static_cast<size_t>(count));
  r.boundary.reserve(static_cast<size_t>(count));
  double x, y;
  auto put = [&](uint8_t b) { r.xy.push_back(x), r.xy.push_back(y), r.boundary.push_back(b); };
  // Progress in blocks: the coordinates, then the triangles (the listener's halves).
  const uint64_t blocks = 2 * static_cast<uint64_t>(tri_end - tri_begin);
  for (int32_t t = tri_begin; t < tri_end; ++t) {
    if (((t - tri_begin) & 0xff) == 0) ReportProgress(static_cast<uint64_t>(t - tri_begin), blocks);
    const int32_t* c = &coarse.tri[3 * int64_t{t}];
    for (int i = 0; i < 3; ++i)
      if (L.vertex_owner_[c[i]] == t) l.Coord(c[i], &x, &y), put(coarse.boundary[c[i]]);
    for (const int64_t e : {l.Edge(c[0], c[1]), l.Edge(c[0], c[2]), l.Edge(c[1], c[2])})
      if (L.edge_owner_[e] == t)
        for (int64_t s = 1; s < n; ++s) l.EdgeCoord(e, s, &x, &y), put(L.edge_count_[e] == 1);
    for (int64_t k = 1; k + 2 <= n; ++k)
      for (int64_t j = 1; j + k < n; ++j) l.InteriorCoord(t, j, k, &x, &y), put(0);
  }
  if (static_cast<int64_t>(r.boundary.size()) != count)
    throw std::logic_error("RefineRange: a block of the wrong size");
  // The blocks' fine triangles, and their smallest doubled area signed by the coarse orientation.
  r.tri.reserve(3 * static_cast<size_t>((tri_end - tri_begin) * n * n));
  r.min_area2 = std::numeric_limits<double>::infinity();
  auto area2 = [](const double* p, const double* q, const double* s) {
    return (q[0] - p[0]) * (s[1] - p[1]) - (s[0] - p[0]) * (q[1] - p[1]);
  };
  for (int32_t t = tri_begin; t < tri_end; ++t) {
    if (((t - tri_begin) & 0xff) == 0)
      ReportProgress(blocks / 2 + static_cast<uint64_t>(t - tri_begin), blocks);
    const int32_t* corner = &coarse.tri[3 * int64_t{t}];
    const double sign =
        area2(&coarse.xy[2 * int64_t{corner[0]}], &coarse.xy[2 * int64_t{corner[1]}],
              &coarse.xy[2 * int64_t{corner[2]}]) < 0
            ? -1.0
            : 1.0;
    FineTriangles(
        l, L, t, true,
        [&](int32_t a, int32_t b, int32_t c, const double* p, const double* q, const double* s) {
          r.tri.push_back(a), r.tri.push_back(b), r.tri.push_back(c);
          r.min_area2 = std::min(r.min_area2, sign * area2(p, q, s));
        });
  }
  // Rows: every fine triangle at a vertex of these blocks lies in a coarse triangle at one of
  // their coarse corners; those coarse triangles in increasing id give each row in increasing id.
  std::vector<int32_t> around;
  for (int32_t t = tri_begin; t < tri_end; ++t)
    for (int i = 0; i < 3; ++i) {
      const int32_t v = coarse.tri[3 * int64_t{t} + i];
      around.insert(around.end(), coarse.v2t.RowBegin(v), coarse.v2t.RowEnd(v));
    }
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  std::vector<std::pair<int32_t, int32_t>> at;  // (vertex - first, fine triangle)
  at.reserve(static_cast<size_t>(L.row_[tri_end] - L.row_[tri_begin]));
  for (const int32_t u : around) {
    int64_t fine = int64_t{u} * n * n;
    FineTriangles(
        l, L, u, false,
        [&](int32_t a, int32_t b, int32_t c, const double*, const double*, const double*) {
          for (const int32_t v : {a, b, c})
            if (v >= r.first_vertex && v - r.first_vertex < count)
              at.emplace_back(static_cast<int32_t>(v - r.first_vertex), static_cast<int32_t>(fine));
          ++fine;
        });
  }
  r.v2t_off.assign(static_cast<size_t>(count) + 1, 0);
  for (const auto& p : at) ++r.v2t_off[p.first + 1];
  r.v2t_off[0] = L.row_[tri_begin];
  for (int64_t v = 0; v < count; ++v) r.v2t_off[v + 1] += r.v2t_off[v];
  if (r.v2t_off.back() != L.row_[tri_end])
    throw std::logic_error("RefineRange: rows do not add up to the blocks' entries");
  r.v2t.resize(at.size());
  std::vector<int64_t> next(r.v2t_off.begin(), r.v2t_off.end() - 1);
  for (const auto& p : at) r.v2t[next[p.first]++ - r.v2t_off[0]] = p.second;  // stable
  return r;
}

RawMesh RefineMeshPieces(const Mesh& coarse, const RefineOptions& o) {
  const PiecesLayout layout(coarse, o);
  const RawMesh whole = RefineMesh(coarse, o);
  RawMesh r;
  r.vertex_file = r.triangle_file = whole.vertex_file;
  r.xy.resize(whole.xy.size());
  const int64_t nv = static_cast<int64_t>(whole.xy.size() / 2);
  for (int64_t g = 0; g < nv; ++g) {
    const int32_t v = layout.NewId(static_cast<int32_t>(g));
    r.xy[2 * int64_t{v}] = whole.xy[2 * g], r.xy[2 * int64_t{v} + 1] = whole.xy[2 * g + 1];
  }
  r.tri.resize(whole.tri.size());
  for (size_t i = 0; i < whole.tri.size(); ++i) r.tri[i] = layout.NewId(whole.tri[i]);
  return r;
}

std::vector<int32_t> InheritParts(const Mesh& coarse, const RefineOptions& o,
                                  const std::vector<int32_t>& coarse_part) {
  if (static_cast<int64_t>(coarse_part.size()) != coarse.NumVertices())
    throw std::invalid_argument("InheritParts: one part per coarse vertex");
  const Lattice l(coarse, o);
  std::vector<int32_t> part(static_cast<size_t>(l.vertices()));
  for (int64_t v = 0; v < l.vertices(); ++v)
    part[v] = coarse_part[l.Responsible(static_cast<int32_t>(v))];
  return part;
}

uint64_t MeshContentHash(const AlignedVector<double>& xy, const AlignedVector<int32_t>& tri) {
  uint64_t h = Mix64(xy.size() * 3 + tri.size());
  for (double d : xy) {
    uint64_t b;
    static_assert(sizeof b == sizeof d, "64-bit doubles");
    std::memcpy(&b, &d, 8);
    h = Mix64(h ^ b) + 0x9E3779B97F4A7C15ull;
  }
  for (int32_t i : tri) h = Mix64(h ^ static_cast<uint32_t>(i)) + 0x9E3779B97F4A7C15ull;
  return h;
}

}  // namespace meshreuse
