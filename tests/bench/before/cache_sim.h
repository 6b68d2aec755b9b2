// The simulators as they were at 6436f89 (before issue 40's rewrite), kept verbatim in namespace
// before so that meshreuse_bench's Multicore/P times the old and the new code on the same streams
// in one run (the "before and after, side by side"). Benchmark-only: nothing links it but
// meshreuse_bench. The original header comment follows.
// Set-associative cache simulation (DESIGN.md "Set-associative simulation"): the sharper test
// of the fully associative miss model. It follows valgrind's simulator (cachegrind/cg_sim.c and
// callgrind/sim.c) so that its numbers can be checked against callgrind's:
//   - each level is `sets` sets of `ways` lines, true LRU within a set (most recently used first,
//     the rest shuffled down; the default), tags are whole line numbers; a level may instead
//     replace first in, first out (a hit does not refresh) or a seeded pseudo-random way;
//   - a set is line % sets (bit selection when sets is a power of two, as valgrind; other counts
//     are allowed here, valgrind refuses them);
//   - write-allocate: a store is looked up and installed exactly like a load (valgrind's default
//     model; the hit and miss counts are the same for write-through and write-back);
//   - an access that straddles two lines counts as one access, and as one miss if either line
//     misses; both lines are looked up (and installed) at every level it reaches;
//   - level i+1 sees exactly the accesses that missed level i (no prefetching, no inclusion
//     enforcement, no write-back traffic);
//   - a level named I1 is an instruction cache beside the first data level (cachegrind's I1):
//     instruction fetches (lackey's I lines, AccessKind::kFetch) go through it and then through
//     the data levels below the first, data accesses skip it. Without an I1 a fetch takes the
//     data path. Misses are split by what caused them: read, write (a store) or fetch, so that a
//     lackey trace gives cachegrind's D1mr/D1mw/I1mr and DLmr/DLmw/ILmr exactly (a modify is a
//     read then a write, and the write always hits: cachegrind counts it as the read alone).
// Cold misses: accesses that touch a line never touched before (they miss at every level): the
// compulsory part, so misses - cold = the excess an ordering could still remove.
// Each thread stream gets a private hierarchy, like the reuse-distance analysis (a traced run is
// serial; sharing of an L3 between threads is not modelled). CacheSimulation is a consumer of any
// access stream (tracer/access_stream.h); its rows have one schema whatever the command. On
// request it also splits each level's lookups and misses by the array each access belongs to
// (CountByArray: the difference of the level counters around each access, so the arrays' counts
// add up to the level's exactly).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "core/table.h"
#include "tracer/access_stream.h"

namespace meshreuse::before {

struct LevelStats {
  uint64_t accesses = 0, misses = 0, cold = 0;
  uint64_t read_misses = 0, write_misses = 0, fetch_misses = 0;
  double MissRate() const { return accesses ? static_cast<double>(misses) / accesses : 0.0; }
  LevelStats& operator+=(const LevelStats& o);
  LevelStats operator-(const LevelStats& o) const;
};

// One level. Lines are addresses >> log2(line bytes).
class SetAssociativeCache {
 public:
  // Lines a level may hold: its tags are allocated up front (calloc: pages as they are touched),
  // and a level of more lines is a mistake (1 B lines in a GiB cache), refused naming the level.
  static constexpr uint64_t kMaxLines = uint64_t{1} << 26;
  // Throws UsageError unless bytes is a multiple of line_bytes * ways.
  SetAssociativeCache(uint64_t bytes, uint32_t ways, uint32_t line_bytes,
                      Replacement policy = Replacement::kLru);
  // The same check, without building the cache.
  static void CheckGeometry(uint64_t bytes, uint32_t ways, uint32_t line_bytes);
  // Looks `line` up; on a hit moves it to the front of its set, on a miss installs it there
  // (evicting the least recently used). Returns true on a hit.
  bool Access(uint64_t line) {
    const uint64_t tag = line + 1;  // 0 is an empty way (lines are below 2^63)
    uint64_t* set = tags_.get() + (pow2_ ? (line & mask_) : (line % sets_)) * ways_;
    if (set[0] == tag) return true;
    for (uint32_t i = 1; i < ways_; ++i)
      if (set[i] == tag) {
        if (policy_ == Replacement::kLru) {
          for (uint32_t j = i; j > 0; --j) set[j] = set[j - 1];
          set[0] = tag;
        }
        return true;
      }
    if (policy_ == Replacement::kRandom) {  // an empty way, else one by xorshift64 (seeded)
      for (uint32_t i = 0; i < ways_; ++i)
        if (set[i] == 0) {
          set[i] = tag;
          victim_ = ~uint64_t{0};
          return false;
        }
      rng_ ^= rng_ << 13, rng_ ^= rng_ >> 7, rng_ ^= rng_ << 17;
      victim_ = set[rng_ % ways_] - 1;
      set[rng_ % ways_] = tag;
      return false;
    }
    victim_ = set[ways_ - 1] - 1;  // ~0 when the way was empty
    for (uint32_t j = ways_ - 1; j > 0; --j) set[j] = set[j - 1];
    set[0] = tag;
    return false;
  }
  // The line the last missing Access evicted, ~0 if it filled an empty way.
  uint64_t victim() const { return victim_; }
  // Whether `line` is held (no change to the set's order).
  bool Contains(uint64_t line) const {
    const uint64_t* set = tags_.get() + (pow2_ ? (line & mask_) : (line % sets_)) * ways_;
    for (uint32_t i = 0; i < ways_; ++i)
      if (set[i] == line + 1) return true;
    return false;
  }
  // Removes `line` if held (the ways after it move up, the last becomes empty): coherence and
  // inclusion. Returns whether it was held.
  bool Invalidate(uint64_t line) {
    uint64_t* set = tags_.get() + (pow2_ ? (line & mask_) : (line % sets_)) * ways_;
    for (uint32_t i = 0; i < ways_; ++i)
      if (set[i] == line + 1) {
        for (uint32_t j = i; j + 1 < ways_; ++j) set[j] = set[j + 1];
        set[ways_ - 1] = 0;
        return true;
      }
    return false;
  }
  uint64_t sets() const { return sets_; }
  uint32_t ways() const { return ways_; }

 private:
  uint64_t sets_, mask_;
  uint32_t ways_;
  bool pow2_;
  Replacement policy_;
  uint64_t rng_ = 0x9E3779B97F4A7C15ull;
  uint64_t victim_ = ~uint64_t{0};
  // sets x ways, most recently used first; 0 = empty. From calloc, whose large blocks are fresh
  // zero pages: a level costs memory only for the sets a stream touches, so 256 streams of a few
  // accesses each do not hold 256 copies of a 24 MiB L3's tags.
  struct Free {
    void operator()(uint64_t* p) const { std::free(p); }
  };
  std::unique_ptr<uint64_t[], Free> tags_;
};

// A hierarchy for one stream; all levels share one line size.
class CacheHierarchy {
 public:
  CacheHierarchy(const std::vector<CacheLevel>& levels, uint32_t line_bytes);
  CacheHierarchy(CacheHierarchy&&) = default;
  CacheHierarchy& operator=(CacheHierarchy&&) = default;
  CacheHierarchy(const CacheHierarchy&) = delete;
  CacheHierarchy& operator=(const CacheHierarchy&) = delete;

  // The levels' tags are allocated at the first access: memory follows the streams that have
  // accesses, whatever thread count a trace's header announces.
  void Access(uint64_t address, uint32_t size, bool write, bool fetch = false);
  const std::vector<LevelStats>& stats() const { return stats_; }
  uint64_t distinct_lines() const { return seen_used_; }
  uint64_t accesses() const { return accesses_; }

 private:
  bool FirstTouch(uint64_t line);  // records the line; true if it was never seen

  std::vector<CacheLevel> config_;
  uint32_t line_bytes_;
  std::vector<SetAssociativeCache> levels_;  // empty until the first access
  std::vector<LevelStats> stats_;
  bool has_i1_ = false;  // without an I1 every access tries every level in turn
  std::vector<uint8_t> data_path_, fetch_path_;  // with one: level indices, in the order tried
  int shift_;
  std::vector<uint64_t> seen_;  // open addressing set of touched lines (~0 = empty)
  uint64_t seen_used_ = 0;
  uint64_t accesses_ = 0;
};

// Per thread stream, and per sweep (BeginSweep marks where each sweep starts). A stream's
// hierarchy is made at its first access.
class CacheSimulation : public AccessConsumer {
 public:
  CacheSimulation(const CacheSpec& spec, uint32_t line_bytes);
  void Begin(const StreamInfo& info) override;  // the streams (threads) and the input's names
  void BeginSweep(int sweep) override;
  void Consume(const meshreuse::Access* a, size_t n) override {
    if (by_array_) return ConsumeByArray(a, n);
    for (size_t i = 0; i < n;) {  // runs of one thread: its hierarchy looked up once a run
      const uint8_t t = a[i].thread;
      CacheHierarchy& h = streams_[t];
      for (; i < n && a[i].thread == t; ++i)
        h.Access(a[i].address, a[i].size, a[i].write,
                 a[i].kind == static_cast<uint8_t>(AccessKind::kFetch));
    }
  }
  // Counts each level's lookups and misses per array too (Access::array: the smoother's arrays,
  // core/access.h, or kForeignArray): which data misses. From the next access on.
  void CountByArray() {
    by_array_ = true;
    per_array_.resize(streams_.size());
  }
  bool by_array() const { return by_array_; }
  // input, ordering, thread, array, level, accesses, misses, miss_share (of the level's misses
  // in that thread): one row per array with accesses, per level, arrays in Array order.
  static std::vector<std::string> ArrayColumns();
  void AppendArrayRows(Table* t) const;
  // Lookups and misses of `array` at level i in `thread` (0 when not counted).
  uint64_t ArrayAccesses(int thread, int array, size_t level) const;
  uint64_t ArrayMisses(int thread, int array, size_t level) const;
  // By hand (tests), after Begin (or with a stream count given to Resize).
  void Access(int thread, uint64_t address, uint32_t size, bool write, bool fetch = false) {
    streams_[thread].Access(address, size, write, fetch);
  }
  void Resize(int threads);
  int threads() const { return static_cast<int>(streams_.size()); }
  const std::vector<LevelStats>& Stats(int thread) const { return streams_[thread].stats(); }
  // Stats of `thread` in sweep s (0-based, in the order BeginSweep was called).
  std::vector<LevelStats> SweepStats(int thread, size_t s) const;
  size_t sweeps() const { return sweeps_; }
  const CacheSpec& spec() const { return spec_; }
  uint32_t line_bytes() const { return line_bytes_; }

  // input, ordering, thread, sweep ("all", or 1-based with per_sweep: the sweeps in which the
  // thread accessed anything), level, size, ways, sets,
  // policy, accesses, hits, misses, cold, excess, miss_rate, read_misses, write_misses,
  // fetch_misses.
  static std::vector<std::string> Columns();
  void AppendRows(Table* t, bool per_sweep) const;

 private:
  CacheSpec spec_;
  uint32_t line_bytes_;
  StreamInfo info_;
  std::vector<CacheHierarchy> streams_;
  // Per thread, its stats at the start of each sweep k, kept only when the thread accessed
  // something since its previous mark: memory follows the accesses, whatever sweep count a
  // header announces. A sweep with no mark at its end had no access.
  struct Mark {
    size_t sweep;
    std::vector<LevelStats> stats;
  };
  std::vector<std::vector<Mark>> marks_;
  std::vector<uint64_t> marked_;  // accesses() at each thread's last mark
  size_t sweeps_ = 0;
  // By array: per thread, 256 arrays x levels x (lookups, misses), made at the thread's first
  // access.
  bool by_array_ = false;
  std::vector<std::vector<uint64_t>> per_array_;
  void ConsumeByArray(const meshreuse::Access* a, size_t n);
  std::vector<LevelStats> StartOf(int thread, size_t s) const;
};

}  // namespace meshreuse::before
