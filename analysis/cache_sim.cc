// Set-associative cache simulation; see cache_sim.h.
#include "analysis/cache_sim.h"

#include <algorithm>
#include <iterator>
#include <new>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/mix.h"
#include "core/schedule.h"

namespace meshreuse {

namespace {
constexpr uint64_t kEmpty = ~uint64_t{0};

}  // namespace

LevelStats& LevelStats::operator+=(const LevelStats& o) {
  accesses += o.accesses;
  misses += o.misses;
  cold += o.cold;
  read_misses += o.read_misses;
  write_misses += o.write_misses;
  fetch_misses += o.fetch_misses;
  return *this;
}

LevelStats LevelStats::operator-(const LevelStats& o) const {
  LevelStats d;
  d.accesses = accesses - o.accesses;
  d.misses = misses - o.misses;
  d.cold = cold - o.cold;
  d.read_misses = read_misses - o.read_misses;
  d.write_misses = write_misses - o.write_misses;
  d.fetch_misses = fetch_misses - o.fetch_misses;
  return d;
}

CacheHierarchy::CacheHierarchy(const std::vector<CacheLevel>& levels, uint32_t line_bytes)
    : config_(levels), line_bytes_(line_bytes) {
  if (line_bytes == 0 || (line_bytes & (line_bytes - 1)))
    throw UsageError("the line size must be a power of two");
  shift_ = __builtin_ctz(line_bytes);
  for (const CacheLevel& l : levels) {
    if (l.ways == 0)
      throw UsageError("cache level " + l.name + " needs its associativity for simulation, e.g. " +
                       l.name + "=32K/8 (the fully associative model is `analyze`)");
    SetAssociativeCache::CheckGeometry(l.bytes, l.ways, line_bytes);
    if (l.bytes / line_bytes > SetAssociativeCache::kMaxLines)
      throw UsageError("cache level " + l.name + ": " + std::to_string(l.bytes / line_bytes) +
                       " lines of " + std::to_string(line_bytes) + " B; a level holds at most " +
                       std::to_string(SetAssociativeCache::kMaxLines) + " lines");
  }
  int i1 = -1;
  for (size_t i = 0; i < levels.size(); ++i) {
    if (levels[i].name != "I1") {
      data_path_.push_back(static_cast<uint8_t>(i));
      continue;
    }
    if (i1 >= 0) throw UsageError("cache level I1 is named twice");
    i1 = static_cast<int>(i);
  }
  if (i1 >= 0 && data_path_.empty())
    throw UsageError(
        "cache level I1 (the instruction cache) needs a data level beside it, e.g. "
        "I1=32K/8,D1=32K/8,LL=8M/16");
  has_i1_ = i1 >= 0;
  if (has_i1_) fetch_path_.push_back(static_cast<uint8_t>(i1));
  fetch_path_.insert(fetch_path_.end(), data_path_.begin() + (i1 >= 0 ? 1 : 0), data_path_.end());
  stats_.resize(levels.size());
  seen_.assign(16, kEmpty);
}

bool CacheHierarchy::FirstTouch(uint64_t line) {
  // A window of kWindowLines lines from the first line recorded, one bit each (a few megabytes of
  // addresses from the first: the smoother's arrays, canonical or not), and the hash set beyond.
  if (!window_) {
    window_base_ = line & ~(kWindowLines - 1);
    window_.reset(static_cast<uint64_t*>(std::calloc(kWindowLines / 64, sizeof(uint64_t))));
    if (!window_) throw std::bad_alloc();
    window_pages_.Reset(window_.get(), kWindowLines / 8);
  }
  if (line - window_base_ < kWindowLines) {
    const uint64_t i = line - window_base_, bit = uint64_t{1} << (i & 63);
    uint64_t& word = window_.get()[i >> 6];
    if (word & bit) return false;
    word |= bit;
    ++seen_used_;
    return true;
  }
  if (2 * (seen_used_ + 1) > seen_.size()) {  // keep the load factor at most 1/2
    std::vector<uint64_t> old(2 * seen_.size(), kEmpty);
    old.swap(seen_);
    const uint64_t m = seen_.size() - 1;
    for (uint64_t x : old)
      if (x != kEmpty) {
        uint64_t i = Mix64(x) & m;
        while (seen_[i] != kEmpty) i = (i + 1) & m;
        seen_[i] = x;
      }
  }
  const uint64_t m = seen_.size() - 1;
  for (uint64_t i = Mix64(line) & m;; i = (i + 1) & m) {
    if (seen_[i] == line) return false;
    if (seen_[i] == kEmpty) {
      seen_[i] = line;
      ++seen_used_;
      return true;
    }
  }
}

void CacheHierarchy::Allocate() {
  for (const CacheLevel& l : config_) levels_.emplace_back(l.bytes, l.ways, line_bytes_, l.policy);
  fast_ = !has_i1_ && !wide_;
}

// A first-level miss goes on to the levels below, one lookup after another, each likely a host
// miss (a 24 MiB level is 6 MiB of sets): their sets asked of the host at once overlap, and so
// does FirstTouch's bit (written if the line is new).
inline void CacheHierarchy::PrefetchBelow(const uint8_t* path, size_t n, uint64_t line) {
  for (size_t k = 1; k < n; ++k) levels_[path ? path[k] : k].PrefetchSet(line);
  if (window_ && line - window_base_ < kWindowLines)
    window_pages_.Touch(&window_.get()[(line - window_base_) >> 6], 8);
}

// The first level's miss counted, then each level below looked up (every line) and counted, in
// path order, until one hits: each level sees the misses of the one before.
inline void CacheHierarchy::MissBelow(const uint8_t* path, size_t n, uint64_t first, uint64_t last,
                                      bool cold, bool write, bool fetch) {
  auto count_miss = [&](LevelStats& s) {
    ++s.misses;
    if (cold) ++s.cold;
    ++(fetch ? s.fetch_misses : write ? s.write_misses : s.read_misses);
  };
  count_miss(stats_[path ? path[0] : 0]);
  for (size_t k = 1; k < n; ++k) {
    const size_t i = path ? path[k] : k;
    LevelStats& s = stats_[i];
    ++s.accesses;
    bool hit = levels_[i].Access(first);
    for (uint64_t l = first + 1; l <= last; ++l) hit = levels_[i].Access(l) && hit;
    if (hit) return;
    count_miss(s);
  }
}

void CacheHierarchy::Access(uint64_t address, uint32_t size, bool write, bool fetch,
                            bool first_missed) {
  Flush();
  ++accesses_;
  if (config_.empty()) return;
  if (__builtin_expect(levels_.empty(), 0)) Allocate();
  const uint64_t first = address >> shift_;
  const uint64_t last = (address + (size ? size - 1 : 0)) >> shift_;
  const uint8_t* path = nullptr;  // the levels in the order tried (without an I1: all, in order)
  size_t n = config_.size();
  if (has_i1_) {
    const std::vector<uint8_t>& p = fetch ? fetch_path_ : data_path_;
    path = p.data(), n = p.size();
  }
  // The first level alone, on the path most accesses take: a hit there touched lines that an
  // earlier access recorded (it missed there first), so the record of first touches is consulted
  // only from a miss on. An access of three lines or more records only its end lines (as it always
  // has); after the first such access every access consults the record, so the counts are those
  // of recording at every access exactly.
  const size_t l0 = path ? path[0] : 0;
  if (first_missed) PrefetchBelow(path, n, first);
  ++stats_[l0].accesses;
  bool hit = false;
  if (first_missed)  // one line (HitFirst looks up no other)
    levels_[l0].InstallMissed(first);
  else
    hit = levels_[l0].Access(first);
  if (__builtin_expect(last != first, 0)) {
    for (uint64_t l = first + 1; l <= last; ++l) hit = levels_[l0].Access(l) && hit;
    if (last - first >= 2) wide_ = true, fast_ = false;
  }
  if (hit && !wide_) return;
  // A line number of ~0 would collide with the empty tag; it is the last line of the address
  // space, which no real access reaches with lines of 2 bytes or more.
  bool cold = FirstTouch(first);
  if (last != first) cold = FirstTouch(last) || cold;
  if (hit) return;
  MissBelow(path, n, first, last, cold, write, fetch);
}

void CacheHierarchy::FlushPending() {
  // fast_: no I1, so the path is every level in order; one line each.
  const size_t n = config_.size();
  for (uint32_t j = 0; j < pending_n_; ++j) PrefetchBelow(nullptr, n, pending_[j].line);
  for (uint32_t j = 0; j < pending_n_; ++j) {
    const uint64_t line = pending_[j].line;
    MissBelow(nullptr, n, line, line, FirstTouch(line), pending_[j].write, false);
  }
  pending_n_ = 0;
}

CacheSimulation::CacheSimulation(const CacheSpec& spec, uint32_t line_bytes)
    : spec_(spec), line_bytes_(line_bytes) {
  const CacheHierarchy check(spec.levels, line_bytes);  // the geometry, before any access
  first_groups_ = check.FirstGroups();
}

void CacheSimulation::Begin(const StreamInfo& info) {
  info_ = info;
  Resize(info.threads);
}

void CacheSimulation::Resize(int threads) {
  if (threads < 1 || threads > kMaxThreads)
    throw std::invalid_argument("streams must be 1.." + std::to_string(kMaxThreads));
  streams_.clear();
  for (int t = 0; t < threads; ++t) streams_.emplace_back(spec_.levels, line_bytes_);
  marks_.assign(threads, {});
  marked_.assign(threads, 0);
  sweeps_ = 0;
  per_array_.assign(by_array_ ? threads : 0, {});
}

void CacheSimulation::Consume(const meshreuse::Access* a, size_t n) {
  if (by_array_) return ConsumeByArray(a, n);
  SetAssociativeCache::WithGroups<4>(first_groups_,
                                     [&](auto g) { ConsumeIn<decltype(g)::value>(a, n); });
}

void CacheSimulation::ConsumeByArray(const meshreuse::Access* a, size_t n) {
  const size_t levels = spec_.levels.size();
  std::vector<uint64_t> before(2 * levels);
  for (size_t i = 0; i < n; ++i) {
    const meshreuse::Access& x = a[i];
    CacheHierarchy& h = streams_[x.thread];
    std::vector<uint64_t>& c = per_array_[x.thread];
    if (c.empty()) c.assign(256 * levels * 2, 0);
    const std::vector<LevelStats>& st = h.stats();  // one entry per level, from construction
    for (size_t l = 0; l < levels; ++l)
      before[2 * l] = st[l].accesses, before[2 * l + 1] = st[l].misses;
    h.Access(x.address, x.size, x.write, x.kind == static_cast<uint8_t>(AccessKind::kFetch));
    uint64_t* row = c.data() + static_cast<size_t>(x.array) * levels * 2;
    for (size_t l = 0; l < levels; ++l) {
      row[2 * l] += st[l].accesses - before[2 * l];
      row[2 * l + 1] += st[l].misses - before[2 * l + 1];
    }
  }
}

uint64_t CacheSimulation::ArrayAccesses(int thread, int array, size_t level) const {
  if (thread < 0 || static_cast<size_t>(thread) >= per_array_.size() || per_array_[thread].empty())
    return 0;
  return per_array_[thread][(static_cast<size_t>(array) * spec_.levels.size() + level) * 2];
}

uint64_t CacheSimulation::ArrayMisses(int thread, int array, size_t level) const {
  if (thread < 0 || static_cast<size_t>(thread) >= per_array_.size() || per_array_[thread].empty())
    return 0;
  return per_array_[thread][(static_cast<size_t>(array) * spec_.levels.size() + level) * 2 + 1];
}

std::vector<std::string> CacheSimulation::ArrayColumns() {
  return {"input", "ordering", "thread", "array", "level", "accesses", "misses", "miss_share"};
}

void CacheSimulation::AppendArrayRows(Table* t) const {
  const std::vector<CacheLevel>& levels = spec_.levels;
  for (int th = 0; th < static_cast<int>(per_array_.size()); ++th) {
    if (per_array_[th].empty()) continue;
    const std::vector<LevelStats>& total = Stats(th);
    for (int a = 0; a < 256; ++a) {
      uint64_t any = 0;  // an I1 sees no data, the data levels no fetches: any level counts
      for (size_t l = 0; l < levels.size(); ++l) any += ArrayAccesses(th, a, l);
      if (any == 0) continue;
      const std::string name = a == Access::kForeignArray ? "trace"
                               : a < kArrays              ? ArrayName(static_cast<Array>(a))
                                                          : std::to_string(a);
      for (size_t l = 0; l < levels.size(); ++l) {
        const uint64_t m = ArrayMisses(th, a, l);
        const uint64_t all = total[l].misses;
        t->AddRow({info_.input, info_.ordering, std::to_string(th), name, levels[l].name,
                   std::to_string(ArrayAccesses(th, a, l)), std::to_string(m),
                   ExactNumber(all ? static_cast<double>(m) / static_cast<double>(all) : 0.0)});
      }
    }
  }
}

void CacheSimulation::BeginSweep(int) {
  for (size_t t = 0; t < streams_.size(); ++t)
    if (streams_[t].accesses() != marked_[t]) {
      marks_[t].push_back({sweeps_, streams_[t].stats()});
      marked_[t] = streams_[t].accesses();
    }
  ++sweeps_;
}

std::vector<LevelStats> CacheSimulation::StartOf(int thread, size_t s) const {
  const std::vector<Mark>& m = marks_[thread];
  const auto it =
      std::upper_bound(m.begin(), m.end(), s, [](size_t v, const Mark& x) { return v < x.sweep; });
  return it == m.begin() ? std::vector<LevelStats>(spec_.levels.size()) : std::prev(it)->stats;
}

std::vector<LevelStats> CacheSimulation::SweepStats(int thread, size_t s) const {
  if (s >= sweeps_) throw std::out_of_range("no such sweep");
  const std::vector<LevelStats> start = StartOf(thread, s);
  const std::vector<LevelStats> end =
      s + 1 < sweeps_ ? StartOf(thread, s + 1) : streams_[thread].stats();
  std::vector<LevelStats> d(start.size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = end[i] - start[i];
  return d;
}

std::vector<std::string> CacheSimulation::Columns() {
  return {"input", "ordering", "thread",    "sweep",       "level",        "size",
          "ways",  "sets",     "policy",    "accesses",    "hits",         "misses",
          "cold",  "excess",   "miss_rate", "read_misses", "write_misses", "fetch_misses"};
}

void CacheSimulation::AppendRows(Table* t, bool per_sweep) const {
  const std::vector<CacheLevel>& levels = spec_.levels;
  for (int th = 0; th < threads(); ++th) {
    std::vector<std::pair<std::string, std::vector<LevelStats>>> parts = {{"all", Stats(th)}};
    if (per_sweep) {  // the sweeps with accesses: each is the sweep before a mark, or the last
      const std::vector<Mark>& m = marks_[th];
      for (const Mark& x : m)
        if (x.sweep > 0) parts.emplace_back(std::to_string(x.sweep), SweepStats(th, x.sweep - 1));
      if (sweeps_ > 0 && streams_[th].accesses() != marked_[th])
        parts.emplace_back(std::to_string(sweeps_), SweepStats(th, sweeps_ - 1));
    }
    for (const auto& [sweep, st] : parts)
      for (size_t i = 0; i < levels.size(); ++i) {
        const LevelStats& s = st[i];
        t->AddRow({info_.input, info_.ordering, std::to_string(th), sweep, levels[i].name,
                   std::to_string(levels[i].bytes), std::to_string(levels[i].ways),
                   std::to_string(levels[i].bytes / line_bytes_ / levels[i].ways),
                   ReplacementName(levels[i].policy), std::to_string(s.accesses),
                   std::to_string(s.accesses - s.misses), std::to_string(s.misses),
                   std::to_string(s.cold), std::to_string(s.misses - s.cold),
                   ExactNumber(s.MissRate()), std::to_string(s.read_misses),
                   std::to_string(s.write_misses), std::to_string(s.fetch_misses)});
      }
  }
}

}  // namespace meshreuse
