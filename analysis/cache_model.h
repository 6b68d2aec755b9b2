// Cache models driven by reuse distances (DESIGN.md "Miss model", "Inverse model", "Cost model").
// Miss model (fully associative LRU): an access misses a level of capacity C (elements or lines)
// iff it is cold or its reuse distance is >= C. Inverse model (the paper's Table 3): given n
// misses at a level, the capacity that explains them is the reuse distance of the n-th largest
// access (cold accesses count as the largest; if n <= cold no finite capacity explains them).
// Cost model (the paper's equation 2): (m1 c2 + m1 m2 c3 + m1 m2 m3 cm) * accesses, where m1 is the
// L1 miss rate and m2, m3 the local miss rates of L2 and L3, which reduces to
// L1 misses * c2 + L2 misses * c3 + L3 misses * cm.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/reuse_histogram.h"

namespace meshreuse {

struct CacheLevel {
  std::string name;
  uint64_t bytes;
  uint32_t ways = 0;  // associativity for the simulator (cache_sim.h); 0: not given
};

// "westmere-ex" (the paper's machine: L1=32K/8,L2=256K/8,L3=24M/24) or a list such as
// "L1=32K,L2=256K,L3=24M" or "L1=32K/8,L2=256K/8,L3=24M/24" (K, M, G are powers of 1024; /W the
// ways, which the fully associative model ignores and the simulator needs). Throws
// std::invalid_argument naming the bad part.
std::vector<CacheLevel> ParseCacheSpec(const std::string& spec);

struct LevelMisses {
  std::string name;
  uint64_t capacity;  // in elements (or lines)
  uint64_t misses;
  double rate;  // misses / accesses
};

// unit_bytes: the element size (66 by default) or the line size (64).
std::vector<LevelMisses> ModelMisses(const ReuseHistogram& h, const std::vector<CacheLevel>& levels,
                                     uint64_t unit_bytes);

// The capacity (in elements or lines) that n misses imply; kInfinite when n <= cold accesses,
// 0 when n exceeds all accesses.
inline constexpr uint64_t kInfiniteCapacity = ~uint64_t{0};
// exclude_cold: the cold accesses are compulsory misses at any capacity, so n misses leave n - cold
// to explain by capacity; n <= cold then means every reuse hits (the largest distance + 1) instead
// of kInfiniteCapacity. (The paper subtracts the misses it attributes to other causes before it
// inverts; cold misses are the part our traces can name.)
uint64_t CapacityForMisses(const ReuseHistogram& h, uint64_t n, bool exclude_cold = false);

struct Latencies {  // cycles; the paper's Westmere-EX (Molka et al. 2009)
  double l2 = 10, l3_low = 38, l3_high = 170, mem_low = 175, mem_high = 290;
};
struct CostRange {
  double low, high;  // additional cycles
};
// levels: the L1, L2, L3 misses (exactly three).
CostRange AdditionalCycles(const std::vector<LevelMisses>& levels, const Latencies& lat = {});

}  // namespace meshreuse
