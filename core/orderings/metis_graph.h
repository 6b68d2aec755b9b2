// The mesh's vertex graph in METIS's CSR form (idx_t, 32-bit in Debian's libmetis-dev), shared by
// the metis and nd orderings. Refuses (std::length_error) graphs whose edge count does not fit.
#pragma once

#include <metis.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace meshreuse::orderings {

struct MetisGraph {
  idx_t n = 0;
  std::vector<idx_t> xadj, adjncy;
};

inline MetisGraph ToMetis(const Mesh& m) {
  MetisGraph g;
  g.n = static_cast<idx_t>(m.NumVertices());
  const int64_t edges = m.v2v.off[m.NumVertices()];
  if (edges > static_cast<int64_t>(std::numeric_limits<idx_t>::max()))
    throw std::length_error("the mesh has more adjacency entries than METIS's idx_t holds");
  g.xadj.assign(m.v2v.off.begin(), m.v2v.off.end());
  g.adjncy.assign(m.v2v.idx.begin(), m.v2v.idx.end());
  return g;
}

inline void MetisCheck(int status, const char* what) {
  if (status != METIS_OK)
    throw std::runtime_error(std::string(what) + " failed (METIS status " + std::to_string(status) +
                             ")");
}

}  // namespace meshreuse::orderings
