// metis: cache-sized parts. METIS_PartGraphKway (Karypis and Kumar 1998) cuts the vertex graph into
// parts whose sweep data fit a cache level: parts = ceil(V * bytes per vertex / part bytes), where
// bytes per vertex is what the sweep reads per vertex on average (coordinates, both adjacency rows
// with their offsets, the triangles' corners, weights and qualities, the interior list) and part
// bytes is the argument (metis:BYTES, K/M suffixes allowed) or by default 256 KiB, the paper's L2.
// The parts are then ordered by a BFS over the part graph (from vertex 0's part, neighbour parts
// by increasing number, further components from the lowest unvisited part), and the vertices of
// each part by a BFS restricted to the part (from its lowest unvisited id, neighbours by id).
// Seeded through METIS_OPTION_SEED: deterministic. One part or fewer: plain BFS.
#include <algorithm>
#include <string>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"
#include "core/ranks/partition.h"

namespace meshreuse {

std::vector<int32_t> orderings::CacheSizedParts(const Mesh& m, uint64_t part_bytes, uint64_t seed,
                                                int32_t* parts) {
  const int32_t n = m.NumVertices();
  const double parts_wanted =
      n * orderings::SweepBytesPerVertex(m) / static_cast<double>(part_bytes);
  *parts = 1;
  if (parts_wanted <= 1 || n < 4) return {};
  *parts = static_cast<int32_t>(std::min<double>(parts_wanted + 0.999999, n / 2));
  return MetisParts(m, *parts, seed);
}

Permutation OrderMetis(const Mesh& m, const OrderingContext& ctx) {
  const int32_t n = m.NumVertices();
  int32_t nparts = 1;
  const std::vector<int32_t> part = orderings::CacheSizedParts(
      m, orderings::ParseCacheBytes(ctx.argument, 256 * 1024, "metis"), ctx.seed, &nparts);
  if (part.empty()) return Permutation::FromNewToOld(orderings::BfsVisitOrder(m));
  const orderings::PartLayout l = orderings::LayOutParts(m, part, nparts);
  // Vertices: a BFS inside each part.
  std::vector<int32_t> order;
  order.reserve(n);
  std::vector<uint8_t> seen(n, 0);
  for (int32_t p : l.order)
    for (int64_t i = l.first[p]; i < l.first[p + 1]; ++i) {
      const int32_t s = l.members[i];
      if (seen[s]) continue;
      seen[s] = 1;
      order.push_back(s);
      for (size_t h = order.size() - 1; h < order.size(); ++h)
        for (const int32_t* q = m.v2v.RowBegin(order[h]); q != m.v2v.RowEnd(order[h]); ++q)
          if (!seen[*q] && part[*q] == p) seen[*q] = 1, order.push_back(*q);
    }
  return Permutation::FromNewToOld(std::move(order));
}

}  // namespace meshreuse
