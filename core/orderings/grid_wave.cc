// grid-wave: metis-wave's layout on parts that cost nothing to find: the cells of a uniform grid.
//
// The race (reports/docs/results.md, issue 24) found that METIS's cache-sized parts, laid out by
// a wave that continues from the parts before them (metis-wave), are as fast as BFS on every
// mesh, where the same parts with a BFS from each part's lowest id (metis) are 5-22% slower; but
// METIS costs about 12 of the paper's ORI sweeps on carabiner. Here the parts are grid cells:
//  1. A grid over the bounding box, gx x gy cells of equal size, as near square as the box allows,
//     with gx * gy = ceil(n * bytes per vertex / BYTES) (grid-wave:BYTES, default 256 KiB = the
//     paper's L2): a cell holds about BYTES of sweep data where the mesh is uniform. A vertex's
//     cell is (floor((x - xmin) / (xmax - xmin) * gx), same for y), the last row and column closed.
//     Part number: cell row-major (y * gx + x). Empty cells are not parts.
//  2. The parts laid out as metis-wave lays out METIS's (orderings::WaveThroughParts: BFS over the
//     part graph from vertex 0's part, each part by a multi-source wave from its vertices next to
//     the parts already placed).
// One cell (a mesh whose data fit BYTES): plain BFS. O(n) besides the waves.
#include <algorithm>
#include <cmath>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"

namespace meshreuse {

std::vector<int32_t> orderings::GridParts(const Mesh& m, uint64_t part_bytes, int32_t* parts) {
  const int32_t n = m.NumVertices();
  *parts = 1;
  const double wanted = n * SweepBytesPerVertex(m) / static_cast<double>(part_bytes);
  if (wanted <= 1 || n < 4) return {};
  double xlo = m.xy[0], xhi = xlo, ylo = m.xy[1], yhi = ylo;
  for (int32_t v = 0; v < n; ++v) {
    xlo = std::min(xlo, m.xy[2 * v]), xhi = std::max(xhi, m.xy[2 * v]);
    ylo = std::min(ylo, m.xy[2 * v + 1]), yhi = std::max(yhi, m.xy[2 * v + 1]);
  }
  const double w = xhi - xlo, h = yhi - ylo;
  const double cells = std::min<double>(std::ceil(wanted), n);
  // gx / gy = w / h and gx * gy = cells, each at least 1.
  int64_t gx = 1, gy = 1;
  if (w > 0 && h > 0) {
    gx = std::clamp<int64_t>(std::llround(std::sqrt(cells * w / h)), 1, n);
    gy =
        std::clamp<int64_t>(static_cast<int64_t>(std::ceil(cells / static_cast<double>(gx))), 1, n);
  } else if (w > 0) {
    gx = static_cast<int64_t>(cells);
  } else if (h > 0) {
    gy = static_cast<int64_t>(cells);
  }
  auto index = [](double v, double lo, double extent, int64_t g) {
    if (!(extent > 0)) return int64_t{0};
    return std::clamp<int64_t>(static_cast<int64_t>((v - lo) / extent * static_cast<double>(g)), 0,
                               g - 1);
  };
  std::vector<int64_t> cell(n);
  for (int32_t v = 0; v < n; ++v)
    cell[v] = index(m.xy[2 * v + 1], ylo, h, gy) * gx + index(m.xy[2 * v], xlo, w, gx);
  // Non-empty cells, numbered in row-major order (gx * gy is about n / 4000: a small table).
  std::vector<int32_t> number(static_cast<size_t>(gx * gy), -1);
  for (int32_t v = 0; v < n; ++v) number[cell[v]] = 0;
  int32_t used = 0;
  for (int32_t& k : number)
    if (k == 0) k = used++;
  std::vector<int32_t> part(n);
  for (int32_t v = 0; v < n; ++v) part[v] = number[cell[v]];
  *parts = used;
  if (*parts <= 1) return {};
  return part;
}

Permutation OrderGridWave(const Mesh& m, const OrderingContext& ctx) {
  int32_t parts = 1;
  const std::vector<int32_t> part = orderings::GridParts(
      m, orderings::ParseCacheBytes(ctx.argument, 256 * 1024, "grid-wave"), &parts);
  if (part.empty()) return Permutation::FromNewToOld(orderings::BfsVisitOrder(m));
  return Permutation::FromNewToOld(orderings::WaveThroughParts(m, part, parts));
}

}  // namespace meshreuse
