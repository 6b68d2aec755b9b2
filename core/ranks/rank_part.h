// One rank's part of a vertex-partitioned mesh, laid out for the distributed smoother
// (core/ranks/halo_smoother.h; ../shared/scale-out.md 3b). The rank owns the vertices of its part
// and keeps one ring of ghosts: every vertex of another part next to one of its own, so every
// triangle with an owned corner is whole. Local ids come in four groups:
//   [0, noncut)                 owned interior vertices whose neighbours are all owned;
//   [noncut, movable)           owned interior vertices with a neighbour elsewhere (cut);
//   [movable, owned)            owned boundary vertices (fixed);
//   [owned, owned + ghosts)     ghosts;
// each group in the rank's ordering (any registered ordering, computed on the part with its ghost
// ring and triangles as a mesh of its own; `ori`: increasing global id). Storage order is visit
// order, as in the paper. Rows of v2v list the neighbours of the movable vertices **by increasing
// global id**, so each sum of neighbour coordinates is added in the serial mesh's order: what
// bit-equality with the serial smoother needs. Non-cut vertices are never anyone's ghost (their
// neighbours are all here); a ghost is a cut or boundary vertex of its owner.
// Triangles: those whose smallest-global-id corner is owned here (each triangle on exactly one
// rank), with their weight in the global quality computed from the whole mesh (quality.h).
// Links: per neighbouring rank, the movable owned vertices it ghosts (sent) and the movable ghosts
// it owns (received), both by increasing global id, so the two ends agree without a handshake.
// Everything here is computed identically on every rank from the whole mesh and the partition.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/aligned.h"
#include "core/mesh.h"
#include "core/orderings/registry.h"
#include "core/ranks/rank_neighbourhood.h"

namespace meshreuse {

// Where a rank stores, and so visits, its cut vertices among its movable ones: after the non-cut
// ones (`last`, the default: the non-cut moves overlap the wait for lower colours' ghosts), before
// them (`first`: the cut values go out first and the non-cut moves overlap their flight), or
// wherever the ordering puts them (`interleaved`: one group, so a rank waits for every lower
// colour before its sweep). Each gives an exact serial order π of its own (VisitOrderOf).
enum class CutPlacement { kLast, kFirst, kInterleaved };
const char* CutPlacementName(CutPlacement c);
CutPlacement ParseCutPlacement(const std::string& s);  // UsageError naming --cut-placement

struct RankLink {
  int32_t rank = 0, colour = 0;
  std::vector<int32_t> send;  // local ids of owned movable vertices `rank` ghosts
  std::vector<int32_t> recv;  // local ids of ghosts that `rank` owns and moves
};

struct RankPart {
  int32_t rank = 0, parts = 1;
  int32_t colour = 0, colours = 1;  // of the part graph's greedy colouring (partition.h)
  // Group ends, see above; with CutPlacement::kFirst the movable vertices are the cut ones,
  // [0, cut()), then the non-cut ones, [cut(), movable); with kInterleaved one group [0, movable)
  // in the ordering's order. `noncut` counts the non-cut vertices in every case.
  int32_t noncut = 0, movable = 0, owned = 0, total = 0;
  CutPlacement placement = CutPlacement::kLast;
  std::vector<int64_t> gid;      // local -> global id
  AlignedVector<double> xy;      // local coordinates, 2 per vertex
  Csr v2v;                       // rows [0, movable), by global id
  AlignedVector<int32_t> tri;    // owned triangles, local corners (aligned: traced, access.h)
  AlignedVector<double> weight;  // their global quality weights
  std::vector<RankLink> links;   // by rank; non-empty send or recv
  int32_t cut() const { return movable - noncut; }
  int32_t ghosts() const { return total - owned; }
};

// `part[v]` in [0, parts) for every vertex of `m`; `colour` a proper colouring of the part graph
// (MeasurePartition's). `ordering` is a registry spec (seeded ones take `seed`). A part may be
// empty. Throws UsageError for a bad ordering spec, std::invalid_argument for inconsistent sizes.
RankPart BuildRankPart(const Mesh& m, const std::vector<int32_t>& part, int32_t parts,
                       const std::vector<int32_t>& colour, int32_t rank,
                       const OrderingSpec& ordering = "ori", uint64_t seed = 1,
                       CutPlacement placement = CutPlacement::kLast);

// The same part from the rank's neighbourhood alone (a distributed read, rank_neighbourhood.h):
// equal, member for member, to BuildRankPart on the whole mesh with the range partition
// (nb.part), the neighbourhood's global ids and weights standing in for the whole mesh's.
RankPart BuildRankPart(const RankNeighbourhood& nb, const std::vector<int32_t>& colour,
                       const OrderingSpec& ordering = "ori", uint64_t seed = 1,
                       CutPlacement placement = CutPlacement::kLast);
// The same from a neighbourhood not needed afterwards: its v2t and interior list are released
// first (a third of its memory), lowering the rank's peak.
RankPart BuildRankPart(RankNeighbourhood&& nb, const std::vector<int32_t>& colour,
                       const OrderingSpec& ordering = "ori", uint64_t seed = 1,
                       CutPlacement placement = CutPlacement::kLast);

// What π needs of one rank: its colour, placement, number of non-cut vertices and its movable
// vertices' global ids in local order.
struct RankMoves {
  int32_t colour = 0;
  CutPlacement placement = CutPlacement::kLast;
  int32_t noncut = 0;
  std::vector<int64_t> gid;
};
// The serial order a distributed ordered Gauss-Seidel sweep equals (halo_smoother.h), ranks in
// turn and each in local order within a step. kLast: every rank's non-cut vertices, then the cut
// vertices of the ranks of colour 0, of colour 1, ...; kFirst: the cut vertices colour by colour,
// then every rank's non-cut ones; kInterleaved: the whole movable set of the ranks of colour 0,
// of colour 1, ... Global ids. (Why each is exact: halo_smoother.h.)
std::vector<int64_t> VisitOrderOf(const std::vector<RankMoves>& ranks);
std::vector<int64_t> GatheredVisitOrder(const std::vector<RankPart>& parts);

}  // namespace meshreuse
