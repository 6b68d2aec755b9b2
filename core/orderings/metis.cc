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

#include "core/error.h"
#include "core/orderings/common.h"
#include "core/orderings/metis_graph.h"
#include "core/orderings/registry.h"
#include "core/stdout_guard.h"

namespace meshreuse {

std::vector<int32_t> orderings::CacheSizedParts(const Mesh& m, uint64_t part_bytes, uint64_t seed,
                                                int32_t* parts) {
  const int32_t n = m.NumVertices();
  const double parts_wanted =
      n * orderings::SweepBytesPerVertex(m) / static_cast<double>(part_bytes);
  *parts = 1;
  if (parts_wanted <= 1 || n < 4) return {};
  orderings::MetisGraph g = orderings::ToMetis(m);
  idx_t ncon = 1, nparts = static_cast<idx_t>(std::min<double>(parts_wanted + 0.999999, n / 2));
  idx_t cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = static_cast<idx_t>(seed & 0x7FFFFFFF);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(n);
  {
    const StdoutToStderr quiet;  // METIS may printf: stdout holds only results
    orderings::MetisCheck(
        METIS_PartGraphKway(&g.n, &ncon, g.xadj.data(), g.adjncy.data(), nullptr, nullptr, nullptr,
                            &nparts, nullptr, nullptr, options, &cut, part.data()),
        "METIS_PartGraphKway");
  }
  *parts = static_cast<int32_t>(nparts);
  return std::vector<int32_t>(part.begin(), part.end());
}

Permutation OrderMetis(const Mesh& m, const OrderingContext& ctx) {
  const int32_t n = m.NumVertices();
  int32_t nparts = 1;
  const std::vector<int32_t> part = orderings::CacheSizedParts(
      m, orderings::ParseCacheBytes(ctx.argument, 256 * 1024, "metis"), ctx.seed, &nparts);
  if (part.empty()) return Permutation::FromNewToOld(orderings::BfsVisitOrder(m));
  // Vertices by part (ascending id within each), and the part graph's neighbour sets.
  std::vector<int64_t> first(nparts + 1, 0);
  for (int32_t v = 0; v < n; ++v) ++first[part[v] + 1];
  for (int32_t p = 0; p < nparts; ++p) first[p + 1] += first[p];
  std::vector<int32_t> members(n);
  {
    std::vector<int64_t> at(first.begin(), first.end() - 1);
    for (int32_t v = 0; v < n; ++v) members[at[part[v]]++] = v;
  }
  std::vector<std::vector<int32_t>> pnbr(nparts);
  for (int32_t v = 0; v < n; ++v)
    for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
      if (part[*q] != part[v]) pnbr[part[v]].push_back(part[*q]);
  for (auto& r : pnbr) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  // Parts in BFS order over the part graph.
  std::vector<int32_t> porder;
  std::vector<uint8_t> pseen(nparts, 0);
  auto part_bfs = [&](int32_t s) {
    pseen[s] = 1;
    porder.push_back(s);
    for (size_t h = porder.size() - 1; h < porder.size(); ++h)
      for (int32_t q : pnbr[porder[h]])
        if (!pseen[q]) pseen[q] = 1, porder.push_back(q);
  };
  part_bfs(part[0]);
  for (int32_t p = 0; p < nparts; ++p)
    if (!pseen[p]) part_bfs(p);
  // Vertices: a BFS inside each part.
  std::vector<int32_t> order;
  order.reserve(n);
  std::vector<uint8_t> seen(n, 0);
  for (int32_t p : porder)
    for (int64_t i = first[p]; i < first[p + 1]; ++i) {
      const int32_t s = members[i];
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
