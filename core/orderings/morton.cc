// morton: vertices sorted by their Z-order (Morton) index -- the bits of the x and y grid
// coordinates interleaved -- over a 2^16 x 2^16 grid of the bounding box (each axis scaled
// independently, as hilbert.cc); ties by id. The cheap sibling of the Hilbert curve: no rotations,
// but jumps at every power-of-two boundary (Morton 1966).
#include <algorithm>
#include <cmath>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"

namespace meshreuse {

namespace {

uint64_t Spread(uint32_t x) {  // bit i of x to bit 2i
  uint64_t v = x;
  v = (v | (v << 16)) & 0x0000FFFF0000FFFFull;
  v = (v | (v << 8)) & 0x00FF00FF00FF00FFull;
  v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0Full;
  v = (v | (v << 2)) & 0x3333333333333333ull;
  v = (v | (v << 1)) & 0x5555555555555555ull;
  return v;
}

}  // namespace

uint64_t MortonIndex(uint32_t x, uint32_t y) { return Spread(x) | (Spread(y) << 1); }

Permutation OrderMorton(const Mesh& m, const OrderingContext&) {
  const int32_t n = m.NumVertices();
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int32_t v = 0; v < n; ++v) {
    x0 = std::min(x0, m.xy[2 * int64_t{v}]), x1 = std::max(x1, m.xy[2 * int64_t{v}]);
    y0 = std::min(y0, m.xy[2 * int64_t{v} + 1]), y1 = std::max(y1, m.xy[2 * int64_t{v} + 1]);
  }
  const double sx = x1 > x0 ? 65535.0 / (x1 - x0) : 0.0;
  const double sy = y1 > y0 ? 65535.0 / (y1 - y0) : 0.0;
  std::vector<double> key(n);  // the index < 2^32 is exact in a double
  std::vector<int32_t> ids(n);
  for (int32_t v = 0; v < n; ++v) {
    const auto gx =
        static_cast<uint32_t>(std::clamp((m.xy[2 * int64_t{v}] - x0) * sx, 0.0, 65535.0));
    const auto gy =
        static_cast<uint32_t>(std::clamp((m.xy[2 * int64_t{v} + 1] - y0) * sy, 0.0, 65535.0));
    key[v] = static_cast<double>(MortonIndex(gx, gy));
    ids[v] = v;
  }
  return Permutation::FromNewToOld(orderings::StableSortByKey(ids, key));
}

}  // namespace meshreuse
