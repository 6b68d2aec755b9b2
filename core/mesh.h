// The mesh model: 2D coordinates, triangles, topological boundary flags and the two adjacencies the
// smoother needs (vertex->vertex, vertex->triangle) in CSR form.
// Invariants after BuildMesh: every vertex is used by a triangle; no triangle is degenerate
// (zero area) or repeated; every edge has one or two triangles; a vertex is a boundary vertex iff
// it lies on an edge with exactly one triangle; v2v rows hold distinct neighbours in increasing id
// order and v2t rows incident triangles in increasing id order; `interior` lists the non-boundary
// vertices in storage order (the smoother's iteration space, DESIGN.md "Smoothing sweep").
#pragma once

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "core/aligned.h"

namespace meshreuse {

// Compressed rows: row r is idx[off[r] .. off[r+1]). Offsets are 64-bit, entries 32-bit ids.
struct Csr {
  AlignedVector<int64_t> off;  // 64-byte aligned: traced (see aligned.h)
  AlignedVector<int32_t> idx;

  int64_t RowSize(int32_t r) const { return off[r + 1] - off[r]; }
  const int32_t* RowBegin(int32_t r) const { return idx.data() + off[r]; }
  const int32_t* RowEnd(int32_t r) const { return idx.data() + off[r + 1]; }
};

// A number per item (its source line, the file's own id) kept as runs of consecutive numbers:
// a file without comments or gaps costs one run whatever its size, where a plain array would cost
// 8 bytes per item (a third of a mesh's memory while it is read). Values must be pushed in item
// order; any sequence works, only its memory depends on the runs.
class RunIndex {
 public:
  RunIndex() = default;
  RunIndex(std::initializer_list<int64_t> values) {
    for (int64_t v : values) Push(v);
  }
  void Push(int64_t value) {
    // last_ + 1 would overflow for a tag of INT64_MAX (a Gmsh file may hold one): a new run.
    if (size_ == 0 || last_ == INT64_MAX || value != last_ + 1) {
      first_item_.push_back(size_);
      first_value_.push_back(value);
    }
    last_ = value;
    ++size_;
  }
  int64_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  size_t runs() const { return first_item_.size(); }
  // The number of item i; `missing` when there is no item i (e.g. a generated mesh).
  int64_t At(int64_t i, int64_t missing = 0) const {
    if (i < 0 || i >= size_) return missing;
    const size_t r = static_cast<size_t>(
        std::upper_bound(first_item_.begin(), first_item_.end(), i) - first_item_.begin() - 1);
    return first_value_[r] + (i - first_item_[r]);
  }
  std::vector<int64_t> ToVector() const {
    std::vector<int64_t> v(static_cast<size_t>(size_));
    for (int64_t i = 0; i < size_; ++i) v[i] = At(i);
    return v;
  }

 private:
  std::vector<int64_t> first_item_, first_value_;
  int64_t size_ = 0, last_ = 0;
};

// What a reader hands to BuildMesh: raw arrays plus where each item came from, so topology errors
// can name a file and a line. Lines and tags may be empty (generated meshes). Coordinates and
// triangles are the arrays the Mesh keeps: BuildMesh moves them in rather than copying.
struct RawMesh {
  AlignedVector<double> xy;           // 2 per vertex, interleaved x, y
  AlignedVector<int32_t> tri;         // 3 per triangle, 0-based indices into the vertices
  std::string vertex_file;            // where vertices came from (e.g. the .node file)
  std::string triangle_file;          // where triangles came from (e.g. the .ele file)
  RunIndex vertex_line;               // source line per vertex
  RunIndex triangle_line;             // source line per triangle
  RunIndex vertex_tag;                // the file's own vertex number, for messages
  RunIndex triangle_tag;              // Gmsh's element tag per triangle (empty for other formats)
  std::vector<std::string> warnings;  // from the reader (e.g. skipped element types)
};

class Mesh {
 public:
  Mesh() = default;
  Mesh(Mesh&&) = default;
  Mesh& operator=(Mesh&&) = default;
  Mesh(const Mesh&) = delete;  // big: copies must be asked for by name
  Mesh& operator=(const Mesh&) = delete;
  Mesh Clone() const;
  // The same copy into `out`, whose arrays keep their storage where it is large enough (a run
  // restarting from a layout: no allocation, no fresh pages).
  void CopyInto(Mesh* out) const;

  int32_t NumVertices() const { return static_cast<int32_t>(xy.size() / 2); }
  int32_t NumTriangles() const { return static_cast<int32_t>(tri.size() / 3); }
  int32_t NumBoundary() const { return NumVertices() - static_cast<int32_t>(interior.size()); }

  // Every array the sweep reads is 64-byte aligned (aligned.h): line-level results are the same
  // in every run.
  AlignedVector<double> xy;
  AlignedVector<int32_t> tri;
  std::vector<uint8_t> boundary;    // 1 on the topological boundary
  Csr v2v;                          // distinct neighbours, increasing id
  Csr v2t;                          // incident triangles, increasing id
  AlignedVector<int32_t> interior;  // non-boundary vertices, increasing id
};

struct BuildReport {
  std::vector<std::string> warnings;
  // mesh vertex -> raw vertex when unused vertices were dropped; empty when none was (identity).
  std::vector<int32_t> kept;
};

// Validates the raw input and builds the adjacency in O(V + T). Throws InputError naming the file
// and line of the offending triangle for: a corner out of range, a repeated corner, zero area, a
// non-finite coordinate, a duplicate triangle, an edge with more than two triangles. Vertices no
// triangle uses are dropped (keeping the relative order of the rest) and reported in `report`.
Mesh BuildMesh(RawMesh raw, BuildReport* report = nullptr);

}  // namespace meshreuse
