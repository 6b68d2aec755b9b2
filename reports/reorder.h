// The runner behind `meshreuse reorder`: a mesh, an ordering computed and applied (each timed),
// the reordered mesh and the permutation written (PREFIX.node, PREFIX.ele, PREFIX.perm, whose
// header names the ordering and, for a seeded one, its seed); for RDR, the chains behind it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/permutation.h"
#include "reports/log.h"

namespace meshreuse {

struct ReorderConfig {
  std::string mesh, ordering, output;  // output: a prefix
  uint64_t seed = 1;
  TriangleOrder triangle_order = TriangleOrder::kSorted;
};

struct ReorderResult {
  std::vector<std::string> written;
  double order_seconds = 0, apply_seconds = 0;
  // rdr and rdr-frontier: chains that placed vertices, the longest, the median, those under ten.
  int64_t chains = 0, longest = 0, median = 0, short_chains = 0;
};

ReorderResult RunReorder(const ReorderConfig& cfg, const Log& log);

}  // namespace meshreuse
