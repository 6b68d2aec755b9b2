// Cache models; see cache_model.h.
#include "analysis/cache_model.h"

#include <cctype>
#include <sstream>
#include <stdexcept>

namespace meshreuse {

std::vector<CacheLevel> ParseCacheSpec(const std::string& spec) {
  if (spec == "westmere-ex" || spec == "westmere")
    return {{"L1", 32 << 10, 8}, {"L2", 256 << 10, 8}, {"L3", 24 << 20, 24}};
  std::vector<CacheLevel> levels;
  std::stringstream ss(spec);
  for (std::string part; std::getline(ss, part, ',');) {
    const size_t eq = part.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == part.size())
      throw std::invalid_argument("cache level '" + part + "' should read NAME=SIZE, e.g. L1=32K");
    std::string size = part.substr(eq + 1);
    uint32_t ways = 0;
    if (const size_t slash = size.find('/'); slash != std::string::npos) {
      const std::string w = size.substr(slash + 1);
      if (w.empty() || w.size() > 6 || w.find_first_not_of("0123456789") != std::string::npos ||
          std::stoul(w) == 0)
        throw std::invalid_argument("associativity '" + w + "' in '" + part +
                                    "' is not a positive number of ways");
      ways = static_cast<uint32_t>(std::stoul(w));
      size = size.substr(0, slash);
      if (size.empty()) throw std::invalid_argument("cache level '" + part + "' has no size");
    }
    uint64_t mult = 1;
    const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(size.back())));
    if (u == 'K' || u == 'M' || u == 'G') {
      mult = u == 'K' ? 1ull << 10 : u == 'M' ? 1ull << 20 : 1ull << 30;
      size.pop_back();
    }
    if (size.empty() || size.size() > 12 ||
        size.find_first_not_of("0123456789") != std::string::npos)
      throw std::invalid_argument("cache size '" + part.substr(eq + 1) +
                                  "' is not a number with K, M or G");
    const uint64_t bytes = std::stoull(size) * mult;
    if (bytes == 0) throw std::invalid_argument("cache level '" + part + "' has size 0");
    levels.push_back({part.substr(0, eq), bytes, ways});
  }
  if (levels.empty()) throw std::invalid_argument("empty cache specification");
  return levels;
}

std::vector<LevelMisses> ModelMisses(const ReuseHistogram& h, const std::vector<CacheLevel>& levels,
                                     uint64_t unit_bytes) {
  std::vector<LevelMisses> out;
  for (const CacheLevel& l : levels) {
    const uint64_t cap = l.bytes / unit_bytes;
    const uint64_t misses = h.cold() + h.CountAtLeast(cap);
    out.push_back(
        {l.name, cap, misses,
         h.accesses() ? static_cast<double>(misses) / static_cast<double>(h.accesses()) : 0.0});
  }
  return out;
}

uint64_t CapacityForMisses(const ReuseHistogram& h, uint64_t n, bool exclude_cold) {
  if (n == 0 || (exclude_cold && n <= h.cold()))  // anything above the largest distance
    return h.finite() ? h.max() + 1 : 0;
  if (n <= h.cold()) return kInfiniteCapacity;
  if (n > h.accesses()) return 0;
  uint64_t seen = h.cold();
  const std::vector<uint64_t>& c = h.counts();
  for (size_t d = c.size(); d > 0; --d) {
    seen += c[d - 1];
    if (seen >= n) return d - 1;
  }
  return 0;
}

CostRange AdditionalCycles(const std::vector<LevelMisses>& l, const Latencies& lat) {
  if (l.size() != 3) throw std::invalid_argument("the cost model needs L1, L2 and L3");
  const double m1 = static_cast<double>(l[0].misses), m2 = static_cast<double>(l[1].misses),
               m3 = static_cast<double>(l[2].misses);
  return {m1 * lat.l2 + m2 * lat.l3_low + m3 * lat.mem_low,
          m1 * lat.l2 + m2 * lat.l3_high + m3 * lat.mem_high};
}

}  // namespace meshreuse
