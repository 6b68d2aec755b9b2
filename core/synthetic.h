// A built-in mesh generator for tests (no external program): a jittered, graded grid of cells, each
// split into two triangles along a random diagonal, with circular holes cut out. Random column
// widths and row heights (graded) make thin, poor-quality triangles; holes make inner boundaries,
// vertices shared by two cells only at a corner, and boundary vertices with no interior neighbour.
// Invariant: every triangle keeps positive area, because each vertex moves by at most
// jitter * (the smaller adjacent cell size) per axis and jitter is capped at 0.24 (< 1/4, the
// bound that keeps a right triangle's orientation under independent moves of its corners).
// Deterministic for a seed on every platform (SplitMix64, no std distributions).
#pragma once

#include <cstdint>

#include "core/mesh.h"

namespace meshreuse {

struct SyntheticOptions {
  int nx = 16;          // cells across
  int ny = 12;          // cells down
  double jitter = 0.2;  // fraction of the local cell size, capped at 0.24
  int holes = 1;        // circular holes
  bool graded = true;   // random column widths and row heights in [0.15, 1]
  uint64_t seed = 1;
};

RawMesh MakeSyntheticMesh(const SyntheticOptions& opt);

// SplitMix64 (Steele, Lea, Flood 2014): small, fast, and the same sequence everywhere.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : s_(seed) {}
  uint64_t Next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }  // [0, 1)
  uint64_t Below(uint64_t n) { return Next() % n; }  // slight bias is irrelevant here

 private:
  uint64_t s_;
};

}  // namespace meshreuse
