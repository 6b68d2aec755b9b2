// The untangle kernel's tangling (core/kernels/untangle.cc): a documented jitter that turns a known
// share of triangles over, the same whatever the numbering of the mesh.
#pragma once

#include <cstdint>

#include "core/mesh.h"

namespace meshreuse {

// What untangle sweeps tangle their input with: 5% of the interior vertices, chosen by this seed.
inline constexpr double kTangleShare = 0.05;
inline constexpr uint64_t kTangleSeed = 41;

struct TangleStats {
  double orientation = 1;  // +1: the mesh's triangles are counter-clockwise, -1 clockwise
  double beta = 0;         // 0.05 x the mean |doubled area| before tangling
  int64_t moved = 0;       // vertices moved
  int64_t inverted = 0;    // triangles turned over (or flat) after
};

// Moves each interior vertex whose position hashes (core/mix.h Mix64 of its coordinates' bits and
// `seed`) below `share` of the range to 1.5 times the way to its neighbour with the smallest
// (x, y): past that neighbour, so both triangles on their edge turn over. Every move is computed
// from the positions before any, so the tangled mesh does not depend on the numbering.
TangleStats TangleMesh(Mesh& m, double share, uint64_t seed);
// Triangles whose doubled area, times `orientation`, is not positive.
int64_t CountInverted(const Mesh& m, double orientation);

}  // namespace meshreuse
