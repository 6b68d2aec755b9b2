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
// A level is a SetAssociativeCache (set_associative_cache.h), shared with the many-core simulator.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "analysis/cache_model.h"
#include "analysis/set_associative_cache.h"
#include "core/table.h"
#include "tracer/access_stream.h"

namespace meshreuse {

struct LevelStats {
  uint64_t accesses = 0, misses = 0, cold = 0;
  uint64_t read_misses = 0, write_misses = 0, fetch_misses = 0;
  double MissRate() const { return accesses ? static_cast<double>(misses) / accesses : 0.0; }
  LevelStats& operator+=(const LevelStats& o);
  LevelStats operator-(const LevelStats& o) const;
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
  // first_missed: the caller's HitFirst has just missed this access (its first level is not
  // looked up again).
  void Access(uint64_t address, uint32_t size, bool write, bool fetch = false,
              bool first_missed = false);
  // The first level's lookup, when that is all an access may do there (one line, no I1, the
  // levels made, no access of three lines so far): a hit counted as Access counts it (kHit), or
  // a miss with nothing changed (kMissed: then Access(..., first_missed = true) goes on from it).
  // Otherwise kNotLookedUp, and Access does it all. G: the first level's groups (FirstGroups()).
  enum Lookup { kNotLookedUp, kMissed, kHit };
  template <uint32_t G>
  Lookup HitFirst(uint64_t address, uint32_t size) {
    if (!fast_) return kNotLookedUp;
    const uint64_t first = address >> shift_;
    if (((address + (size ? size - 1 : 0)) >> shift_) != first) return kNotLookedUp;
    if (!levels_.front().Hit<G>(first)) return kMissed;
    ++accesses_;
    ++stats_.front().accesses;
    return kHit;
  }
  // HitFirst's hits over a[from..n) while they are thread t's: the index of the first access not
  // taken (another thread's, or one that HitFirst would not call a hit), all before it counted.
  template <uint32_t G>
  size_t HitRun(const meshreuse::Access* a, size_t from, size_t n, uint8_t t) {
    if (!fast_) return from;
    const size_t end =
        levels_.front().HitRun<G>(from, n, OneLineOf{a, t, shift_}, [](size_t, uint64_t) {});
    accesses_ += end - from;
    stats_.front().accesses += end - from;
    return end;
  }
  // Whether the last HitRun stopped at a first-level miss (of thread t's one-line access): what
  // HitFirst would answer there, kMissed, without the lookup.
  bool RunMissed() const { return fast_ && levels_.front().run_missed(); }
  // What Access(address, size, write, false, true) does after HitFirst's kMissed, with the levels
  // below the first looked up later, in order, by Flush: up to kPending first-level misses at once,
  // their sets asked of the host together (a level below is a host miss per lookup, and one after
  // another they do not overlap). Exact: only misses reach those levels and the record of first
  // touches, in the order they happen; Access flushes before anything else touches them, and the
  // caller flushes before reading stats() (CacheSimulation: at the end of each Consume).
  void MissFirst(uint64_t address, bool write) {
    const uint64_t line = address >> shift_;
    ++accesses_;
    ++stats_.front().accesses;
    levels_.front().InstallMissed(line);
    pending_[pending_n_++] = {line, write};
    if (pending_n_ == kPending) Flush();
  }
  void Flush() {
    if (pending_n_) FlushPending();
  }
  uint32_t FirstGroups() const {
    return config_.empty() ? 0 : SetAssociativeCache::GroupsOf(config_[0].ways);
  }
  const std::vector<LevelStats>& stats() const { return stats_; }
  uint64_t distinct_lines() const { return seen_used_; }
  uint64_t accesses() const { return accesses_; }

 private:
  bool FirstTouch(uint64_t line);  // records the line; true if it was never seen
  void Allocate();
  void FlushPending();
  // path: the levels in the order tried, n of them (null: every level, in order).
  void PrefetchBelow(const uint8_t* path, size_t n, uint64_t line);
  void MissBelow(const uint8_t* path, size_t n, uint64_t first, uint64_t last, bool cold,
                 bool write, bool fetch);
  static constexpr uint32_t kPending = 16;
  struct Pending {
    uint64_t line;
    bool write;
  };
  Pending pending_[kPending];
  uint32_t pending_n_ = 0;

  std::vector<CacheLevel> config_;
  uint32_t line_bytes_;
  std::vector<SetAssociativeCache> levels_;  // empty until the first access
  std::vector<LevelStats> stats_;
  bool has_i1_ = false;  // without an I1 every access tries every level in turn
  std::vector<uint8_t> data_path_, fetch_path_;  // with one: level indices, in the order tried
  int shift_;
  static constexpr uint64_t kWindowLines = uint64_t{1} << 22;  // a bit each: 512 KiB
  struct FreeWords {
    void operator()(uint64_t* p) const { std::free(p); }
  };
  std::unique_ptr<uint64_t[], FreeWords> window_;  // touched lines near the first, made then
  WritablePages window_pages_;
  uint64_t window_base_ = 0;
  std::vector<uint64_t> seen_;  // the others: open addressing set (~0 = empty)
  uint64_t seen_used_ = 0;
  uint64_t accesses_ = 0;
  bool wide_ = false;  // an access spanned three lines or more: record at every access
  bool fast_ = false;  // HitFirst may answer: the levels made, no I1, not wide_
};

// Per thread stream, and per sweep (BeginSweep marks where each sweep starts). A stream's
// hierarchy is made at its first access.
class CacheSimulation : public AccessConsumer {
 public:
  CacheSimulation(const CacheSpec& spec, uint32_t line_bytes);
  void Begin(const StreamInfo& info) override;  // the streams (threads) and the input's names
  void BeginSweep(int sweep) override;
  // Out of line, as MulticoreSimulation's: its hit loop's variants are compiled once.
  void Consume(const meshreuse::Access* a, size_t n) override;
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
  // The loop every access takes: first-level hits in runs (HitRun), anything else through Access.
  template <uint32_t G>
  void ConsumeIn(const meshreuse::Access* a, size_t n) {
    for (size_t i = 0; i < n;) {  // runs of one thread: its hierarchy looked up once a run
      const uint8_t t = a[i].thread;
      CacheHierarchy& h = streams_[t];
      while (i < n && a[i].thread == t) {
        i = h.HitRun<G>(a, i, n, t);
        if (i == n || a[i].thread != t) break;
        if (const auto r =
                h.RunMissed() ? CacheHierarchy::kMissed : h.HitFirst<G>(a[i].address, a[i].size);
            r == CacheHierarchy::kMissed && a[i].kind != kFetchKind)
          h.MissFirst(a[i].address, a[i].write);
        else if (r != CacheHierarchy::kHit)
          h.Access(a[i].address, a[i].size, a[i].write, a[i].kind == kFetchKind,
                   r == CacheHierarchy::kMissed);
        ++i;
      }
    }
    for (CacheHierarchy& h : streams_) h.Flush();
  }
  static constexpr uint8_t kFetchKind = static_cast<uint8_t>(AccessKind::kFetch);
  uint32_t first_groups_ = 0;
  std::vector<LevelStats> StartOf(int thread, size_t s) const;
};

}  // namespace meshreuse
