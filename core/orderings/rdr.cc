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

#include "core/orderings/common.h"
#include "core/orderings/registry.h"
#include "core/quality.h"

namespace meshreuse {

Permutation RdrOrder(const Mesh& m, const std::vector<double>& quality) {
  const int32_t n = m.NumVertices();
  // Each neighbour row sorted once by (quality, id): then "unprocessed neighbours of v by
  // increasing quality" is row v with the processed ones skipped, and no sort runs in the chain.
  const std::vector<int32_t> nbr = orderings::RowsByKey(m, quality);
  const int64_t* off = m.v2v.off.data();
  // Byte flags: 2 x V bytes stay in L2, so the chain's misses are the rows alone.
  std::vector<uint8_t> processed(n, 0), sorted(n, 0);
  std::vector<int32_t> order;
  order.reserve(n);
  for (const int32_t i :
       orderings::StableSortByKey({m.interior.begin(), m.interior.end()}, quality)) {
    if (processed[i]) continue;
    if (!sorted[i]) {
      order.push_back(i);
      sorted[i] = 1;
    }
    // head = i, then l[0] of each l: process head, l = its unprocessed neighbours by quality,
    // append the unsorted ones of l, continue from l[0]; stop when l is empty.
    int32_t head = i;
    while (true) {
      processed[head] = 1;
      int32_t next = -1;
      for (const int32_t* p = nbr.data() + off[head]; p != nbr.data() + off[head + 1]; ++p) {
        const int32_t u = *p;
        if (processed[u]) continue;
        if (next < 0) next = u;
        __builtin_prefetch(off + u);  // the chain's next row offset, before it is needed
        if (!sorted[u]) {
          order.push_back(u);
          sorted[u] = 1;
        }
      }
      if (next < 0) break;
      head = next;
    }
  }
  for (int32_t v = 0; v < n; ++v)  // never reached (see the file comment)
    if (!sorted[v]) order.push_back(v);
  return Permutation::FromNewToOld(std::move(order));
}

Permutation OrderRdr(const Mesh& m, const OrderingContext&) {
  return RdrOrder(m, VertexQualities(m));
}

}  // namespace meshreuse
