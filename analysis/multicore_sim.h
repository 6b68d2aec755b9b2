// Many-core cache simulation: the thread streams of a traced run on a machine (machine.h), each
// thread on a core by a placement, every access through its core's private levels, then its
// socket's shared levels, then memory (local or remote by the machine's NUMA rule). The rules of
// one level are cache_sim.h's (set-associative, LRU by default, write-allocate, a straddling access
// is one access and misses if either line misses, a level sees the misses of the one above), and
// beyond them:
//   - inclusion: an inclusive shared level that evicts a line removes it from the private levels
//     of its socket's cores (each removal from a core that held it is an inclusion victim);
//   - write-invalidate coherence (the machine may turn it off): a write by a core removes the
//     line from every other core's private levels and every other socket's shared levels; the
//     next miss of a core or socket on a line so removed is a coherence miss (counted apart,
//     within the misses). Which cores may hold a line is kept in a directory;
//   - a next-line prefetcher at a level: a demand miss of line L there brings L+1 into that level
//     and into every level below it that lacks it (as a request down the hierarchy would; an
//     inclusive level keeps holding what is above it), not counted as an access anywhere; a later
//     demand hit on a prefetched line that no demand had touched is a prefetch hit, a miss the
//     prefetcher hid;
//   - cold misses are first touches by the level's owner (a core for a private level, a socket for
//     a shared one), so a machine of private levels gives today's per-stream numbers exactly.
// The interleaving of the streams is the traced run's (SmoothOptions::interleave): accesses are
// simulated in the order they arrive. Per thread: counts per level, memory accesses local and
// remote, and the cost model's cycles (every access pays the first level's latency, a miss at
// level i the latency of level i+1, memory's after the last: the paper's equation 2 per thread);
// time(p) is the slowest thread's.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "analysis/cache_sim.h"
#include "analysis/machine.h"
#include "analysis/set_associative_cache.h"
#include "analysis/writable_pages.h"
#include "core/table.h"
#include "tracer/access_stream.h"

namespace meshreuse {

struct CoreLevelStats {
  uint64_t accesses = 0, misses = 0, cold = 0, read_misses = 0, write_misses = 0;
  uint64_t coherence = 0;          // misses on lines another core's write removed
  uint64_t inclusion_victims = 0;  // private levels: lines removed by the shared level's eviction
  uint64_t prefetches = 0, prefetch_hits = 0;
  CoreLevelStats& operator+=(const CoreLevelStats& o);
  CoreLevelStats operator-(const CoreLevelStats& o) const;
};

struct ThreadStats {
  std::vector<CoreLevelStats> levels;
  uint64_t memory_local = 0, memory_remote = 0;
  uint64_t invalidations_sent = 0;  // lines this core's writes removed elsewhere
  ThreadStats& operator+=(const ThreadStats& o);
  ThreadStats operator-(const ThreadStats& o) const;
  // The cost model's cycles for these counts on `m` (low and high ends of the latency ranges).
  double CyclesLow(const Machine& m) const;
  double CyclesHigh(const Machine& m) const;
};

class MulticoreSimulation : public AccessConsumer {
 public:
  // A set of prefetched lines counts its lines per bucket line & kFilterMask: a bucket of 0 says
  // a line is not there without a probe (a first-level hit asks at every access).
  static constexpr uint64_t kFilterMask = 1023;

  MulticoreSimulation(const Machine& m, Placement placement);
  ~MulticoreSimulation() override;
  void Begin(const StreamInfo& info) override;  // the threads: placed on cores
  void BeginSweep(int sweep) override;
  // Out of line: its loop's variants (records, groups, prefetch, coherence, the level's set
  // indexing, replacement and tags) are compiled once, here, not in every file that calls it.
  void Consume(const meshreuse::Access* a, size_t n) override;
  // By hand (tests), after Begin or Resize. first_missed: HitFirst has just missed it.
  void Access(int thread, uint64_t address, uint32_t size, bool write, bool first_missed = false) {
    WithRecords([&](auto r) { AccessAs<decltype(r)>(thread, address, size, write, first_missed); });
  }
  void Resize(int threads);

  int threads() const { return static_cast<int>(core_of_.size()); }
  int CoreOf(int thread) const { return core_of_[thread]; }
  const ThreadStats& Stats(int thread) const { return stats_[thread]; }
  // Thread `thread`'s counts in sweep s (0-based, in BeginSweep order; empty before any).
  ThreadStats SweepStats(int thread, size_t s) const;
  size_t sweeps() const { return marks_.size(); }
  const Machine& machine() const { return m_; }
  Placement placement() const { return placement_; }

  // input, ordering, machine, placement, threads, thread, core, socket, sweep ("all", or the
  // 1-based last sweep with last_sweep), level (the machine's, then memory_local, memory_remote),
  // accesses, hits, misses, cold, coherence, inclusion_victims, prefetches, prefetch_hits,
  // read_misses, write_misses, cycles_low, cycles_high (on the level "all" rows only... see .cc).
  static std::vector<std::string> Columns();
  void AppendRows(Table* t, bool last_sweep_only) const;

 private:
  struct Owner;  // a core's or a socket's caches, seen lines and coherence-removed lines
  Owner& CoreOwner(int core);
  Owner& SocketOwner(int socket);
  // Per line: the cores and sockets that may hold it (a superset: the directory coherence
  // consults), those that have missed on it (first touches: cold misses), and those coherence
  // took it from (their next miss on it is a coherence miss). Only the cores of threads ever
  // have a bit, so Bits is as wide as the highest such core needs: 8 bits (8 B a record, padded
  // so that none straddles two host lines), 32 (16 B) or 64 (32 B). A first-level miss reads and
  // writes its line's record, and at 32 B the records of carabiner's 712,810 lines (21.8 MiB)
  // outweighed the sets of every simulated level at 32 threads (13.1 MiB) in the host's caches
  // (issue 40: at 16 B, the 32-thread command 0.90x the time;
  // reports/docs/simulator-performance.md).
  template <class B>
  struct alignas(alignof(B) < 8 ? 8 : alignof(B)) LineInfo {
    using Bits = B;
    Bits cores = 0, seen_cores = 0, removed_cores = 0;
    uint8_t sockets = 0, seen_sockets = 0, removed_sockets = 0;
  };
  using Byte = LineInfo<uint8_t>;
  using Narrow = LineInfo<uint32_t>;
  using Wide = LineInfo<uint64_t>;
  enum class Records { kByte, kNarrow, kWide };
  // f(R()) with the records of this run (Resize chooses them).
  template <class F>
  void WithRecords(F&& f) {
    if (records_ == Records::kByte)
      f(Byte());
    else if (records_ == Records::kNarrow)
      f(Narrow());
    else
      f(Wide());
  }
  // Everything that touches records, for records R (WithRecords).
  template <class R>
  void ConsumeAs(const meshreuse::Access* a, size_t n) {
    if (!fast_) {
      for (size_t i = 0; i < n; ++i) AccessAs<R>(a[i].thread, a[i].address, a[i].size, a[i].write);
      return;
    }
    SetAssociativeCache::WithGroups<4>(l1_groups_, [&](auto g) {
      constexpr uint32_t G = decltype(g)::value;
      for (size_t i = 0; i < n;) {  // a thread's first-level hits in runs, the rest one by one
        const uint8_t t = a[i].thread;
        i = HitRun<G, R>(a, i, n, t);
        if (i == n || a[i].thread != t) continue;
        // A run stopped by a first-level miss: HitFirst's answer, known (SetAssociativeCache::
        // run_missed; the run's cache is the thread's first level, made).
        const FirstLevel& f = first_of_thread_[t];
        const auto r = f.cache && f.cache->run_missed()
                           ? CacheHierarchy::kMissed
                           : HitFirst<G, R>(t, a[i].address, a[i].size, a[i].write);
        if (r == CacheHierarchy::kMissed && !prefetching_)
          MissPlain<R>(t, a[i].address >> shift_, a[i].write);
        else if (r != CacheHierarchy::kHit)
          AccessAs<R>(t, a[i].address, a[i].size, a[i].write, r == CacheHierarchy::kMissed);
        ++i;
      }
    });
  }
  template <class R>
  void AccessAs(int thread, uint64_t address, uint32_t size, bool write, bool first_missed = false);
  template <class R>
  R& Info(uint64_t line);  // never grows the table: ReserveSparse first
  template <class R>
  R* Dense() const {  // the direct array's records
    return static_cast<R*>(dense_.get());
  }
  // The core's first (private) level looked up, when that is all an access may do there (one
  // line): a hit counted as Access counts it (a prefetched line's first demand a prefetch hit)
  // and a write's coherence done (kHit), or a miss with nothing changed (kMissed); otherwise
  // kNotLookedUp (as CacheHierarchy::HitFirst). G: that level's groups (WithGroups).
  // (Consume calls it only where fast_.)
  template <uint32_t G, class R>
  CacheHierarchy::Lookup HitFirst(int thread, uint64_t address, uint32_t size, bool write) {
    const FirstLevel& f = first_of_thread_[thread];
    if (!f.cache) return CacheHierarchy::kNotLookedUp;
    const uint64_t first = address >> shift_;
    if (((address + (size ? size - 1 : 0)) >> shift_) != first) return CacheHierarchy::kNotLookedUp;
    if (!f.cache->Hit<G>(first)) return CacheHierarchy::kMissed;
    ++*f.accesses;
    if (f.prefetch && f.filter[first & kFilterMask]) FirstPrefetchHit<R>(thread, first);
    if (write && coherent_) WriteHit<R>(f, first);
    return CacheHierarchy::kHit;
  }
  // HitFirst's hits over a[from..n) while they are thread t's (SetAssociativeCache::HitRun), and
  // where no level prefetches its one-line first-level misses too (MissPlain): the index of the
  // first access not taken, every one before it done and counted (a hit's write coherence touches
  // other cores' and sockets' levels, never this core's).
  template <uint32_t G, class R>
  [[gnu::always_inline]] size_t HitRun(const meshreuse::Access* a, size_t from, size_t n,
                                       uint8_t t) {
    const FirstLevel& f = first_of_thread_[t];
    if (!f.cache) return from;
    // The level's prefetcher and coherence fixed at compile time (one thread has no coherence:
    // its hits then test nothing). A miss where no level prefetches is done in the run
    // (MissPlain, which counts its first-level access), and the run goes on after it (issue 40:
    // ending the run and starting the next at every miss was about 100 instructions a miss).
    size_t misses = 0;
    auto run = [&](auto prefetch, auto coherent) __attribute__((always_inline)) {
      return f.cache->HitRun<G>(
          from, n, OneLineOf{a, t, shift_},
          [ this, a, t, &f ](size_t i, uint64_t line) __attribute__((always_inline)) {
            if constexpr (decltype(prefetch)::value)
              if (f.filter[line & kFilterMask]) FirstPrefetchHit<R>(t, line);
            if constexpr (decltype(coherent)::value)
              if (a[i].write) WriteHit<R>(f, line);
          },
          [ this, a, t, &misses ](size_t i, uint64_t line) __attribute__((always_inline)) {
            if (decltype(prefetch)::value || prefetching_) return false;
            MissPlain<R>(t, line, a[i].write);
            ++misses;
            return true;
          });
    };
    using Yes = std::true_type;
    using No = std::false_type;
    const size_t end = f.prefetch ? (coherent_ ? run(Yes(), Yes()) : run(Yes(), No()))
                                  : (coherent_ ? run(No(), Yes()) : run(No(), No()));
    *f.accesses += end - from - misses;
    return end;
  }
  // Coherence of a write hit by f's thread: the line held elsewhere is taken away. Inline the
  // common case, a record in the direct array that names no other core or socket (one load).
  struct FirstLevel;
  template <class R>
  void WriteHit(const FirstLevel& f, uint64_t line) {
    if (line - info_base_ < kDenseLines) {
      const R& e = Dense<R>()[line - info_base_];
      if (!(e.cores & f.other_cores) && !(e.sockets & f.other_sockets)) return;
    }
    WriteHitSlow<R>(f.core, line);
  }
  template <class R>
  void WriteHitSlow(int core, uint64_t line);
  // What Access(thread, address, size, write, true) does for a one-line access where no level
  // prefetches (the report's machine runs but the prefetcher's): the same counts and changes, in
  // the same order, along the thread's levels found once (LevelsOf) instead of level by level
  // through the general loop, which weighs each level's prefetcher, owner and the access's second
  // line (by callgrind at 32 threads, 1,211 instructions a first-level miss there).
  template <class R>
  void MissPlain(int thread, uint64_t line, bool write);
  // Thread `thread`'s FirstLevel with its levels (FirstLevel::levels) made (at every miss: the
  // made case inline).
  const FirstLevel& LevelsOf(int thread) {
    const FirstLevel& f = first_of_thread_[thread];
    return f.levels_made ? f : MakeLevels(thread);
  }
  const FirstLevel& MakeLevels(int thread);
  // A first-level hit where that level prefetches: if the line was prefetched and not demanded
  // since, a prefetch hit (as Access counts it). Touches the set of prefetched lines, not the
  // level. Called only where the set's filter (FirstLevel::filter) says it may hold the line.
  template <class R>
  void FirstPrefetchHit(int thread, uint64_t line);
  // Level `level` (the machine's index) of `o` took `line` out (~0: nothing): out of that level's
  // prefetched lines too where held_only_ (see Owner in the .cc).
  void Removed(Owner& o, size_t level, uint64_t line);
  // The sets of `line` at every level below the first (f's, from LevelsOf) and its record,
  // asked of the host (no change to any level) as a first-level miss begins: the lookups that
  // follow go one after another, each likely a host miss (a socket's 24 MiB level is 3 MiB of
  // sets), and asked at once their misses overlap instead of adding up. kNext: line + 1's too,
  // in the same pass (SetAssociativeCache::PrefetchSetAndNext).
  template <bool kNext, class R>
  void PrefetchBelow(const FirstLevel& f, uint64_t line);
  template <class R>
  void ReserveSparse(uint64_t more);
  // The line out of the private levels of the socket's cores (those with a thread: no other
  // core has levels, socket_cores_) whose bit (core % cores_per_socket) `local` has.
  void BackInvalidate(int socket, uint64_t line, uint64_t local = ~uint64_t{0});
  // Back-invalidation's filter (issue 40). An inclusive shared level's eviction took the line
  // out of every private level of the socket's cores in turn, and almost never found it there:
  // carabiner ORI at 8 threads compact, two sweeps, 1.06 M evictions of the one socket's L3, 16
  // lookups each, 31 inclusion victims. So where the machine's shared level is one, inclusive,
  // keeps its lines in their ways (LRU or FIFO) and serves at most 8 cores, each of its ways keeps
  // the socket's cores whose private levels may hold its line (a bit a core: a superset, since a
  // private level's own eviction leaves the bit), and an eviction looks in those alone. Nothing
  // reads the bits before a socket's first eviction, so they are made then, from the private
  // levels as they are, and kept from then on.
  struct Holders {
    bool active = false;
    std::vector<uint8_t> cores;  // per slot of the level (SetAssociativeCache::SlotOf)
  };
  // The socket's shared level `c` has just looked `line` up for `core` (Access: `hit`, or an
  // install whose victim is c.victim()); to_core: the core's private levels hold the line too (a
  // demand access, or a private prefetcher's fill). The victim back-invalidated, the bits kept.
  // (Only for an inclusive shared level.)
  void SharedTook(int socket, SetAssociativeCache& c, uint64_t line, bool hit, int core,
                  bool to_core) {
    if (!holders_[socket].active) {
      if (!hit && c.victim() != ~uint64_t{0}) FirstEviction(socket, c);
      return;
    }
    HoldersTook(socket, c, line, hit, core, to_core);
  }
  // Until the bits are kept: the victim out of every core, then the bits made where they may be.
  void FirstEviction(int socket, SetAssociativeCache& c);
  void HoldersTook(int socket, SetAssociativeCache& c, uint64_t line, bool hit, int core,
                   bool to_core);
  template <class R>
  void InvalidateOthers(int core, R& e, uint64_t line);
  int HomeSocket(uint64_t line) const;

  Machine m_;
  Placement placement_;
  StreamInfo info_;
  int shift_;
  size_t private_levels_;
  size_t levels_n_;           // m_.levels.size(), at every miss
  uint32_t reach_back_ = 0;   // bit i: level i is shared and inclusive (its evictions reach back)
  std::vector<int> core_of_;  // per thread
  std::vector<int> thread_of_core_;                      // -1: idle core
  std::vector<std::vector<int>> socket_cores_;           // per socket, its cores with a thread
  std::vector<ThreadStats> stats_;                       // per thread
  std::vector<std::unique_ptr<Owner>> cores_, sockets_;  // made at first use
  bool coherent_ = false;                                // coherence on and more than one thread
  bool fast_ = false;                 // HitFirst may answer: a private first level
  uint32_t l1_groups_ = 0;            // the first level's groups of ways
  std::vector<bool> held_only_;       // per level: its prefetched lines are lines it holds
  bool drop_any_ = false;             // some level's are
  bool prefetching_ = false;          // some level has a prefetcher
  bool holders_ok_ = false;           // the filter may be kept (Holders)
  std::vector<Holders> holders_;      // per socket
  Records records_ = Records::kWide;  // by the highest core a thread is on (Resize)
  // Per thread, what HitFirst needs in one place: its core's first level (null until made), that
  // level's access count in the thread's stats, its core, whether that level prefetches, and then
  // the filter of its set of prefetched lines (made with the level); and for a first-level miss
  // its socket and every level of its path in the machine's order (made by LevelsOf, at the
  // thread's first miss that asks).
  struct FirstLevel {
    SetAssociativeCache* cache = nullptr;
    uint64_t* accesses = nullptr;
    int core = 0;
    bool prefetch = false;
    const uint32_t* filter = nullptr;
    uint64_t other_cores = 0;   // every core's bit but its core's (WriteHit)
    uint8_t other_sockets = 0;  // every socket's bit but its socket's
    int socket = 0;
    bool levels_made = false;
    SetAssociativeCache* levels[Machine::kMaxLevels] = {};
  };
  std::vector<FirstLevel> first_of_thread_;
  // Line records: a direct array for the 2^22 lines from the stream's base (the canonical arrays
  // of a mesh of a few million vertices; calloc'ed, so pages cost memory only once touched), a
  // hash table beyond.
  static constexpr uint64_t kDenseLines = uint64_t{1} << 22;
  struct Free {
    void operator()(void* p) const { std::free(p); }
  };
  std::unique_ptr<void, Free> dense_;
  WritablePages info_pages_;  // dense_'s pages, made writable at a line's first miss
  uint64_t info_base_ = 0;
  template <class R>
  struct SparseEntry {
    uint64_t line = ~uint64_t{0};
    R info;
  };
  // One of them in use, by records_.
  std::tuple<std::vector<SparseEntry<Byte>>, std::vector<SparseEntry<Narrow>>,
             std::vector<SparseEntry<Wide>>>
      sparse_;
  template <class R>
  std::vector<SparseEntry<R>>& Sparse() {
    return std::get<std::vector<SparseEntry<R>>>(sparse_);
  }
  uint64_t sparse_used_ = 0;
  std::vector<std::vector<ThreadStats>> marks_;  // [sweep][thread] at its start
};

}  // namespace meshreuse
