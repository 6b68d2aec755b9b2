// One rank's piece of a partitioned grid for ParaView (a .pvtu's .vtu piece, core/vtu_io.h): the
// rank's local vertices as its RankPart stores them (owned, then ghosts) at their current
// coordinates, its owned triangles (each triangle is owned by exactly one rank, rank_part.h) and
// one layer of ghost cells (the other ranks' triangles with a corner owned here), marked the VTK
// way: vtkGhostType 1 on a point or cell that another piece owns. Fields: GlobalNodeIds (VTK's
// global ids: the vertex ids of the whole mesh), vertex quality (an owned vertex's from its whole
// ring, owned triangles and ghost cells; a ghost's from its owner), boundary flag (a ghost's from
// its owner), triangle quality and the owning rank of each cell. The union of the pieces' owned
// points and cells is the whole mesh, each once.
// Two collective exchanges build it (AllGather, every rank at once): each rank's border triangles
// (owned, with a ghost corner) as global-id triples, then the quality and boundary flag of each
// owned vertex next to a ghost. Both are the size of the cut, not of the part.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ranks/communicator.h"
#include "core/ranks/rank_part.h"
#include "core/vtu_io.h"

namespace meshreuse {

struct RankPiece {
  int32_t owned_cells = 0;
  std::vector<int32_t> tri;  // owned triangles, then ghost cells; local corners
  std::vector<uint8_t> point_ghost, cell_ghost, boundary;
  std::vector<float> vertex_quality, triangle_quality;
  std::vector<int32_t> cell_rank;
};

// Every rank of `tx` calls it at once, with its part after the last sweep (its ghosts current).
RankPiece BuildRankPiece(const RankPart& p, Communicator& tx);

// The grid to write: arrays pointing into `p` and `piece`, which must outlive it.
VtuGrid PieceGrid(const RankPart& p, const RankPiece& piece);

}  // namespace meshreuse
