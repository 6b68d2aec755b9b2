// The SplitMix64 finaliser (Steele, Lea and Flood 2014): a fast bijective mix of 64 bits, the hash
// of every open-addressing table and set index here (consecutive ids and line numbers spread).
#pragma once

#include <cstdint>

namespace meshreuse {

inline uint64_t Mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace meshreuse
