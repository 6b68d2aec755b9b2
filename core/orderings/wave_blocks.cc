// wave-blocks: a BFS wavefront cut into cache-sized blocks, each laid out by a local BFS.
//
// Why: BFS keeps a sweep's working set to about three levels, so on meshes larger than the caches
// it loads each line once per sweep at L2 and L3 (the compulsory floor; reports/docs/results.md),
// but a vertex's neighbours in the next and previous levels lie a whole level (hundreds of
// vertices, tens of KiB) away in the order: past L1. Space-filling curves and cache-sized METIS
// parts have the L1 locality and lose the L2 floor. Here the wavefront is kept at the scale of L2
// and blocked at the scale of L1.
//
// Definition (S = block vertices, B = band vertices; wave-blocks:BLOCK[/BAND] in bytes gives S =
// BLOCK / the sweep's bytes per vertex, default 32 KiB = L1, and B = BAND / the same, default
// 4 x BLOCK, so that two bands fit the paper's 256 KiB L2; a larger L2 takes a larger BAND):
//  1. BFS exactly as `bfs` (from vertex 0, neighbours by increasing id, each further component
//     from its lowest unvisited id); each vertex's parent is the vertex that enqueued it, its level
//     its distance from its component's root. A level is a maximal run of the BFS order with one
//     component and one distance.
//  2. Bands: the levels in BFS order grouped greedily; a band takes the next level while its
//     vertex count stays within B (always at least one level); a component's root starts a band.
//  3. Blocks: with h the band's number of levels and w = ceil(S / h), the band's first level is cut
//     into arcs of w consecutive vertices (arc = index in the level / w); every other vertex of the
//     band takes its parent's arc (its parent lies one level up, in the same band).
//  4. Order: bands in BFS order; inside a band, by arc; inside an arc (a block of about h x w = S
//     vertices), in BFS order (level by level: a local BFS).
// Within a block a neighbour in the next level is about w vertices on (L1); across blocks of a
// band, a block; across bands, about a band (L2). With S >= n one band and one arc: plain BFS.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/orderings/common.h"
#include "core/orderings/registry.h"

namespace meshreuse {

std::vector<int32_t> orderings::WaveBlocksOrder(const Mesh& m, int64_t block, int64_t band) {
  const int32_t n = m.NumVertices();
  block = std::max<int64_t>(block, 1);
  band = std::max<int64_t>(band, 1);
  // 1. BFS with parents; a vertex's level is its parent's plus one (parents come first).
  std::vector<int32_t> parent, depth(n, 0);
  const std::vector<int32_t> bfs = BfsVisitOrder(m, &parent);
  for (int32_t v : bfs)
    if (parent[v] >= 0) depth[v] = depth[parent[v]] + 1;
  // Level starts in the BFS order (a root, or a change of depth), and n at the end.
  std::vector<int64_t> level;
  for (int32_t i = 0; i < n; ++i)
    if (i == 0 || parent[bfs[i]] < 0 || depth[bfs[i]] != depth[bfs[i - 1]]) level.push_back(i);
  level.push_back(n);
  // 2-4. Bands, arcs, and the order.
  std::vector<int32_t> order, arc(n, 0);
  order.reserve(n);
  std::vector<int64_t> count;
  for (size_t l = 0; l + 1 < level.size();) {
    size_t e = l + 1;  // the band is levels [l, e)
    while (e + 1 < level.size() && parent[bfs[level[e]]] >= 0 && level[e + 1] - level[l] <= band)
      ++e;
    const int64_t h = static_cast<int64_t>(e - l);
    const int64_t w = (block + h - 1) / h;
    const int64_t lo = level[l], hi = level[e];
    for (int64_t i = lo; i < hi; ++i) {
      const int32_t v = bfs[i];
      arc[v] = i < level[l + 1] ? static_cast<int32_t>((i - lo) / w) : arc[parent[v]];
    }
    // A stable counting sort of the band by arc.
    const int32_t arcs = static_cast<int32_t>((level[l + 1] - lo + w - 1) / w);
    count.assign(arcs + 1, 0);
    for (int64_t i = lo; i < hi; ++i) ++count[arc[bfs[i]] + 1];
    for (int32_t a = 0; a < arcs; ++a) count[a + 1] += count[a];
    order.resize(hi);
    for (int64_t i = lo; i < hi; ++i) order[lo + count[arc[bfs[i]]]++] = bfs[i];
    l = e;
  }
  return order;
}

std::pair<uint64_t, uint64_t> orderings::ParseWaveBlocks(const std::string& arg) {
  const size_t slash = arg.find('/');
  const uint64_t block = ParseCacheBytes(arg.substr(0, slash), 32 * 1024, "wave-blocks");
  if (slash == std::string::npos) return {block, 4 * block};
  if (slash == 0) throw UsageError("wave-blocks:BLOCK/BAND needs BLOCK, not '" + arg + "'");
  const uint64_t band = ParseCacheBytes(arg.substr(slash + 1), 0, "wave-blocks");
  if (band == 0 || band < block)
    throw UsageError("wave-blocks:BLOCK/BAND needs BAND at least BLOCK, not '" + arg + "'");
  return {block, band};
}

Permutation OrderWaveBlocks(const Mesh& m, const OrderingContext& ctx) {
  const auto [block_bytes, band_bytes] = orderings::ParseWaveBlocks(ctx.argument);
  const double per_vertex = std::max(orderings::SweepBytesPerVertex(m), 1.0);
  auto vertices = [&](uint64_t bytes) {
    return std::max<int64_t>(1, std::llround(static_cast<double>(bytes) / per_vertex));
  };
  return Permutation::FromNewToOld(
      orderings::WaveBlocksOrder(m, vertices(block_bytes), vertices(band_bytes)));
}

}  // namespace meshreuse
