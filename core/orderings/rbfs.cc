// rbfs: the BFS visit order reversed (the variant Munson and Hovland found best for Feasible
// Newton mesh optimisation).
#include <algorithm>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"

namespace meshreuse {

Permutation OrderRbfs(const Mesh& m, const OrderingContext&) {
  std::vector<int32_t> order = orderings::BfsVisitOrder(m);
  std::reverse(order.begin(), order.end());
  return Permutation::FromNewToOld(std::move(order));
}

}  // namespace meshreuse
