// Set-associative cache simulation; see cache_sim.h.
#include "analysis/cache_sim.h"

#include <stdexcept>
#include <string>

namespace meshreuse {

namespace {
constexpr uint64_t kEmpty = ~uint64_t{0};

uint64_t Mix(uint64_t x) {  // SplitMix64 finaliser: spreads consecutive line numbers
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
}  // namespace

LevelStats& LevelStats::operator+=(const LevelStats& o) {
  accesses += o.accesses;
  misses += o.misses;
  cold += o.cold;
  read_misses += o.read_misses;
  write_misses += o.write_misses;
  return *this;
}

LevelStats LevelStats::operator-(const LevelStats& o) const {
  LevelStats d;
  d.accesses = accesses - o.accesses;
  d.misses = misses - o.misses;
  d.cold = cold - o.cold;
  d.read_misses = read_misses - o.read_misses;
  d.write_misses = write_misses - o.write_misses;
  return d;
}

void SetAssociativeCache::CheckGeometry(uint64_t bytes, uint32_t ways, uint32_t line_bytes) {
  if (line_bytes == 0 || ways == 0 || bytes == 0 || bytes % (uint64_t{line_bytes} * ways) != 0)
    throw std::invalid_argument("a cache of " + std::to_string(bytes) + " B cannot have " +
                                std::to_string(ways) + " ways of " + std::to_string(line_bytes) +
                                " B lines (the size must be a multiple of ways x line size)");
}

SetAssociativeCache::SetAssociativeCache(uint64_t bytes, uint32_t ways, uint32_t line_bytes) {
  CheckGeometry(bytes, ways, line_bytes);
  sets_ = bytes / line_bytes / ways;
  ways_ = ways;
  pow2_ = (sets_ & (sets_ - 1)) == 0;
  mask_ = sets_ - 1;
  tags_.assign(sets_ * ways_, kEmpty);
}

CacheHierarchy::CacheHierarchy(const std::vector<CacheLevel>& levels, uint32_t line_bytes)
    : config_(levels), line_bytes_(line_bytes) {
  if (line_bytes == 0 || (line_bytes & (line_bytes - 1)))
    throw std::invalid_argument("the line size must be a power of two");
  shift_ = __builtin_ctz(line_bytes);
  for (const CacheLevel& l : levels) {
    if (l.ways == 0)
      throw std::invalid_argument("cache level " + l.name +
                                  " needs its associativity for simulation, e.g. " + l.name +
                                  "=32K/8 (the fully associative model is `analyze`)");
    SetAssociativeCache::CheckGeometry(l.bytes, l.ways, line_bytes);
  }
  stats_.resize(levels.size());
  seen_.assign(16, kEmpty);
}

bool CacheHierarchy::FirstTouch(uint64_t line) {
  if (2 * (seen_used_ + 1) > seen_.size()) {  // keep the load factor at most 1/2
    std::vector<uint64_t> old(2 * seen_.size(), kEmpty);
    old.swap(seen_);
    const uint64_t m = seen_.size() - 1;
    for (uint64_t x : old)
      if (x != kEmpty) {
        uint64_t i = Mix(x) & m;
        while (seen_[i] != kEmpty) i = (i + 1) & m;
        seen_[i] = x;
      }
  }
  const uint64_t m = seen_.size() - 1;
  for (uint64_t i = Mix(line) & m;; i = (i + 1) & m) {
    if (seen_[i] == line) return false;
    if (seen_[i] == kEmpty) {
      seen_[i] = line;
      ++seen_used_;
      return true;
    }
  }
}

void CacheHierarchy::Access(uint64_t address, uint32_t size, bool write) {
  if (levels_.size() != config_.size())
    for (const CacheLevel& l : config_) levels_.emplace_back(l.bytes, l.ways, line_bytes_);
  const uint64_t first = address >> shift_;
  const uint64_t last = (address + (size ? size - 1 : 0)) >> shift_;
  // A line number of ~0 would collide with the empty tag; it is the last line of the address
  // space, which no real access reaches with lines of 2 bytes or more.
  bool cold = FirstTouch(first);
  if (last != first) cold = FirstTouch(last) || cold;
  for (size_t i = 0; i < levels_.size(); ++i) {
    LevelStats& s = stats_[i];
    ++s.accesses;
    bool hit = levels_[i].Access(first);
    for (uint64_t l = first + 1; l <= last; ++l) hit = levels_[i].Access(l) && hit;
    if (hit) return;
    ++s.misses;
    if (cold) ++s.cold;
    ++(write ? s.write_misses : s.read_misses);
  }
}

CacheSimulation::CacheSimulation(const std::vector<CacheLevel>& levels, uint32_t line_bytes,
                                 int threads) {
  if (threads < 1 || threads > 256) throw std::invalid_argument("threads must be 1..256");
  for (int t = 0; t < threads; ++t) streams_.emplace_back(levels, line_bytes);
}

void CacheSimulation::BeginSweep() {
  std::vector<std::vector<LevelStats>> now;
  for (const CacheHierarchy& h : streams_) now.push_back(h.stats());
  marks_.push_back(std::move(now));
}

std::vector<LevelStats> CacheSimulation::SweepStats(int thread, size_t s) const {
  const std::vector<LevelStats>& start = marks_.at(s)[thread];
  const std::vector<LevelStats>& end =
      s + 1 < marks_.size() ? marks_[s + 1][thread] : streams_[thread].stats();
  std::vector<LevelStats> d(start.size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = end[i] - start[i];
  return d;
}

}  // namespace meshreuse
