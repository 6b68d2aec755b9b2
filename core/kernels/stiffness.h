// The P1 (linear triangle) stiffness matrix of the Laplace operator, the matrix the FEM kernels
// assemble (core/kernels/assembly.cc) and multiply by (core/kernels/spmv.cc): CSR with a row per
// vertex, its columns the vertex and its neighbours in increasing id (so the pattern is the mesh's
// v2v with the diagonal added: off[i] = v2v.off[i] + i), and per triangle the positions of its
// local 3x3 matrix's nine entries, corner by corner in stored order (the element map every FEM
// code builds once, so the scatter-add finds its entries without a search).
// Local matrix (Ciarlet; any FEM text): with e_a the edge opposite corner a (e_a = p_{a+2} -
// p_{a+1}, indices mod 3) and Area2 the doubled signed area, K_ab = (e_a . e_b) / (2 |Area2|).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/access.h"
#include "core/aligned.h"
#include "core/mesh.h"

namespace meshreuse {

struct StiffnessMatrix {
  AlignedVector<int64_t> off;  // V + 1
  AlignedVector<int32_t> col;  // nnz = 2 E + V
  AlignedVector<double> val;   // nnz, zero until assembled
  AlignedVector<int64_t> map;  // 9 per triangle: map[9t + 3a + b] = position of (corner a, b)
  int64_t nnz() const { return static_cast<int64_t>(col.size()); }
  uint64_t Bytes() const {
    return 8 * uint64_t{off.size()} + 4 * uint64_t{col.size()} + 8 * uint64_t{val.size()} +
           8 * uint64_t{map.size()};
  }
};

// The pattern and the element map of `m`; values zero.
StiffnessMatrix StiffnessPattern(const Mesh& m);

// One assembly sweep into `a` (its values zeroed first, then every triangle's local matrix added
// at its map's positions; core/kernels/assembly.cc documents its accesses); returns the sum of the
// local matrices' traces. Instantiated for NullSink (spmv assembles once with it) and KernelSink.
template <class Sink>
double AssembleStiffness(const Mesh& m, StiffnessMatrix& a, Sink& sink);

// The local matrix of the triangle with corners (ax, ay), (bx, by), (cx, cy), row-major.
inline void LocalStiffness(double ax, double ay, double bx, double by, double cx, double cy,
                           double k[9]) {
  const double ex[3] = {cx - bx, ax - cx, bx - ax}, ey[3] = {cy - by, ay - cy, by - ay};
  const double inv = 1.0 / (2.0 * std::fabs(ex[2] * ey[1] - ey[2] * ex[1]));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) k[3 * a + b] = (ex[a] * ex[b] + ey[a] * ey[b]) * inv;
}

}  // namespace meshreuse
