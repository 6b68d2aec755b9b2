// Uniform refinement of a triangle mesh (issue 23, ../shared/scale-out.md section 3b): every
// triangle into 4^K by K halvings of its edges at once, n = 2^K segments per coarse edge.
//
// Global ids need no communication: the coarse vertices keep theirs (0..V-1); then the n-1 points
// of each coarse edge, edges numbered by (lower id, higher id) in increasing order, points from the
// lower-id end; then the (n-1)(n-2)/2 interior points of each coarse triangle, triangles in file
// order, points by lattice row. So any process holding the coarse mesh can produce any piece of
// the fine mesh (RefinePiece), and pieces agree bit for bit with the whole.
// Coordinates: an edge point is x_lo + (x_hi - x_lo) * (s / n), s counted from the lower-id end:
// the same doubles from both triangles that share the edge (the shapes are piecewise linear, so the
// fine geometry is exact up to that rounding). Interior points: A + (B - A) j/n + (C - A) k/n with
// the triangle's corners A, B, C in file order. Fine triangles keep their coarse triangle's
// orientation and come in coarse-triangle order, each coarse triangle's by lattice row.
// Jitter (optional): each new vertex that is not on the coarse boundary moves by up to
// jitter * h / 2 in x and in y, h the smallest altitude of the coarse triangles it touches divided
// by n, the offset a hash of (global id, seed): positive areas for jitter below 0.7 (a fine
// triangle's altitude is at least h, and each corner moves less than h / 2).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "core/mesh_file.h"

namespace meshreuse {

struct RefineOptions {
  int levels = 1;     // K: each triangle into 4^K
  double jitter = 0;  // 0..0.5, a fraction of the local fine spacing
  uint64_t seed = 1;  // of the jitter
};

// The fine mesh's size; throws UsageError when its vertex or triangle ids would exceed 32 bits.
struct RefinedSize {
  int64_t vertices = 0, triangles = 0, edges = 0;  // edges: the coarse mesh's
};
RefinedSize RefinedSizeOf(const Mesh& coarse, const RefineOptions& o);

// The fine triangles of coarse triangles [tri_begin, tri_end) with global vertex ids, and the
// coordinates of exactly the vertices they use (ids ascending).
struct RefinedPiece {
  std::vector<int32_t> tri;  // 3 global ids per fine triangle
  std::vector<int32_t> ids;  // the vertices used, ascending
  std::vector<double> xy;    // their coordinates, 2 per id
};
RefinedPiece RefinePiece(const Mesh& coarse, const RefineOptions& o, int32_t tri_begin,
                         int32_t tri_end);

// The whole fine mesh (every vertex is used by some fine triangle).
RawMesh RefineMesh(const Mesh& coarse, const RefineOptions& o);

// The pieces layout of a refined mesh (`mesh refine --layout pieces`, `meshreuse-mpi refine`):
// fine vertex ids in blocks, one per coarse triangle in the coarse mesh's triangle order, so that
// any process holding the coarse mesh can write any range of blocks of the fine mesh's file with no
// communication (a Hilbert order of the fine vertices would need a distributed sort). Coarse
// vertex v belongs to the block of its lowest-id triangle, a coarse edge's points to the block of
// its lower-id triangle. Block t holds, in order: its owned corners (corner order), its owned
// edges' points (edges c0c1, c0c2, c1c2; points from the edge's lower-id end), its interior points
// (the refinement's order). Fine triangles keep the refinement's order (coarse triangle by coarse
// triangle), so a range of blocks is also a range of triangles. With the coarse mesh in Hilbert
// order (LayOutForRanks), ranges of ids partition the fine mesh about as well as its Hilbert order.
struct RefinedRange;
class PiecesLayout {
 public:
  PiecesLayout(const Mesh& coarse, const RefineOptions& o);
  int64_t vertices() const { return block_.back(); }
  int64_t triangles() const;
  // The pieces id of the refinement's global id g (refine.h's numbering).
  int32_t NewId(int32_t g) const;
  // Fine vertices [BlockStart(t), BlockStart(t + 1)) are coarse triangle t's; t in [0, T].
  int64_t BlockStart(int32_t t) const { return block_[t]; }
  // v2t row offset of BlockStart(t): the fine triangles' corners at the vertices before it.
  int64_t RowStart(int32_t t) const { return row_[t]; }
  // Writers' split: coarse triangles [Split(r), Split(r + 1)) for rank r of P, from the first
  // block starting at or after V r / P (a rank may get none; a block may hold no vertex -- a
  // triangle owning none of its corners and edges, with no interior point below K = 2 -- but
  // always has triangles, so Split(P) is T).
  int32_t Split(int32_t r, int32_t parts) const;

 private:
  friend RefinedRange RefineRange(const Mesh&, const RefineOptions&, const PiecesLayout&, int32_t,
                                  int32_t);
  int32_t nv_ = 0, nt_ = 0;
  int64_t n_ = 1, interior_ = 0, edge_base_ = 0, tri_base_ = 0;
  std::vector<int32_t> vertex_owner_, edge_owner_;
  std::vector<uint8_t> vertex_slot_, edge_slot_, edge_count_, corners_, edges_;
  std::vector<int64_t> block_, row_;
};

// The file sections of coarse triangles [tri_begin, tri_end)'s blocks in the pieces layout:
// vertices [first_vertex, first_vertex + boundary.size()), triangles [first_triangle,
// first_triangle + tri.size() / 3), v2t rows of those vertices (offsets absolute, one more than
// the vertices), each row's triangles in increasing id: exactly the bytes the whole mesh in that
// layout stores there (the tests compare with WriteMeshFile of RefineMesh permuted).
struct RefinedRange : MeshFileRange {
  // The smallest doubled area of the range's fine triangles, signed by their coarse triangle's
  // orientation: positive when every one keeps it (a mesh read may turn either way).
  double min_area2 = 0;
};
RefinedRange RefineRange(const Mesh& coarse, const RefineOptions& o, const PiecesLayout& layout,
                         int32_t tri_begin, int32_t tri_end);
// The whole refined mesh in the pieces layout (the reference the ranges are tested against).
RawMesh RefineMeshPieces(const Mesh& coarse, const RefineOptions& o);

// A partition of the coarse vertices inherited by the fine ones, computed locally (../shared/
// scale-out.md 3c): a coarse vertex keeps its part, a point of a coarse edge takes the part of the
// edge's lower-id end, an interior point that of its triangle's smallest corner.
std::vector<int32_t> InheritParts(const Mesh& coarse, const RefineOptions& o,
                                  const std::vector<int32_t>& coarse_part);

// A content hash of coordinates and triangles (bit patterns), for "the same mesh bit for bit".
uint64_t MeshContentHash(const AlignedVector<double>& xy, const AlignedVector<int32_t>& tri);

}  // namespace meshreuse
