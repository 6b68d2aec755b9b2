// rdr: Reuse Distance Reducing ordering, Algorithm 2 of Aupy, Park, Raghavan, line by line:
//   for i in interior vertices by increasing quality:
//     if not processed[i]:
//       if not sorted[i]: append i
//       processed[i] = true
//       l = unprocessed neighbours of i by increasing quality
//       while l is not empty:
//         append every vertex of l not yet sorted, in l's order
//         processed[l[0]] = true
//         l = unprocessed neighbours of l[0] by increasing quality
// Quality is the initial vertex quality (quality.h). Ties break by the original vertex id (the
// sorts are stable over id order), so the result is deterministic. "Neighbours" are all mesh
// neighbours, boundary ones included, as the paper writes it: the chain may pass through boundary
// vertices. Theorem 1 says every vertex is ordered once; that holds for vertices reachable this
// way. A vertex the algorithm never reaches -- one whose neighbours are all boundary vertices
// that no chain visits, e.g. in a component without interior vertices -- is appended at the end,
// in id order, so the result is always a permutation.
#include "core/orderings/rdr.h"

#include <algorithm>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"
#include "core/quality.h"

namespace meshreuse {

Permutation RdrOrder(const Mesh& m, const std::vector<double>& quality, RdrChains* chains) {
  const int32_t n = m.NumVertices();
  const int64_t* off = m.v2v.off.data();
  const int32_t* idx = m.v2v.idx.data();
  // Byte flags: 2 x V bytes stay in L2, so the chain's misses are the rows alone.
  std::vector<uint8_t> processed(n, 0), sorted(n, 0);
  std::vector<int32_t> order;
  order.reserve(n);
  // "Unprocessed neighbours of head by increasing quality" is sorted when head is processed, over
  // those neighbours only (each row once, at most a few dozen entries): no pass sorts every row.
  // Ties by id: rows are in increasing id and the insertion sort is stable.
  std::vector<std::pair<double, int32_t>> l;
  for (const int32_t i :
       orderings::StableSortByKey({m.interior.begin(), m.interior.end()}, quality)) {
    if (order.size() == static_cast<size_t>(n)) break;  // every vertex placed: nothing can change
    if (processed[i]) continue;
    const size_t chain_start = order.size();
    if (!sorted[i]) {
      order.push_back(i);
      sorted[i] = 1;
    }
    int32_t head = i;
    while (true) {
      processed[head] = 1;
      l.clear();
      const bool hub = off[head + 1] - off[head] > 32;  // sorted once below, O(d log d)
      for (const int32_t* p = idx + off[head]; p != idx + off[head + 1]; ++p) {
        const int32_t u = *p;
        if (processed[u]) continue;
        __builtin_prefetch(idx + off[u]);  // a candidate for the chain's next row
        const double qu = quality[u];
        if (hub) {
          l.emplace_back(qu, u);
          continue;
        }
        size_t k = l.size();
        l.emplace_back();
        for (; k > 0 && l[k - 1].first > qu; --k) l[k] = l[k - 1];
        l[k] = {qu, u};
      }
      if (hub)  // stable by quality: ties keep the row's increasing ids
        std::stable_sort(l.begin(), l.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
      if (l.empty()) break;
      for (const auto& e : l)
        if (!sorted[e.second]) {
          order.push_back(e.second);
          sorted[e.second] = 1;
        }
      head = l[0].second;
    }
    if (chains) chains->placed.push_back(static_cast<int64_t>(order.size() - chain_start));
  }
  for (int32_t v = 0; v < n && order.size() < static_cast<size_t>(n); ++v)
    if (!sorted[v]) order.push_back(v);  // never reached (see the file comment)
  return Permutation::FromNewToOld(std::move(order));
}

Permutation OrderRdr(const Mesh& m, const OrderingContext&) {
  return RdrOrder(m, VertexQualities(m));
}

}  // namespace meshreuse
