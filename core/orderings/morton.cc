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

uint64_t MortonIndex(uint32_t x, uint32_t y) { return Spread(x) | (Spread(y) << 1); }

}  // namespace

Permutation OrderMorton(const Mesh& m, const OrderingContext&) {
  return Permutation::FromNewToOld(orderings::SortAlongCurve(m, MortonIndex));
}

}  // namespace meshreuse
