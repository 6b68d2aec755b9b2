// Cache models; see cache_model.h.
#include "analysis/cache_model.h"

#include <cctype>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/table.h"

namespace meshreuse {

const char* ReplacementName(Replacement r) {
  return r == Replacement::kLru ? "lru" : r == Replacement::kFifo ? "fifo" : "random";
}

bool CacheSpec::has_latencies() const {
  for (size_t i = 1; i < levels.size(); ++i)
    if (!levels[i].latency.known()) return false;
  return memory.known();
}

namespace {

// "10" or "38-170": a latency range in cycles.
LatencyRange ParseLatency(const std::string& s, const std::string& part) {
  const size_t dash = s.find('-');
  auto num = [&](const std::string& x) {
    if (x.empty() || x.size() > 9 || x.find_first_not_of("0123456789.") != std::string::npos)
      throw UsageError("latency '" + s + "' in '" + part + "' is not CYCLES or LOW-HIGH");
    return std::stod(x);
  };
  LatencyRange r;
  r.low = num(s.substr(0, dash));
  r.high = dash == std::string::npos ? r.low : num(s.substr(dash + 1));
  if (r.high < r.low) throw UsageError("latency '" + s + "' in '" + part + "': LOW above HIGH");
  return r;
}

}  // namespace

CacheSpec ParseCacheSpec(const std::string& text) {
  CacheSpec spec;
  spec.text = text;
  if (text == "westmere-ex" || text == "westmere") {  // the alias is listed in every --help
    spec.text = "westmere-ex";
    spec.levels = {{"L1", 32 << 10, 8, Replacement::kLru, {4, 4}},
                   {"L2", 256 << 10, 8, Replacement::kLru, {10, 10}},
                   {"L3", 24 << 20, 24, Replacement::kLru, {38, 170}}};
    spec.memory = {175, 290};
    return spec;
  }
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, ',');) {
    std::string body = part;
    LatencyRange latency;
    if (const size_t at = body.find('@'); at != std::string::npos) {
      latency = ParseLatency(body.substr(at + 1), part);
      body = body.substr(0, at);
    }
    if (body == "mem" || body == "memory") {
      if (!latency.known()) throw UsageError("'" + part + "': memory takes only mem@CYCLES");
      spec.memory = latency;
      continue;
    }
    const size_t eq = body.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == body.size())
      throw UsageError("cache level '" + part + "' should read NAME=SIZE, e.g. L1=32K");
    std::string size = body.substr(eq + 1);
    uint32_t ways = 0;
    Replacement policy = Replacement::kLru;
    if (const size_t slash = size.find('/'); slash != std::string::npos) {
      std::string w = size.substr(slash + 1);
      if (const size_t s2 = w.find('/'); s2 != std::string::npos) {
        const std::string p = w.substr(s2 + 1);
        if (p == "lru")
          policy = Replacement::kLru;
        else if (p == "fifo")
          policy = Replacement::kFifo;
        else if (p == "random")
          policy = Replacement::kRandom;
        else
          throw UsageError("replacement '" + p + "' in '" + part + "' (lru, fifo or random)");
        w = w.substr(0, s2);
      }
      if (w.empty() || w.size() > 6 || w.find_first_not_of("0123456789") != std::string::npos ||
          std::stoul(w) == 0)
        throw UsageError("associativity '" + w + "' in '" + part +
                         "' is not a positive number of ways");
      ways = static_cast<uint32_t>(std::stoul(w));
      size = size.substr(0, slash);
      if (size.empty()) throw UsageError("cache level '" + part + "' has no size");
    }
    uint64_t mult = 1;
    const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(size.back())));
    if (u == 'K' || u == 'M' || u == 'G') {
      mult = u == 'K' ? 1ull << 10 : u == 'M' ? 1ull << 20 : 1ull << 30;
      size.pop_back();
    }
    if (size.empty() || size.size() > 12 ||
        size.find_first_not_of("0123456789") != std::string::npos)
      throw UsageError("cache size '" + body.substr(eq + 1) + "' is not a number with K, M or G");
    const uint64_t n = std::stoull(size);
    if (n > kMaxCacheBytes / mult)
      throw UsageError("cache level '" + part + "' is larger than 1 GiB, the largest simulated");
    const uint64_t bytes = n * mult;
    if (bytes == 0) throw UsageError("cache level '" + part + "' has size 0");
    spec.levels.push_back({body.substr(0, eq), bytes, ways, policy, latency});
  }
  if (spec.levels.empty()) throw UsageError("empty cache specification");
  if (spec.levels.size() > 8) throw UsageError("at most 8 cache levels");
  return spec;
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

std::string CapacityCell(uint64_t c, double scale) {
  if (c == kInfiniteCapacity) return "inf";
  return scale == 1.0 ? std::to_string(c) : Fixed(static_cast<double>(c) * scale, 2);
}

uint64_t CapacityForMisses(const ReuseHistogram& h, uint64_t n, bool exclude_cold) {
  if (n == 0 || (exclude_cold && n <= h.cold()))  // anything above the largest distance
    return h.finite() ? h.max() + 1 : 0;
  if (n <= h.cold()) return kInfiniteCapacity;
  if (n > h.accesses()) return 0;
  uint64_t seen = h.cold(), found = 0;
  h.ForEachDown([&](uint64_t d, uint64_t c) {
    seen += c;
    if (seen < n) return true;
    found = d;
    return false;
  });
  return found;
}

std::optional<CostRange> AdditionalCycles(const std::vector<uint64_t>& misses,
                                          const CacheSpec& spec) {
  if (misses.size() != spec.levels.size() || !spec.has_latencies()) return std::nullopt;
  CostRange c{0, 0};
  for (size_t i = 0; i < misses.size(); ++i) {
    const LatencyRange& next =
        i + 1 < spec.levels.size() ? spec.levels[i + 1].latency : spec.memory;
    c.low += static_cast<double>(misses[i]) * next.low;
    c.high += static_cast<double>(misses[i]) * next.high;
  }
  return c;
}

}  // namespace meshreuse
