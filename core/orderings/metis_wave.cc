// metis-wave: metis's cache-sized parts and part order, with a wavefront inside each part that
// continues from the parts placed before it.
//
// `metis` lays each part out by a BFS from its lowest id, wherever in the part that vertex lies,
// so a part's first vertices are rarely the ones next to the part before it. Here (issue 24 (b)):
//  1. Parts: METIS k-way parts sized to a cache (metis-wave:BYTES, default 256 KiB = the paper's
//     L2), seeded as metis's (the same parts for the same seed); ordered as metis orders them, by
//     a BFS over the part graph from vertex 0's part, neighbour parts by increasing number, further
//     components from the lowest unvisited part.
//  2. Inside a part: its seeds are its vertices with a neighbour already placed, by the earliest
//     position of such a neighbour (ties by id); a BFS restricted to the part starts from all of
//     them at once (a multi-source wave, neighbours by increasing id). Vertices it cannot reach
//     (the first part of a component, or a piece of a part cut off inside it) start their own BFS,
//     lowest id first.
// One part (a mesh whose data fit BYTES): plain BFS.
#include <algorithm>
#include <utility>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"

namespace meshreuse {

std::vector<int32_t> orderings::WaveThroughParts(const Mesh& m, const std::vector<int32_t>& part,
                                                 int32_t parts) {
  const int32_t n = m.NumVertices();
  const PartLayout l = LayOutParts(m, part, parts);
  const std::vector<int64_t>& first = l.first;
  const std::vector<int32_t>& members = l.members;

  std::vector<int32_t> order;
  order.reserve(n);
  std::vector<int32_t> pos(n, -1);
  std::vector<std::pair<int32_t, int32_t>> seeds;  // (earliest placed neighbour, id)
  auto place = [&](int32_t v) {
    pos[v] = static_cast<int32_t>(order.size());
    order.push_back(v);
  };
  auto wave = [&](size_t head, int32_t p) {  // BFS inside p from order[head..]
    for (; head < order.size(); ++head)
      for (const int32_t* q = m.v2v.RowBegin(order[head]); q != m.v2v.RowEnd(order[head]); ++q)
        if (pos[*q] < 0 && part[*q] == p) place(*q);
  };
  for (int32_t p : l.order) {
    seeds.clear();
    for (int64_t i = first[p]; i < first[p + 1]; ++i) {
      const int32_t v = members[i];
      int32_t earliest = -1;
      for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
        if (pos[*q] >= 0 && (earliest < 0 || pos[*q] < earliest)) earliest = pos[*q];
      if (earliest >= 0) seeds.emplace_back(earliest, v);
    }
    std::sort(seeds.begin(), seeds.end());
    const size_t head = order.size();
    for (const auto& s : seeds) place(s.second);
    wave(head, p);
    for (int64_t i = first[p]; i < first[p + 1]; ++i)
      if (pos[members[i]] < 0) {
        const size_t h = order.size();
        place(members[i]);
        wave(h, p);
      }
  }
  return order;
}

Permutation OrderMetisWave(const Mesh& m, const OrderingContext& ctx) {
  int32_t parts = 1;
  const std::vector<int32_t> part = orderings::CacheSizedParts(
      m, orderings::ParseCacheBytes(ctx.argument, 256 * 1024, "metis-wave"), ctx.seed, &parts);
  if (part.empty()) return Permutation::FromNewToOld(orderings::BfsVisitOrder(m));
  return Permutation::FromNewToOld(orderings::WaveThroughParts(m, part, parts));
}

}  // namespace meshreuse
