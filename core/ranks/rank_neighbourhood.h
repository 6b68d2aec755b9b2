// One rank's share of a distributed mesh file (mesh_file.h), read without the rest of the mesh:
// the owned vertices -- the range of ids [RangeFirst(r), RangeFirst(r + 1)) (the Hilbert-range
// partition of partition.h when the file is in Hilbert order, HilbertRangeParts' own formula), or
// any set of ids (a part PT-Scotch computed: core/ranks/part_directory.h says who owns what) --,
// their v2t rows, every triangle those rows list, and the ghost ring (the other corners of those
// triangles) with coordinates, boundary flags and triangle counts. About (owned + ghosts) * 100
// bytes of reading, whatever the size of the mesh; a scattered part is read run by run of
// consecutive ids, each block once.
// The result is the neighbourhood as a Mesh of its own, local ids in increasing global id and
// triangles in increasing global id, so BuildRankPart (rank_part.h) lays it out exactly as it lays
// out the same rank from the whole mesh (the same local mesh of the part, the same rows, the same
// weights): a distributed read smooths bit for bit as a whole read with `--partition hilbert`.
// Checks, beyond the file's (each an InputError naming the file and the vertex or triangle): every
// owned row increasing, within range and listing triangles that hold the vertex; the triangles
// holding an owned vertex are exactly its row (so its neighbours are all here); the owned boundary
// flags equal what the owned triangles say (each vertex is owned by one rank, so every flag a
// ghost is read with is checked by its owner); BuildMesh's checks on the neighbourhood (areas,
// repeated triangles, edges of more than two triangles). What one rank cannot see -- a triangle
// that no row lists -- CheckRankShares finds from every rank's counts.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace meshreuse {

// The first id of rank r's range of n ids over `parts` ranks, and the rank of id v: rank r holds
// the ids i with floor(i * parts / n) = r (HilbertRangeParts' formula).
int64_t RangeFirst(int32_t r, int64_t n, int32_t parts);
int32_t RangeOwner(int64_t v, int64_t n, int32_t parts);

struct RankNeighbourhood {
  int32_t rank = 0, parts = 1;
  int64_t vertices = 0, triangles = 0;  // of the whole mesh
  uint64_t content_id = 0;
  int64_t owned = 0;                // owned vertices (local ids hold them in increasing gid)
  Mesh mesh;                        // owned + ghosts, local ids by increasing global id
  std::vector<int64_t> gid;         // local -> global
  std::vector<int32_t> part;        // local -> owning rank
  std::vector<double> weight;       // per local triangle, its weight in the global quality
  int64_t owned_triangles = 0;      // triangles whose smallest corner is owned
  int64_t row_entries = 0;          // sum of the owned v2t row lengths
  int64_t cut_edges = 0;            // edges from an owned vertex to a larger id elsewhere
  std::vector<int32_t> neighbours;  // ranks owning a ghost, increasing
  uint64_t bytes_read = 0;
};

// What a rank needs of each ghost, from the ghost's owner.
struct GhostRecord {
  double x = 0, y = 0;
  int64_t triangles = 0;  // its v2t row's length, for the quality weights
  uint8_t boundary = 0;
};
// A rank's answer for one of its owned vertices (InputError for a vertex it does not own).
using OwnedLookup = std::function<GhostRecord(int64_t gid)>;
// What a rank asks of the others: the ghosts it needs (increasing global id) and their owners
// (in any order: a scattered part's ghosts), with the file's name and content id, so an exchange
// can refuse ranks that read different files before any of them answers for a vertex.
struct GhostRequest {
  std::string path;
  uint64_t content_id = 0;
  int64_t vertices = 0;
  std::vector<int64_t> wanted;
  std::vector<int32_t> owner;
};
// The records of the request's ghosts, in order. Called once per rank, after the rank has read its
// own range, with `mine` answering for it: every rank of a job calls it at the same point, so an
// implementation can exchange requests and answers between ranks (the distributed smoother's: one
// request and one answer per neighbouring rank, what the owner read and will check). Empty: each
// rank reads its ghosts from the file itself, the blocks around each ghost, no communication (on
// a 400 x 320 synthetic mesh, a 9.2 MB file, at 4 ranks a rank then read 33-35% of the file
// against its 25%).
using GhostLookup =
    std::function<std::vector<GhostRecord>(const GhostRequest& request, const OwnedLookup& mine)>;

class Communicator;
// The exchange through a transport (halo_smoother.h; MPI or threads): one all-gather of who asks
// whom for how many, then per neighbouring rank one request (the global ids) and one answer (x, y,
// triangles, flag per ghost) -- 40 bytes a ghost. Every rank of the transport must read at once.
GhostLookup GhostExchange(Communicator& tx);

// Throws InputError for a damaged or inconsistent file, UsageError when `parts` exceeds the
// vertices.
RankNeighbourhood ReadRankNeighbourhood(const std::string& path, int32_t rank, int32_t parts,
                                        const GhostLookup& lookup = {});
// The owners of a rank's ghosts (increasing global ids), one per ghost: called once by every rank
// at the same point, ghosts or none, so an implementation may ask the other ranks
// (part_directory.h's LookUpParts).
using GhostOwners = std::function<std::vector<int32_t>(const std::vector<int64_t>& ghosts)>;
// The neighbourhood of any owned set (increasing ids; empty: a part with no vertex, which still
// takes part in the collective calls). The same checks as ReadRankNeighbourhood; every vertex
// must be owned by exactly one rank, which CheckRankShares verifies from the shares' counts.
RankNeighbourhood ReadPartNeighbourhood(const std::string& path, int32_t rank, int32_t parts,
                                        std::vector<int64_t> owned, const GhostOwners& owners,
                                        const GhostLookup& lookup = {});

// Positions in an increasing list of ids, found by binary search over its runs of consecutive
// ids (the longest run tried first: a range's owned ids are one run), so the search stays in
// cache where a search of the ids themselves would not.
class SortedIds {
 public:
  explicit SortedIds(const std::vector<int64_t>& ids);  // std::logic_error unless increasing
  int64_t Find(int64_t id) const;                       // its position, or -1
 private:
  std::vector<int64_t> start_, pos_;
  int64_t big_first_ = 0, big_pos_ = 0, big_len_ = 0;  // the longest run
};

// Rows of the vertex graph (neighbours by global id, each row increasing) for the vertices
// [first, first + off.size() - 1) of a graph of `vertices` vertices: what a distributed
// partitioner (PT-Scotch) is given by each rank.
struct GraphRows {
  int64_t vertices = 0, first = 0;
  std::vector<int64_t> off = {0}, adj;
  uint64_t bytes_read = 0;  // of the mesh file (ReadRangeGraphRows)
};
// Rank r's range of rows, from the whole mesh or from a mesh file (its rows and triangles only,
// checked as ReadRankNeighbourhood checks them).
GraphRows RangeGraphRows(const Mesh& m, int32_t rank, int32_t parts);
GraphRows ReadRangeGraphRows(const std::string& path, int32_t rank, int32_t parts);

// What each rank contributes to the checks no single rank can make.
struct RankShare {
  uint64_t content_id = 0;
  int64_t vertices = 0, triangles = 0, owned_triangles = 0, row_entries = 0, cut_edges = 0;
  int64_t owned = 0;
  std::vector<int32_t> neighbours;
};
RankShare ShareOf(const RankNeighbourhood& nb);
std::string PackShare(const RankShare& s);
RankShare UnpackShare(const std::string& bytes);  // std::logic_error when short
// Every rank calls it with every rank's share (by rank) and gets the same verdict: InputError when
// ranks read different files (content ids differ), when the owned vertices do not add up to the
// file's V, the owned triangles to its T or the rows to 3T (a triangle some row omits), or when the
// neighbour relation is not symmetric. Returns the part graph (each rank's neighbours) for the
// colouring.
std::vector<std::vector<int32_t>> CheckRankShares(const std::string& path,
                                                  const std::vector<RankShare>& shares);

}  // namespace meshreuse
