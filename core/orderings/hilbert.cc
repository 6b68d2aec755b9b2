// hilbert: vertices sorted by their index along a Hilbert curve of order 16 laid over the mesh's
// bounding box (each axis scaled to 0..65535 independently); ties by id. The classic xy -> d
// conversion (Hilbert 1891; as in Warren, "Hacker's Delight", 16-3).
#include <algorithm>
#include <cmath>

#include "core/orderings/common.h"
#include "core/orderings/registry.h"

namespace meshreuse {

namespace {

uint64_t HilbertIndex(uint32_t x, uint32_t y) {
  constexpr uint32_t n = 1u << 16;
  uint64_t d = 0;
  for (uint32_t s = n / 2; s > 0; s /= 2) {
    const uint32_t rx = (x & s) ? 1 : 0;
    const uint32_t ry = (y & s) ? 1 : 0;
    d += uint64_t{s} * s * ((3 * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant so the curve continues
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

}  // namespace

Permutation OrderHilbert(const Mesh& m, const OrderingContext&) {
  const int32_t n = m.NumVertices();
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int32_t v = 0; v < n; ++v) {
    x0 = std::min(x0, m.xy[2 * int64_t{v}]), x1 = std::max(x1, m.xy[2 * int64_t{v}]);
    y0 = std::min(y0, m.xy[2 * int64_t{v} + 1]), y1 = std::max(y1, m.xy[2 * int64_t{v} + 1]);
  }
  const double sx = x1 > x0 ? 65535.0 / (x1 - x0) : 0.0;
  const double sy = y1 > y0 ? 65535.0 / (y1 - y0) : 0.0;
  std::vector<double> key(n);  // d < 2^32 is exact in a double
  std::vector<int32_t> ids(n);
  for (int32_t v = 0; v < n; ++v) {
    const auto gx =
        static_cast<uint32_t>(std::clamp((m.xy[2 * int64_t{v}] - x0) * sx, 0.0, 65535.0));
    const auto gy =
        static_cast<uint32_t>(std::clamp((m.xy[2 * int64_t{v} + 1] - y0) * sy, 0.0, 65535.0));
    key[v] = static_cast<double>(HilbertIndex(gx, gy));
    ids[v] = v;
  }
  return Permutation::FromNewToOld(orderings::StableSortByKey(ids, key));
}

}  // namespace meshreuse
