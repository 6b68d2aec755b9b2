// BuildRankPiece and PieceGrid; see rank_piece.h.
#include "core/ranks/rank_piece.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "core/quality.h"

namespace meshreuse {

namespace {

template <class T>
void Append(std::string* b, const T& v) {
  b->append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
std::vector<T> Unpack(const std::string& b) {
  std::vector<T> v(b.size() / sizeof(T));
  if (!v.empty()) std::memcpy(v.data(), b.data(), v.size() * sizeof(T));
  return v;
}

// The quality and boundary flag of an owned vertex next to a ghost, for the ranks that ghost it.
struct BorderVertex {
  int64_t gid;
  float quality;
  uint8_t boundary;
};

}  // namespace

RankPiece BuildRankPiece(const RankPart& p, Communicator& tx) {
  RankPiece piece;
  const int32_t total = p.total, owned = p.owned;
  const int64_t nt = static_cast<int64_t>(p.weight.size());
  // Local ids by global id, to place the other ranks' triangles.
  std::vector<std::pair<int64_t, int32_t>> by_gid(static_cast<size_t>(total));
  for (int32_t v = 0; v < total; ++v) by_gid[v] = {p.gid[v], v};
  std::sort(by_gid.begin(), by_gid.end());
  auto local = [&by_gid](int64_t g) {
    const auto it = std::lower_bound(by_gid.begin(), by_gid.end(), std::make_pair(g, INT32_MIN));
    return it != by_gid.end() && it->first == g ? it->second : -1;
  };

  std::string border;
  piece.tri.assign(p.tri.begin(), p.tri.end());
  for (int64_t t = 0; t < nt; ++t) {
    const int32_t* c = &p.tri[3 * t];
    if (c[0] >= owned || c[1] >= owned || c[2] >= owned)
      for (int j = 0; j < 3; ++j) Append(&border, p.gid[c[j]]);
  }
  piece.owned_cells = static_cast<int32_t>(nt);
  piece.cell_rank.assign(static_cast<size_t>(nt), p.rank);
  const std::vector<std::string> borders = tx.AllGather(border);
  for (int32_t r = 0; r < static_cast<int32_t>(borders.size()); ++r) {
    if (r == p.rank) continue;
    const std::vector<int64_t> g = Unpack<int64_t>(borders[r]);
    for (size_t k = 0; k + 2 < g.size(); k += 3) {
      int32_t c[3];
      bool mine = false;
      for (int j = 0; j < 3; ++j) {
        c[j] = local(g[k + j]);
        mine = mine || (c[j] >= 0 && c[j] < owned);
      }
      if (!mine) continue;
      // Every corner of a triangle with an owned corner is local: the ghost ring holds every
      // vertex next to an owned one.
      if (c[0] < 0 || c[1] < 0 || c[2] < 0)
        throw std::logic_error("rank piece: a ghost cell's corner is not local");
      piece.tri.insert(piece.tri.end(), c, c + 3);
      piece.cell_rank.push_back(r);
    }
  }
  const size_t cells = piece.tri.size() / 3;
  piece.cell_ghost.assign(cells, 0);
  std::fill(piece.cell_ghost.begin() + nt, piece.cell_ghost.end(), uint8_t{1});

  // Qualities: an owned vertex's ring is whole here (its owned triangles and ghost cells).
  piece.triangle_quality.resize(cells);
  std::vector<double> sum(static_cast<size_t>(total), 0.0);
  std::vector<int32_t> count(static_cast<size_t>(total), 0);
  std::vector<uint8_t> next_to_ghost(static_cast<size_t>(owned), 0);
  for (size_t t = 0; t < cells; ++t) {
    const int32_t* c = &piece.tri[3 * t];
    const double q = TriangleQuality(p.xy.data(), c);
    piece.triangle_quality[t] = static_cast<float>(q);
    const bool ghostly = c[0] >= owned || c[1] >= owned || c[2] >= owned;
    for (int j = 0; j < 3; ++j) {
      sum[c[j]] += q;
      ++count[c[j]];
      if (ghostly && c[j] < owned) next_to_ghost[c[j]] = 1;
    }
  }
  piece.vertex_quality.assign(static_cast<size_t>(total), 0.0f);
  piece.boundary.assign(static_cast<size_t>(total), 0);
  piece.point_ghost.assign(static_cast<size_t>(total), 0);
  std::string mine;
  for (int32_t v = 0; v < owned; ++v) {
    piece.vertex_quality[v] = count[v] ? static_cast<float>(sum[v] / count[v]) : 0.0f;
    piece.boundary[v] = v >= p.movable;
    if (next_to_ghost[v])
      Append(&mine, BorderVertex{p.gid[v], piece.vertex_quality[v], piece.boundary[v]});
  }
  // A ghost's quality and flag from its owner.
  std::vector<BorderVertex> known;
  for (const std::string& b : tx.AllGather(mine))
    for (const BorderVertex& x : Unpack<BorderVertex>(b)) known.push_back(x);
  std::sort(known.begin(), known.end(),
            [](const BorderVertex& a, const BorderVertex& b) { return a.gid < b.gid; });
  for (int32_t v = owned; v < total; ++v) {
    piece.point_ghost[v] = 1;
    const auto it = std::lower_bound(known.begin(), known.end(), p.gid[v],
                                     [](const BorderVertex& a, int64_t g) { return a.gid < g; });
    if (it == known.end() || it->gid != p.gid[v])
      throw std::logic_error("rank piece: no owner sent a ghost's quality");
    piece.vertex_quality[v] = it->quality;
    piece.boundary[v] = it->boundary;
  }
  return piece;
}

VtuGrid PieceGrid(const RankPart& p, const RankPiece& piece) {
  VtuGrid g;
  const int64_t n = p.total, cells = static_cast<int64_t>(piece.cell_ghost.size());
  g.points = n, g.xy = p.xy.data(), g.cells = cells, g.tri = piece.tri.data();
  g.point_data.push_back(VtuArrayOf("vertex_quality", piece.vertex_quality.data(), n));
  g.point_data.push_back(VtuArrayOf("boundary", piece.boundary.data(), n));
  g.point_data.push_back(VtuArrayOf("GlobalNodeIds", p.gid.data(), n));
  g.point_data.push_back(VtuArrayOf("vtkGhostType", piece.point_ghost.data(), n));
  g.cell_data.push_back(VtuArrayOf("triangle_quality", piece.triangle_quality.data(), cells));
  g.cell_data.push_back(VtuArrayOf("rank", piece.cell_rank.data(), cells));
  g.cell_data.push_back(VtuArrayOf("vtkGhostType", piece.cell_ghost.data(), cells));
  g.global_ids = "GlobalNodeIds";
  return g;
}

}  // namespace meshreuse
