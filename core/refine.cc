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
    double h = 0;
    if (id < tri_base_) {
      const int64_t e = (id - edge_base_) / (n_ - 1), s = (id - edge_base_) % (n_ - 1) + 1;
      const double f = static_cast<double>(s) / static_cast<double>(n_);
      *x = X(lo_[e]) + (X(hi_[e]) - X(lo_[e])) * f;
      *y = Y(lo_[e]) + (Y(hi_[e]) - Y(lo_[e])) * f;
      if (o_.jitter > 0 && edge_count_[e] > 1) h = edge_h_[e];
    } else {
      const int64_t local = (id - tri_base_) % interior_;
      const int32_t t = static_cast<int32_t>((id - tri_base_) / interior_);
      int64_t k = 1, left = local;
      while (left >= n_ - 1 - k) left -= n_ - 1 - k, ++k;
      const int64_t j = left + 1;
      const int32_t* c = &m_.tri[3 * int64_t{t}];
      const double fj = static_cast<double>(j) / static_cast<double>(n_);
      const double fk = static_cast<double>(k) / static_cast<double>(n_);
      *x = X(c[0]) + (X(c[1]) - X(c[0])) * fj + (X(c[2]) - X(c[0])) * fk;
      *y = Y(c[0]) + (Y(c[1]) - Y(c[0])) * fj + (Y(c[2]) - Y(c[0])) * fk;
      if (o_.jitter > 0) h = tri_h_[t];
    }
    if (h > 0) {
      const uint64_t r = Mix64(static_cast<uint64_t>(id) ^ Mix64(o_.seed));
      const double u = static_cast<double>(r >> 32) * 0x1.0p-32 - 0.5;
      const double v = static_cast<double>(r & 0xffffffffu) * 0x1.0p-32 - 0.5;
      *x += o_.jitter * h * u;
      *y += o_.jitter * h * v;
    }
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
  for (int64_t v = 0; v < l.vertices(); ++v)
    l.Coord(static_cast<int32_t>(v), &r.xy[2 * v], &r.xy[2 * v + 1]);
  r.tri.resize(3 * static_cast<size_t>(l.triangles()));
  size_t at = 0;
  for (int32_t t = 0; t < coarse.NumTriangles(); ++t)
    l.Triangles(t, [&](int32_t a, int32_t b, int32_t c) {
      r.tri[at++] = a, r.tri[at++] = b, r.tri[at++] = c;
    });
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
