// Cache models driven by reuse distances (DESIGN.md "Miss model", "Inverse model", "Cost model").
// Miss model (fully associative LRU): an access misses a level of capacity C (elements or lines)
// iff it is cold or its reuse distance is >= C. Inverse model (the paper's Table 3): given n
// misses at a level, the capacity that explains them is the reuse distance of the n-th largest
// access (cold accesses count as the largest; if n <= cold no finite capacity explains them).
// Cost model (the paper's equation 2): (m1 c2 + m1 m2 c3 + m1 m2 m3 cm) * accesses, where m1 is the
// L1 miss rate and m2, m3 the local miss rates of L2 and L3, which reduces to
// L1 misses * c2 + L2 misses * c3 + L3 misses * cm; for n levels, the sum over levels of its
// misses times the next level's latency (memory's after the last).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/reuse_histogram.h"

namespace meshreuse {

// How a set chooses its victim: least recently used (the default; valgrind's and the paper's
// model), first in first out (hits do not refresh a line), or a seeded pseudo-random way.
enum class Replacement { kLru, kFifo, kRandom };
const char* ReplacementName(Replacement r);

// Cycles to serve an access from a level (or memory), as a range (the paper gives L3 and memory
// latencies as ranges); unknown: NaN.
struct LatencyRange {
  double low = NAN, high = NAN;
  bool known() const { return std::isfinite(low) && std::isfinite(high); }
};

struct CacheLevel {
  CacheLevel() = default;
  CacheLevel(std::string n, uint64_t b, uint32_t w = 0, Replacement p = Replacement::kLru,
             LatencyRange l = {})
      : name(std::move(n)), bytes(b), ways(w), policy(p), latency(l) {}
  std::string name;
  uint64_t bytes = 0;
  uint32_t ways = 0;  // associativity for the simulator (cache_sim.h); 0: not given
  Replacement policy = Replacement::kLru;
  LatencyRange latency;  // of an access served here (a hit), for the cost model
};

// The levels from the closest (L1) out, and memory's latency.
struct CacheSpec {
  std::vector<CacheLevel> levels;
  LatencyRange memory;
  std::string text;  // as given, for tables and run.json
  // Every latency the cost model needs (levels 2..n and memory) is known.
  bool has_latencies() const;
};

// "westmere-ex" (the paper's machine: L1=32K/8,L2=256K/8@10,L3=24M/24@38-170,mem@175-290; the
// latencies of Molka et al. 2009 that the paper's equation 2 uses) or a list of levels, each
// NAME=SIZE[/WAYS[/POLICY]][@CYCLES[-CYCLES]], and optionally mem@CYCLES[-CYCLES]: K, M, G are
// powers of 1024; WAYS the associativity (the fully associative model ignores it, the simulator
// needs it); POLICY lru, fifo or random; CYCLES the latency of an access served there. Sizes
// above 1 GiB (and sums that overflow) are refused. Throws UsageError naming the bad part.
CacheSpec ParseCacheSpec(const std::string& spec);
inline constexpr uint64_t kMaxCacheBytes = uint64_t{1} << 30;

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
// A capacity as a table cell: "inf" for kInfiniteCapacity, else the count (times `scale`, with
// two decimals, where scale is not 1: e.g. thousands).
std::string CapacityCell(uint64_t c, double scale = 1.0);

struct CostRange {
  double low, high;  // additional cycles
};
// The paper's equation 2 for any number of levels: the misses of level i are served by level i+1
// (memory after the last), each at that level's latency. `misses` per level, in level order.
// Nothing (nullopt) when a needed latency is unknown: callers say so rather than drop columns.
std::optional<CostRange> AdditionalCycles(const std::vector<uint64_t>& misses,
                                          const CacheSpec& spec);

}  // namespace meshreuse
