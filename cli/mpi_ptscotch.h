// `--partition ptscotch` for meshreuse-mpi (issue 23, ../shared/scale-out.md 3c): PT-Scotch, the
// distributed partitioner, over MPI_COMM_WORLD. Built only with MPI and Debian's 64-bit PT-Scotch
// (libptscotch-dev, scotch-int64); the libraries stay MPI-free, so it lives here beside the MPI
// driver.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ranks/rank_neighbourhood.h"

namespace meshreuse::cli {

// Every rank of MPI_COMM_WORLD calls it at once with `parts` equal to the number of ranks: rank r
// hands PT-Scotch its graph rows, ids [RangeFirst(r), RangeFirst(r + 1))
// (core/ranks/rank_neighbourhood.h), PT-Scotch partitions the distributed graph (balance within 3%,
// random state seeded by `seed`), and rank r gets the parts of its rows
// (core/ranks/part_directory.h then says who owns what). EnvironmentError when PT-Scotch fails.
std::vector<int32_t> PtScotchParts(const GraphRows& rows, int32_t parts, uint64_t seed);

}  // namespace meshreuse::cli
