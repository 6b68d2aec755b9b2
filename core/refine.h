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

// A partition of the coarse vertices inherited by the fine ones, computed locally (../shared/
// scale-out.md 3c): a coarse vertex keeps its part, a point of a coarse edge takes the part of the
// edge's lower-id end, an interior point that of its triangle's smallest corner.
std::vector<int32_t> InheritParts(const Mesh& coarse, const RefineOptions& o,
                                  const std::vector<int32_t>& coarse_part);

// A content hash of coordinates and triangles (bit patterns), for "the same mesh bit for bit".
uint64_t MeshContentHash(const AlignedVector<double>& xy, const AlignedVector<int32_t>& tri);

}  // namespace meshreuse
