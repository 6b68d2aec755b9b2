// The edge-swap kernel's jitter (core/kernels/edge_swap.cc): a documented perturbation that leaves
// every triangle valid and the mesh no longer Delaunay, the same whatever the numbering.
#pragma once

#include <cstdint>

#include "core/mesh.h"

namespace meshreuse {

// What edge-swap sweeps perturb their input with.
inline constexpr double kJitterAmount = 0.15;
inline constexpr uint64_t kJitterSeed = 43;

// Moves every interior vertex by `amount` x the least altitude of its triangles, in a direction
// drawn from a hash (core/mix.h Mix64) of its coordinates' bits and `seed`; every move computed
// from the positions before any. With amount <= 0.15 no triangle turns over: each corner of a
// triangle moves less than 0.15 of its least altitude h, which changes its doubled area (at least
// h |e| for each edge e) by less than 0.45 of it to first order and 0.07 to second. Returns the
// vertices moved.
int64_t JitterMesh(Mesh& m, double amount, uint64_t seed);

// Whether every interior edge of `m` is locally Delaunay (the fourth point not strictly inside the
// circumcircle of either triangle): the naive check of all edges, for tests.
bool IsDelaunay(const Mesh& m);
// The (triangle, edge) pairs whose edge is not locally Delaunay seen from that triangle (an edge
// may count from both sides).
int64_t NotDelaunayEdges(const Mesh& m);

}  // namespace meshreuse
