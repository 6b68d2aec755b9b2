// rdr-frontier: the paper's Algorithm 2 with one rule changed, the restart. Algorithm 2 as written
// (rdr.cc) restarts a dead-ended chain from the next-worst interior vertex anywhere in the mesh,
// so consecutive chains land far apart. Here a dead-ended chain restarts from the worst-quality
// vertex that is already placed (appended to the order) and not yet processed -- a priority queue
// over the placed frontier, keyed by (initial vertex quality, id) -- and falls back to the global
// quality order over interior vertices only when that frontier is empty. Chains themselves are
// Algorithm 2's: process the head, append its unsorted neighbours by increasing quality, continue
// from the first unprocessed one. Vertices never reached are appended in id order, as in rdr.
#include <queue>
#include <utility>

#include "core/orderings/common.h"
#include "core/orderings/rdr.h"
#include "core/orderings/registry.h"
#include "core/quality.h"

namespace meshreuse {

Permutation RdrFrontierOrder(const Mesh& m, const std::vector<double>& quality, RdrChains* chains) {
  const int32_t n = m.NumVertices();
  const std::vector<int32_t> nbr = orderings::RowsByKey(m, quality);
  const int64_t* off = m.v2v.off.data();
  std::vector<uint8_t> processed(n, 0), sorted(n, 0);
  std::vector<int32_t> order;
  order.reserve(n);
  using Entry = std::pair<double, int32_t>;  // (quality, id): the smallest on top
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> frontier;
  auto place = [&](int32_t v) {
    order.push_back(v);
    sorted[v] = 1;
    frontier.emplace(quality[v], v);
  };
  const std::vector<int32_t> global =
      orderings::StableSortByKey({m.interior.begin(), m.interior.end()}, quality);
  size_t g = 0;
  while (true) {
    int32_t head = -1;
    while (!frontier.empty() && head < 0) {
      if (!processed[frontier.top().second]) head = frontier.top().second;
      frontier.pop();
    }
    const size_t chain_start = order.size();
    if (head < 0) {  // the frontier is empty: the worst unprocessed interior vertex
      while (g < global.size() && processed[global[g]]) ++g;
      if (g == global.size()) break;
      head = global[g];
      if (!sorted[head]) place(head);
    }
    while (true) {  // one chain, as Algorithm 2
      processed[head] = 1;
      int32_t next = -1;
      for (const int32_t* p = nbr.data() + off[head]; p != nbr.data() + off[head + 1]; ++p) {
        if (processed[*p]) continue;
        if (next < 0) next = *p;
        if (!sorted[*p]) place(*p);
      }
      if (next < 0) break;
      head = next;
    }
    if (chains) chains->placed.push_back(static_cast<int64_t>(order.size() - chain_start));
  }
  for (int32_t v = 0; v < n; ++v)
    if (!sorted[v]) order.push_back(v);
  return Permutation::FromNewToOld(std::move(order));
}

Permutation OrderRdrFrontier(const Mesh& m, const OrderingContext&) {
  return RdrFrontierOrder(m, VertexQualities(m));
}

}  // namespace meshreuse
