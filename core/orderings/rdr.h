// The paper's RDR ordering and its two variants with the vertex qualities given explicitly, so
// tests can choose them.
#pragma once

#include <vector>

#include "core/mesh.h"
#include "core/permutation.h"

namespace meshreuse {

// Chains: each walk from a start vertex until it dead-ends; `placed` counts the vertices a chain
// appended to the order (its start included when the start was new).
struct RdrChains {
  std::vector<int64_t> placed;
};
Permutation RdrOrder(const Mesh& m, const std::vector<double>& quality,
                     RdrChains* chains = nullptr);
Permutation RdrFrontierOrder(const Mesh& m, const std::vector<double>& quality,
                             RdrChains* chains = nullptr);                    // rdr_frontier.cc
Permutation RdrWaveOrder(const Mesh& m, const std::vector<double>& quality);  // rdr_wave.cc

}  // namespace meshreuse
