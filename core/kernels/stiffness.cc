// StiffnessPattern; see stiffness.h.
#include "core/kernels/stiffness.h"

#include <algorithm>
#include <stdexcept>

namespace meshreuse {

// Untimed set-up of every assembly and spmv run, so it runs on every core, as edge-swap's does
// (each row's and each triangle's entries its own: the same matrix on any number of threads): on
// the --quick report's meshes it was 7% of the kernels part's samples, serial.
StiffnessMatrix StiffnessPattern(const Mesh& m) {
  StiffnessMatrix a;
  const int32_t nv = m.NumVertices();
  a.off.resize(static_cast<size_t>(nv) + 1);
  a.col.resize(m.v2v.idx.size() + static_cast<size_t>(nv));
  a.val.assign(a.col.size(), 0.0);
  for (int32_t i = 0; i <= nv; ++i) a.off[i] = m.v2v.off[i] + i;
#pragma omp parallel for schedule(static, 4096)
  for (int32_t i = 0; i < nv; ++i) {
    int64_t k = a.off[i];
    bool diagonal = false;
    for (const int32_t* u = m.v2v.RowBegin(i); u != m.v2v.RowEnd(i); ++u) {
      if (!diagonal && *u > i) a.col[k++] = i, diagonal = true;
      a.col[k++] = *u;
    }
    if (!diagonal) a.col[k++] = i;
  }
  a.map.resize(9 * static_cast<size_t>(m.NumTriangles()));
  bool missing = false;  // (an exception cannot leave the parallel loop)
#pragma omp parallel for schedule(static, 4096) reduction(|| : missing)
  for (int32_t t = 0; t < m.NumTriangles(); ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    for (int r = 0; r < 3; ++r) {
      const int32_t* b = a.col.data() + a.off[c[r]];
      const int32_t* e = a.col.data() + a.off[c[r] + 1];
      for (int s = 0; s < 3; ++s) {
        const int32_t* at = std::lower_bound(b, e, c[s]);
        missing = missing || at == e || *at != c[s];
        a.map[9 * int64_t{t} + 3 * r + s] = at - a.col.data();
      }
    }
  }
  if (missing) throw std::logic_error("stiffness pattern misses an entry");
  return a;
}

}  // namespace meshreuse
