// A serial Gauss-Seidel visit order read from a file: one 0-based vertex id per line, '#' starts a
// comment; it must list every interior vertex of the mesh exactly once and nothing else. The
// smoother then visits the interior vertices in that order while the storage (and each neighbour
// sum's order) stays the mesh's own: the serial sweep a distributed ordered sweep equals
// (halo_smoother.h, `meshreuse-mpi smooth --pi-out`). A file: permutation would renumber the
// vertices, and the renumbered rows would add the neighbours in another order (other last bits).
#pragma once

#include <cstdint>
#include <string>

#include "core/aligned.h"
#include "core/mesh.h"

namespace meshreuse {

// Throws InputError naming the file and line: not a number, an id out of range, a boundary
// vertex, a repeat (with the line of its first use), a missing interior vertex (naming it).
AlignedVector<int32_t> ReadVisitOrder(const std::string& path, const Mesh& m);

}  // namespace meshreuse
