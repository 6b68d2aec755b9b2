// The working set of one sweep of each mesh kernel (issue 41: `mesh info --kernels`): the distinct
// cache lines a sweep of the kernel touches on the mesh as it is stored, in total and per array,
// with the sweep's loads and stores. Measured, not estimated: two sweeps of the kernel are traced
// (tracer/access_stream.h, one thread) on a copy of the mesh and the last is counted: the second,
// or the first where the kernel stopped after it (edge-swap, when it flipped nothing). A line is
// counted where an access starts, as analysis/sweep_footprint.h counts it, so the total is that
// file's D_s: the lines a sweep must bring in, which no cache smaller than them holds from one
// sweep to the next. Per array, the lines each tag touched (the weights and the qualities are one
// array under two tags: their lines count for each, once in the total).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh.h"
#include "reports/log.h"

namespace meshreuse {

struct KernelWorkingSet {
  std::string kernel;
  uint64_t accesses = 0;  // loads and stores of the counted sweep
  uint64_t lines = 0;     // distinct lines it touches
  // Per array (Array tag) touched, in Array order: the distinct lines of its accesses.
  std::vector<std::pair<std::string, uint64_t>> arrays;
};

// `kernels`: names of core/kernels/ (UsageError for an unknown one); a progress line per kernel.
std::vector<KernelWorkingSet> KernelWorkingSets(const Mesh& mesh,
                                                const std::vector<std::string>& kernels,
                                                uint32_t line_bytes, const Log& log);

}  // namespace meshreuse
