// bfs: breadth-first search order (Strout and Hovland 2004, the paper's BFS). Start rule: vertex 0,
// the first vertex of the original order; neighbours are queued in increasing id (v2v rows are
// sorted); when a component is exhausted, the next starts at the lowest unvisited id. Vertices are
// numbered in the order they are dequeued (= enqueued, for a FIFO).
#include "core/orderings/common.h"
#include "core/orderings/registry.h"

namespace meshreuse {

namespace orderings {

std::vector<int32_t> BfsVisitOrder(const Mesh& m, std::vector<int32_t>* parent) {
  const int32_t n = m.NumVertices();
  std::vector<int32_t> order;
  order.reserve(n);
  std::vector<uint8_t> seen(n, 0);
  if (parent) parent->assign(n, -1);
  for (int32_t s = 0; s < n; ++s) {
    if (seen[s]) continue;
    seen[s] = 1;
    order.push_back(s);
    for (size_t head = order.size() - 1; head < order.size(); ++head) {
      const int32_t v = order[head];
      for (const int32_t* p = m.v2v.RowBegin(v); p != m.v2v.RowEnd(v); ++p)
        if (!seen[*p]) {
          seen[*p] = 1;
          if (parent) (*parent)[*p] = v;
          order.push_back(*p);
        }
    }
  }
  return order;
}

}  // namespace orderings

Permutation OrderBfs(const Mesh& m, const OrderingContext&) {
  return Permutation::FromNewToOld(orderings::BfsVisitOrder(m));
}

}  // namespace meshreuse
