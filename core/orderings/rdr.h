// The paper's RDR ordering with the vertex qualities given explicitly, so tests can choose them.
#pragma once

#include <vector>

#include "core/mesh.h"
#include "core/permutation.h"

namespace meshreuse {

Permutation RdrOrder(const Mesh& m, const std::vector<double>& quality);

}  // namespace meshreuse
