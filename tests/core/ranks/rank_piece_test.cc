// The pieces of a partitioned grid (core/ranks/rank_piece.h), built on P threads, against the
// whole mesh: every vertex owned by one piece; the owned cells, each once, are the mesh's
// triangles; a piece's ghost cells are exactly the triangles it touches and does not own, marked
// with their owner's rank; every point's coordinates, boundary flag and vertex quality are the
// whole mesh's (the quality to Float32's rounding: the sums may run in another order); triangle
// qualities are the mesh's, rounded once. Hilbert and METIS partitions, P = 1..5, one empty part.
#include "core/ranks/rank_piece.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "core/quality.h"
#include "core/ranks/partition.h"
#include "core/ranks/thread_communicator.h"
#include "core/synthetic.h"

namespace meshreuse {
namespace {

using Tri = std::array<int64_t, 3>;

void CheckPieces(const Mesh& m, const std::vector<int32_t>& part, int32_t P) {
  const PartitionStats ps = MeasurePartition(m, part, P);
  std::vector<RankPart> parts;
  for (int32_t r = 0; r < P; ++r) parts.push_back(BuildRankPart(m, part, P, ps.colour, r, "bfs"));
  std::vector<RankPiece> pieces(P);
  ThreadCommunicator::Run(
      P, [&](Communicator& tx) { pieces[tx.rank()] = BuildRankPiece(parts[tx.rank()], tx); });
  const std::vector<double> vq = VertexQualities(m);
  const std::vector<double> tq = TriangleQualities(m);
  std::map<Tri, int32_t> mesh_tri;  // corners in the mesh's order -> triangle id
  for (int32_t t = 0; t < m.NumTriangles(); ++t)
    mesh_tri[{m.tri[3 * t], m.tri[3 * t + 1], m.tri[3 * t + 2]}] = t;
  std::vector<int32_t> vertex_owner(m.NumVertices(), -1), cell_owner(m.NumTriangles(), -1);
  std::vector<std::set<int32_t>> ghosts(P);
  for (int32_t r = 0; r < P; ++r) {
    const RankPart& p = parts[r];
    const RankPiece& piece = pieces[r];
    ASSERT_EQ(piece.point_ghost.size(), static_cast<size_t>(p.total));
    for (int32_t v = 0; v < p.total; ++v) {
      const int64_t g = p.gid[v];
      EXPECT_EQ(piece.point_ghost[v], v >= p.owned ? 1 : 0);
      if (v < p.owned) {
        EXPECT_EQ(vertex_owner[g], -1) << "vertex " << g << " owned twice";
        vertex_owner[g] = r;
      }
      EXPECT_EQ(p.xy[2 * v], m.xy[2 * g]);
      EXPECT_EQ(p.xy[2 * v + 1], m.xy[2 * g + 1]);
      EXPECT_EQ(piece.boundary[v], m.boundary[g]) << "rank " << r << " vertex " << g;
      EXPECT_NEAR(piece.vertex_quality[v], vq[g], 1e-6) << "rank " << r << " vertex " << g;
    }
    const size_t cells = piece.cell_ghost.size();
    ASSERT_EQ(piece.tri.size(), 3 * cells);
    for (size_t c = 0; c < cells; ++c) {
      const Tri t = {p.gid[piece.tri[3 * c]], p.gid[piece.tri[3 * c + 1]],
                     p.gid[piece.tri[3 * c + 2]]};
      const auto it = mesh_tri.find(t);
      ASSERT_NE(it, mesh_tri.end()) << "rank " << r << ": a cell that is no triangle of the mesh";
      EXPECT_EQ(piece.triangle_quality[c], static_cast<float>(tq[it->second]));
      EXPECT_EQ(piece.cell_ghost[c], c >= static_cast<size_t>(piece.owned_cells) ? 1 : 0);
      if (piece.cell_ghost[c] == 0) {
        EXPECT_EQ(cell_owner[it->second], -1) << "a triangle owned twice";
        cell_owner[it->second] = r;
        EXPECT_EQ(piece.cell_rank[c], r);
      } else {
        EXPECT_TRUE(ghosts[r].insert(it->second).second) << "a ghost cell twice";
        EXPECT_NE(piece.cell_rank[c], r);
      }
    }
  }
  for (int32_t v = 0; v < m.NumVertices(); ++v) ASSERT_GE(vertex_owner[v], 0) << v;
  for (int32_t t = 0; t < m.NumTriangles(); ++t) ASSERT_GE(cell_owner[t], 0) << t;
  for (int32_t r = 0; r < P; ++r) {
    std::set<int32_t> expected;
    for (int32_t t = 0; t < m.NumTriangles(); ++t)
      if (cell_owner[t] != r)
        for (int j = 0; j < 3; ++j)
          if (vertex_owner[m.tri[3 * t + j]] == r) expected.insert(t);
    EXPECT_EQ(ghosts[r], expected) << "rank " << r << " of " << P;
  }
  // The ghost cells' ranks are their owners'.
  for (int32_t r = 0; r < P; ++r)
    for (size_t c = pieces[r].owned_cells; c < pieces[r].cell_ghost.size(); ++c) {
      const RankPart& p = parts[r];
      const Tri t = {p.gid[pieces[r].tri[3 * c]], p.gid[pieces[r].tri[3 * c + 1]],
                     p.gid[pieces[r].tri[3 * c + 2]]};
      EXPECT_EQ(pieces[r].cell_rank[c], cell_owner[mesh_tri[t]]);
    }
}

TEST(RankPiece, PiecesAreTheWholeMeshWithOneLayerOfGhostCells) {
  SyntheticOptions o;
  o.nx = 30, o.ny = 24, o.holes = 2, o.seed = 3;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  for (int32_t P : {1, 2, 3, 5}) {
    SCOPED_TRACE("hilbert P=" + std::to_string(P));
    CheckPieces(m, HilbertRangeParts(m, P), P);
  }
  for (int32_t P : {2, 4}) {
    SCOPED_TRACE("metis P=" + std::to_string(P));
    CheckPieces(m, MetisParts(m, P, 1), P);
  }
}

TEST(RankPiece, AnEmptyPartHasAnEmptyPiece) {
  SyntheticOptions o;
  o.nx = 12, o.ny = 10, o.seed = 2;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  std::vector<int32_t> part(m.NumVertices());
  for (int32_t v = 0; v < m.NumVertices(); ++v) part[v] = v < m.NumVertices() / 2 ? 0 : 2;
  CheckPieces(m, part, 3);  // part 1 is empty
}

}  // namespace
}  // namespace meshreuse
