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
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/orderings/common.h"
#include "core/orderings/metis_graph.h"
#include "core/orderings/registry.h"
#include "core/stdout_guard.h"

namespace meshreuse {

uint64_t orderings::ParseMetisPartBytes(const std::string& arg) {
  if (arg.empty()) return 256 * 1024;
  size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(arg, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  uint64_t mult = 1;
  if (used + 1 == arg.size() && (arg[used] == 'K' || arg[used] == 'k')) mult = 1024, ++used;
  if (used + 1 == arg.size() && (arg[used] == 'M' || arg[used] == 'm')) mult = 1 << 20, ++used;
  if (used != arg.size() || v == 0 || v > (uint64_t{1} << 40) / mult)
    throw UsageError("metis:BYTES needs a positive size such as 262144 or 256K, not '" + arg + "'");
  return v * mult;
}

namespace {

// What the sweep reads per vertex on average: coordinates, both adjacency rows and their offsets,
// the triangles' corners, weights and qualities, the interior list.
double SweepBytesPerVertex(const Mesh& m) {
  const double v = m.NumVertices(), t = m.NumTriangles();
  const double bytes = 16 * v + 8 * (v + 1) + 4.0 * m.v2v.idx.size() + 8 * (v + 1) +
                       4.0 * m.v2t.idx.size() + 12 * t + 16 * t + 4.0 * m.interior.size();
  return v > 0 ? bytes / v : 0;
}

}  // namespace

Permutation OrderMetis(const Mesh& m, const OrderingContext& ctx) {
  const int32_t n = m.NumVertices();
  const uint64_t part_bytes = orderings::ParseMetisPartBytes(ctx.argument);
  const double parts_wanted = n * SweepBytesPerVertex(m) / static_cast<double>(part_bytes);
  if (parts_wanted <= 1 || n < 4) return Permutation::FromNewToOld(orderings::BfsVisitOrder(m));
  orderings::MetisGraph g = orderings::ToMetis(m);
  idx_t ncon = 1, nparts = static_cast<idx_t>(std::min<double>(parts_wanted + 0.999999, n / 2));
  idx_t cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = static_cast<idx_t>(ctx.seed & 0x7FFFFFFF);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(n);
  {
    const StdoutToStderr quiet;  // METIS may printf: stdout holds only results
    orderings::MetisCheck(
        METIS_PartGraphKway(&g.n, &ncon, g.xadj.data(), g.adjncy.data(), nullptr, nullptr, nullptr,
                            &nparts, nullptr, nullptr, options, &cut, part.data()),
        "METIS_PartGraphKway");
  }
  // Vertices by part (ascending id within each), and the part graph's neighbour sets.
  std::vector<int64_t> first(nparts + 1, 0);
  for (int32_t v = 0; v < n; ++v) ++first[part[v] + 1];
  for (idx_t p = 0; p < nparts; ++p) first[p + 1] += first[p];
  std::vector<int32_t> members(n);
  {
    std::vector<int64_t> at(first.begin(), first.end() - 1);
    for (int32_t v = 0; v < n; ++v) members[at[part[v]]++] = v;
  }
  std::vector<std::vector<idx_t>> pnbr(nparts);
  for (int32_t v = 0; v < n; ++v)
    for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
      if (part[*q] != part[v]) pnbr[part[v]].push_back(part[*q]);
  for (auto& r : pnbr) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  // Parts in BFS order over the part graph.
  std::vector<idx_t> porder;
  std::vector<uint8_t> pseen(nparts, 0);
  auto part_bfs = [&](idx_t s) {
    pseen[s] = 1;
    porder.push_back(s);
    for (size_t h = porder.size() - 1; h < porder.size(); ++h)
      for (idx_t q : pnbr[porder[h]])
        if (!pseen[q]) pseen[q] = 1, porder.push_back(q);
  };
  part_bfs(part[0]);
  for (idx_t p = 0; p < nparts; ++p)
    if (!pseen[p]) part_bfs(p);
  // Vertices: a BFS inside each part.
  std::vector<int32_t> order;
  order.reserve(n);
  std::vector<uint8_t> seen(n, 0);
  for (idx_t p : porder)
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
