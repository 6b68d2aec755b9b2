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
  return Permutation::FromNewToOld(orderings::SortAlongCurve(m, HilbertIndex));
}

}  // namespace meshreuse
