// Set-associative LRU cache simulation (DESIGN.md "Set-associative simulation"): the sharper test
// of the fully associative miss model. It follows valgrind's simulator (cachegrind/cg_sim.c and
// callgrind/sim.c) so that its numbers can be checked against callgrind's:
//   - each level is `sets` sets of `ways` lines, true LRU within a set (most recently used first,
//     the rest shuffled down), tags are whole line numbers;
//   - a set is line % sets (bit selection when sets is a power of two, as valgrind; other counts
//     are allowed here, valgrind refuses them);
//   - write-allocate: a store is looked up and installed exactly like a load (valgrind's default
//     model; the hit and miss counts are the same for write-through and write-back);
//   - an access that straddles two lines counts as one access, and as one miss if either line
//     misses; both lines are looked up (and installed) at every level it reaches;
//   - level i+1 sees exactly the accesses that missed level i (no prefetching, no inclusion
//     enforcement, no write-back traffic).
// Cold misses: accesses that touch a line never touched before (they miss at every level): the
// compulsory part, so misses - cold = the excess an ordering could still remove.
// Each thread stream gets a private hierarchy, like the reuse-distance analysis (a traced run is
// serial; sharing of an L3 between threads is not modelled).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "tracer/sink.h"

namespace meshreuse {

struct LevelStats {
  uint64_t accesses = 0, misses = 0, cold = 0;
  uint64_t read_misses = 0, write_misses = 0;
  double MissRate() const { return accesses ? static_cast<double>(misses) / accesses : 0.0; }
  LevelStats& operator+=(const LevelStats& o);
  LevelStats operator-(const LevelStats& o) const;
};

// One level. Lines are addresses >> log2(line bytes).
class SetAssociativeCache {
 public:
  // Throws std::invalid_argument unless bytes is a multiple of line_bytes * ways.
  SetAssociativeCache(uint64_t bytes, uint32_t ways, uint32_t line_bytes);
  // The same check, without building the cache.
  static void CheckGeometry(uint64_t bytes, uint32_t ways, uint32_t line_bytes);
  // Looks `line` up; on a hit moves it to the front of its set, on a miss installs it there
  // (evicting the least recently used). Returns true on a hit.
  bool Access(uint64_t line) {
    uint64_t* set = tags_.data() + (pow2_ ? (line & mask_) : (line % sets_)) * ways_;
    if (set[0] == line) return true;
    for (uint32_t i = 1; i < ways_; ++i)
      if (set[i] == line) {
        for (uint32_t j = i; j > 0; --j) set[j] = set[j - 1];
        set[0] = line;
        return true;
      }
    for (uint32_t j = ways_ - 1; j > 0; --j) set[j] = set[j - 1];
    set[0] = line;
    return false;
  }
  uint64_t sets() const { return sets_; }
  uint32_t ways() const { return ways_; }

 private:
  uint64_t sets_, mask_;
  uint32_t ways_;
  bool pow2_;
  std::vector<uint64_t> tags_;  // sets x ways, most recently used first; ~0 = empty
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
  void Access(uint64_t address, uint32_t size, bool write);
  const std::vector<LevelStats>& stats() const { return stats_; }
  uint64_t distinct_lines() const { return seen_used_; }

 private:
  bool FirstTouch(uint64_t line);  // records the line; true if it was never seen

  std::vector<CacheLevel> config_;
  uint32_t line_bytes_;
  std::vector<SetAssociativeCache> levels_;  // empty until the first access
  std::vector<LevelStats> stats_;
  int shift_;
  std::vector<uint64_t> seen_;  // open addressing set of touched lines (~0 = empty)
  uint64_t seen_used_ = 0;
};

// Per thread stream, and per sweep (BeginSweep marks where each sweep starts).
class CacheSimulation {
 public:
  CacheSimulation(const std::vector<CacheLevel>& levels, uint32_t line_bytes, int threads);
  void BeginSweep();
  void Access(int thread, uint64_t address, uint32_t size, bool write) {
    streams_[thread].Access(address, size, write);
  }
  int threads() const { return static_cast<int>(streams_.size()); }
  const std::vector<LevelStats>& Stats(int thread) const { return streams_[thread].stats(); }
  // Stats of `thread` in sweep s (0-based, in the order BeginSweep was called).
  std::vector<LevelStats> SweepStats(int thread, size_t s) const;
  size_t sweeps() const { return marks_.size(); }

 private:
  std::vector<CacheHierarchy> streams_;
  std::vector<std::vector<std::vector<LevelStats>>> marks_;  // [sweep][thread] stats at its start
};

// The sink the smoother streams into; addresses are canonical (sink.h), so the numbers are the
// same in every run and equal to a simulation of the trace file.
struct CacheSimSink {
  static constexpr bool kEnabled = true;
  explicit CacheSimSink(CacheSimulation* s) : sim(s) {}
  CacheSimulation* sim;
  AddressCanonicalizer canon;
  void Bind(const ArrayLayout& l) { canon = AddressCanonicalizer(l); }
  void BeginSweep(int) { sim->BeginSweep(); }
  void Access(int thread, const MemRef& r) {
    sim->Access(thread, canon(thread, r), r.size, r.write);
  }
};

}  // namespace meshreuse
