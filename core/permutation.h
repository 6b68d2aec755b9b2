// A vertex permutation: new -> old and old -> new, validated to be a bijection on 0..n-1.
// Applying it to a mesh permutes the vertex arrays, renumbers triangle corners and re-sorts the
// triangles to follow the new vertex order (data and iteration reordering, Strout and Hovland
// 2004), so the smoother's traversal and the storage agree.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace meshreuse {

class Permutation {
 public:
  Permutation() = default;
  Permutation(Permutation&&) = default;
  Permutation& operator=(Permutation&&) = default;
  Permutation(const Permutation&) = delete;  // V entries twice: copies are asked for by name
  Permutation& operator=(const Permutation&) = delete;
  Permutation Clone() const;

  // Throws std::invalid_argument naming the first problem (an id out of range, a repeated id).
  static Permutation FromNewToOld(std::vector<int32_t> new_to_old);
  static Permutation Identity(int32_t n);

  int32_t size() const { return static_cast<int32_t>(new_to_old_.size()); }
  int32_t OldOf(int32_t new_id) const { return new_to_old_[new_id]; }
  int32_t NewOf(int32_t old_id) const { return old_to_new_[old_id]; }
  const std::vector<int32_t>& new_to_old() const { return new_to_old_; }
  const std::vector<int32_t>& old_to_new() const { return old_to_new_; }
  Permutation Inverse() const;

 private:
  std::vector<int32_t> new_to_old_, old_to_new_;
};

// Where the triangles go when a mesh is laid out in an ordering: one policy for every ordering
// alike, ori included, so comparisons are like for like (DESIGN.md "Orderings").
//   kSorted (default): stably sorted by their smallest new corner, so the triangles of early
//                      vertices come first (storage follows the traversal);
//   kFile:             the file's triangle order, corners renumbered (ori + kFile = the file as
//                      is, the paper's ORI).
enum class TriangleOrder { kSorted, kFile };
TriangleOrder ParseTriangleOrder(const std::string& s);  // sorted | file; UsageError
const char* TriangleOrderName(TriangleOrder t);

// The reordered mesh: vertex new_id is old vertex p.OldOf(new_id). Triangles are renumbered
// (corner order, hence orientation, kept) and placed by `order`. Throws std::invalid_argument if
// sizes differ. Permutes every array directly, in parallel (coordinates, boundary flags, both CSR
// adjacencies -- rows moved, entries renumbered and re-sorted within each row -- triangles and the
// interior list), O(V + T), no validation pass: the result equals ApplyPermutationByRebuild's.
Mesh ApplyPermutation(const Mesh& m, const Permutation& p,
                      TriangleOrder order = TriangleOrder::kSorted);
// The same into `out`, reusing its arrays: a working copy that is reordered again and again (as
// `compare` does before each run) costs no allocation, and when its sizes already match, not even
// a page fault. `out` must not be `m`.
void ApplyPermutationInto(const Mesh& m, const Permutation& p, TriangleOrder order, Mesh* out);
// The same in place, for a mesh that is not needed in its old order (smooth, analyze, reorder):
// each array is rebuilt and swapped in by turn, so the peak is the mesh plus about 40 bytes a
// vertex, not two meshes.
void ApplyPermutationInPlace(Mesh* m, const Permutation& p,
                             TriangleOrder order = TriangleOrder::kSorted);
// The reference: the permuted vertex and triangle arrays handed to BuildMesh, which validates them
// and rebuilds the adjacency from scratch (the implementation before issue 12; tests compare).
Mesh ApplyPermutationByRebuild(const Mesh& m, const Permutation& p,
                               TriangleOrder order = TriangleOrder::kSorted);

// How far apart in memory the two ends of each mesh edge are under `p`: |new(u) - new(v)| over all
// edges. A cheap locality diagnostic (the paper's "span of accesses", its Figure 4): a sweep reads
// every neighbour of the vertex it moves, so a large span means a far, likely uncached, read.
struct EdgeSpan {
  int64_t median = 0, p90 = 0, p99 = 0, max = 0;
  double mean = 0;
};
EdgeSpan MeasureEdgeSpan(const Mesh& m, const Permutation& p);

}  // namespace meshreuse
