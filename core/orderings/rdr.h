// The paper's RDR ordering and its two variants with the vertex qualities given explicitly, so
// tests can choose them.
#pragma once

#include <vector>

#include "core/mesh.h"
#include "core/permutation.h"

namespace meshreuse {

Permutation RdrOrder(const Mesh& m, const std::vector<double>& quality);
Permutation RdrFrontierOrder(const Mesh& m, const std::vector<double>& quality);  // rdr_frontier.cc
Permutation RdrWaveOrder(const Mesh& m, const std::vector<double>& quality);      // rdr_wave.cc

}  // namespace meshreuse
