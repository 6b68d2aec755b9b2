// Many-core cache simulation; see multicore_sim.h.
#include "analysis/multicore_sim.h"

#include <algorithm>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <string>

#include "core/access.h"
#include "core/error.h"
#include "core/schedule.h"

namespace meshreuse {

namespace {

uint64_t Mix(uint64_t x) {  // SplitMix64's finaliser: consecutive lines spread over the table
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A set of lines (all below 2^63): open addressing, linear probing, erase by backward shift (no
// tombstones, so a lookup of a line not held stops at the first empty slot: with at most half
// the slots taken, a probe or two). The first level's prefetched lines are looked up at every
// hit there, mostly lines not held; with tombstones (the form before) a table that churned at a
// steady size filled up to three quarters and such a lookup walked about eight slots, a quarter
// of a one-thread prefetch run's time.
class LineSet {
 public:
  static constexpr uint64_t kMask = MulticoreSimulation::kFilterMask;
  bool Insert(uint64_t line) {  // true if it was new
    if (2 * (size_ + 1) > slots_.size()) Grow();
    const uint64_t m = slots_.size() - 1;
    for (uint64_t i = Mix(line) & m;; i = (i + 1) & m) {
      if (slots_[i] == line) return false;
      if (slots_[i] == kEmpty) {
        slots_[i] = line;
        ++size_;
        ++filter_[line & kMask];
        return true;
      }
    }
  }
  bool Erase(uint64_t line) {
    if (filter_[line & kMask] == 0) return false;
    const uint64_t m = slots_.size() - 1;
    uint64_t i = Mix(line) & m;
    for (;; i = (i + 1) & m) {
      if (slots_[i] == line) break;
      if (slots_[i] == kEmpty) return false;
    }
    // Knuth's algorithm R: each later line of the cluster whose home is not cyclically in
    // (hole, its slot] moves back into the hole, so every line stays reachable from its home.
    for (uint64_t j = i;;) {
      j = (j + 1) & m;
      if (slots_[j] == kEmpty) break;
      const uint64_t home = Mix(slots_[j]) & m;
      if (((j - home) & m) >= ((j - i) & m)) {
        slots_[i] = slots_[j];
        i = j;
      }
    }
    slots_[i] = kEmpty;
    --size_;
    --filter_[line & kMask];
    return true;
  }
  bool empty() const { return size_ == 0; }
  // Per bucket line & kMask, the lines held (the vector is never resized: the pointer stays).
  const uint32_t* filter() const { return filter_.data(); }
  bool Contains(uint64_t line) const {
    if (filter_[line & kMask] == 0) return false;
    const uint64_t m = slots_.size() - 1;
    for (uint64_t i = Mix(line) & m;; i = (i + 1) & m) {
      if (slots_[i] == line) return true;
      if (slots_[i] == kEmpty) return false;
    }
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  void Grow() {  // twice the slots, the lines inserted again (their counts too)
    std::vector<uint64_t> old(2 * slots_.size(), kEmpty);
    old.swap(slots_);
    size_ = 0;
    std::fill(filter_.begin(), filter_.end(), 0);
    for (uint64_t x : old)
      if (x != kEmpty) Insert(x);
  }
  std::vector<uint64_t> slots_ = std::vector<uint64_t>(16, kEmpty);
  uint64_t size_ = 0;  // lines held
  std::vector<uint32_t> filter_ = std::vector<uint32_t>(kMask + 1, 0);
};

}  // namespace

// Per level, `prefetched` holds the lines that its prefetcher brought there and no demand there
// has touched since. At a prefetching level with none above it (the first level, in practice),
// the set also keeps only lines the level holds: a line leaves it when evicted or invalidated
// too, since such a level gets a line back only by its own demand miss (which takes it out
// anyway) or its own prefetch (which puts it in again). Below another prefetcher a line can come
// back by that one's fill, still counted as this level's prefetched line, so there it stays.
// (Kept, evicted lines changed no count but made the set grow with every prefetch never used: a
// hash lookup far out in memory on every first-level hit.)
struct MulticoreSimulation::Owner {
  std::vector<SetAssociativeCache> caches;  // the levels it holds, in the machine's order
  std::vector<LineSet> prefetched;          // per level (see above)
};

MulticoreSimulation::MulticoreSimulation(const Machine& m, Placement placement)
    : m_(m),
      placement_(placement),
      private_levels_(m.private_levels()),
      levels_n_(m.levels.size()) {
  // Machines come checked (machine.h's Check); a thread's levels are a fixed array (FirstLevel).
  if (m.levels.size() > Machine::kMaxLevels)
    throw std::logic_error("MulticoreSimulation: more than Machine::kMaxLevels levels");
  shift_ = __builtin_ctz(m.line_bytes);
  fast_ = private_levels_ > 0;
  bool above = false;  // a prefetcher at a level above
  for (size_t i = private_levels_; i < m.levels.size(); ++i)
    if (m.levels[i].inclusive) reach_back_ |= uint32_t{1} << i;
  for (const MachineLevel& l : m.levels) {
    held_only_.push_back(l.prefetch && !above);
    above = above || l.prefetch;
    drop_any_ = drop_any_ || held_only_.back();
    prefetching_ = prefetching_ || l.prefetch;
  }
  if (!m.levels.empty()) l1_groups_ = SetAssociativeCache::GroupsOf(m.levels[0].cache.ways);
  holders_ok_ = private_levels_ + 1 == m.levels.size() && m.levels.back().inclusive &&
                m.levels.back().cache.policy != Replacement::kRandom && m.cores_per_socket <= 8;
  cores_.resize(m.cores());
  sockets_.resize(m.sockets);
}

MulticoreSimulation::~MulticoreSimulation() = default;

void MulticoreSimulation::Begin(const StreamInfo& info) {
  info_ = info;
  Resize(info.threads);
}

void MulticoreSimulation::Resize(int threads) {
  core_of_ = PlaceThreads(m_, threads, placement_);
  coherent_ = m_.coherence && threads > 1;  // one core has no one to invalidate
  thread_of_core_.assign(m_.cores(), -1);
  for (int t = 0; t < threads; ++t) thread_of_core_[core_of_[t]] = t;
  socket_cores_.assign(m_.sockets, {});
  for (int core = 0; core < m_.cores(); ++core)  // in core order, as the loop over all was
    if (thread_of_core_[core] >= 0) socket_cores_[core / m_.cores_per_socket].push_back(core);
  stats_.assign(threads, ThreadStats());
  for (ThreadStats& s : stats_) s.levels.resize(m_.levels.size());
  for (auto& c : cores_) c.reset();
  first_of_thread_.assign(threads, FirstLevel());
  for (int t = 0; t < threads; ++t) {
    first_of_thread_[t].core = core_of_[t];
    first_of_thread_[t].other_cores = ~(uint64_t{1} << core_of_[t]);
    first_of_thread_[t].socket = core_of_[t] / m_.cores_per_socket;
    first_of_thread_[t].other_sockets = static_cast<uint8_t>(~(1u << first_of_thread_[t].socket));
    first_of_thread_[t].prefetch = private_levels_ > 0 && m_.levels[0].prefetch;
    if (!m_.levels.empty()) first_of_thread_[t].accesses = &stats_[t].levels.front().accesses;
  }
  for (auto& s : sockets_) s.reset();
  holders_.assign(m_.sockets, Holders());
  info_base_ = info_.canonical ? AddressCanonicalizer::kCanonicalBase >> shift_ : 0;
  const int top = core_of_.empty() ? 0 : *std::max_element(core_of_.begin(), core_of_.end());
  records_ = top < 8 ? Records::kByte : top < 32 ? Records::kNarrow : Records::kWide;
  size_t record = 0;
  sparse_ = decltype(sparse_)();
  WithRecords([&](auto r) {
    using R = decltype(r);
    record = sizeof(R);
    Sparse<R>().assign(1024, SparseEntry<R>());
  });
  dense_.reset(std::calloc(kDenseLines, record));
  if (!dense_) throw std::bad_alloc();
  info_pages_.Reset(dense_.get(), kDenseLines * record);
  sparse_used_ = 0;
  marks_.clear();
}

MulticoreSimulation::Owner& MulticoreSimulation::CoreOwner(int core) {
  if (!cores_[core]) {
    cores_[core] = std::make_unique<Owner>();
    for (size_t i = 0; i < private_levels_; ++i) {
      const CacheLevel& l = m_.levels[i].cache;
      cores_[core]->caches.emplace_back(l.bytes, l.ways, m_.line_bytes, l.policy);
    }
    cores_[core]->prefetched.resize(private_levels_);
    if (private_levels_ > 0 && thread_of_core_[core] >= 0) {
      FirstLevel& f = first_of_thread_[thread_of_core_[core]];
      f.cache = &cores_[core]->caches.front();
      f.filter = cores_[core]->prefetched.front().filter();
    }
  }
  return *cores_[core];
}

MulticoreSimulation::Owner& MulticoreSimulation::SocketOwner(int socket) {
  if (!sockets_[socket]) {
    sockets_[socket] = std::make_unique<Owner>();
    for (size_t i = private_levels_; i < m_.levels.size(); ++i) {
      const CacheLevel& l = m_.levels[i].cache;
      sockets_[socket]->caches.emplace_back(l.bytes, l.ways, m_.line_bytes, l.policy);
    }
    sockets_[socket]->prefetched.resize(m_.levels.size() - private_levels_);
  }
  return *sockets_[socket];
}

// Room for `more` new sparse records without growing: Access takes references to records and
// then looks more up (a straddling access's second line, prefetched lines: at most 4 new), so the
// table grows before, never while a reference is held.
template <class R>
void MulticoreSimulation::ReserveSparse(uint64_t more) {
  std::vector<SparseEntry<R>>& sparse = Sparse<R>();
  if (4 * (sparse_used_ + more) > 3 * sparse.size()) {
    std::vector<SparseEntry<R>> old(2 * sparse.size());
    old.swap(sparse);
    const uint64_t m = sparse.size() - 1;
    for (const SparseEntry<R>& e : old)
      if (e.line != ~uint64_t{0}) {
        uint64_t i = Mix(e.line) & m;
        while (sparse[i].line != ~uint64_t{0}) i = (i + 1) & m;
        sparse[i] = e;
      }
  }
}

template <class R>
R& MulticoreSimulation::Info(uint64_t line) {
  if (line - info_base_ < kDenseLines) return Dense<R>()[line - info_base_];
  std::vector<SparseEntry<R>>& sparse = Sparse<R>();
  const uint64_t m = sparse.size() - 1;
  for (uint64_t i = Mix(line) & m;; i = (i + 1) & m) {
    if (sparse[i].line == line) return sparse[i].info;
    if (sparse[i].line == ~uint64_t{0}) {
      sparse[i].line = line;
      ++sparse_used_;
      return sparse[i].info;
    }
  }
}

int MulticoreSimulation::HomeSocket(uint64_t line) const {
  if (m_.numa == Numa::kFirstTouch) return 0;
  return static_cast<int>(((line << shift_) >> 12) % static_cast<uint64_t>(m_.sockets));
}

template <class R>
void MulticoreSimulation::WriteHitSlow(int core, uint64_t line) {
  ReserveSparse<R>(1);  // (the line's record exists: it missed here before; this keeps Info's rule)
  R& e = Info<R>(line);
  const int socket = core / m_.cores_per_socket;
  if ((e.cores & ~(uint64_t{1} << core)) || (e.sockets & ~(1u << socket) & 0xFFu))
    InvalidateOthers<R>(core, e, line);
}

void MulticoreSimulation::Removed(Owner& o, size_t level, uint64_t line) {
  if (!held_only_[level] || line == ~uint64_t{0}) return;
  LineSet& set = o.prefetched[level < private_levels_ ? level : level - private_levels_];
  if (!set.empty()) set.Erase(line);
}

template <class R>
void MulticoreSimulation::FirstPrefetchHit(int thread, uint64_t line) {
  const int core = core_of_[thread];
  LineSet& set = cores_[core]->prefetched.front();
  if (set.empty() || !set.Erase(line)) return;
  ++stats_[thread].levels.front().prefetch_hits;
  ReserveSparse<R>(1);
  Info<R>(line).seen_cores |= typename R::Bits{1} << core;  // its first demand: not new
}

void MulticoreSimulation::BackInvalidate(int socket, uint64_t line, uint64_t local) {
  for (const int core : socket_cores_[socket]) {
    if (!cores_[core] || !(local >> (core - socket * m_.cores_per_socket) & 1)) continue;
    Owner& o = *cores_[core];
    const int t = thread_of_core_[core];
    for (size_t i = 0; i < private_levels_; ++i)
      if (o.caches[i].Invalidate(line)) {
        if (drop_any_) Removed(o, i, line);
        if (t >= 0) ++stats_[t].levels[i].inclusion_victims;
      }
  }
}

void MulticoreSimulation::FirstEviction(int socket, SetAssociativeCache& c) {
  BackInvalidate(socket, c.victim());
  // With one to three cores, looking in each is cheaper than the bits (the harness at one thread:
  // 7.3-8.7 ns an access with them, 6.4-7.8 without).
  if (!holders_ok_ || socket_cores_[socket].size() < 4) return;
  // Every line of the socket's cores' private levels is in `c` (inclusion), and only they need a
  // bit: the line just installed is among them, the victim no longer.
  Holders& h = holders_[socket];
  h.cores.assign(c.slots(), 0);
  for (const int core : socket_cores_[socket]) {
    if (!cores_[core]) continue;
    const uint8_t bit = static_cast<uint8_t>(1u << (core - socket * m_.cores_per_socket));
    for (size_t i = 0; i < private_levels_; ++i)
      cores_[core]->caches[i].ForEachLine([&](uint64_t line) {
        const uint64_t k = c.SlotOf(line);
        if (k != ~uint64_t{0}) h.cores[k] |= bit;
      });
  }
  h.active = true;
}

void MulticoreSimulation::HoldersTook(int socket, SetAssociativeCache& c, uint64_t line, bool hit,
                                      int core, bool to_core) {
  Holders& h = holders_[socket];
  const uint64_t k = c.SlotOf(line);
  const uint8_t bit =
      to_core ? static_cast<uint8_t>(1u << (core - socket * m_.cores_per_socket)) : 0;
  if (hit) {
    h.cores[k] |= bit;
    return;
  }
  // The line took the victim's way: its bits are the victim's until now.
  if (c.victim() != ~uint64_t{0}) BackInvalidate(socket, c.victim(), h.cores[k]);
  h.cores[k] = bit;
}

template <class R>
void MulticoreSimulation::InvalidateOthers(int core, R& e, uint64_t line) {
  using Bits = typename R::Bits;
  const int socket = core / m_.cores_per_socket;
  const int t = thread_of_core_[core];
  for (uint64_t others = e.cores & ~(uint64_t{1} << core); others; others &= others - 1) {
    const int d = __builtin_ctzll(others);  // a thread's core: within Bits
    Owner& o = *cores_[d];
    bool held = false;
    for (size_t i = 0; i < private_levels_; ++i)
      if (o.caches[i].Invalidate(line)) {
        if (drop_any_) Removed(o, i, line);
        held = true;
      }
    if (held) {
      e.removed_cores |= Bits{1} << d;
      ++stats_[t].invalidations_sent;
    }
  }
  for (unsigned others = e.sockets & ~(1u << socket) & 0xFFu; others; others &= others - 1) {
    const int s = __builtin_ctz(others);
    Owner& o = *sockets_[s];
    bool held = false;
    for (size_t i = 0; i < o.caches.size(); ++i)
      if (o.caches[i].Invalidate(line)) {
        if (drop_any_) Removed(o, private_levels_ + i, line);
        held = true;
      }
    if (held) {
      e.removed_sockets = static_cast<uint8_t>(e.removed_sockets | (1u << s));
      ++stats_[t].invalidations_sent;
    }
  }
  e.cores &= Bits{1} << core;
  e.sockets = static_cast<uint8_t>(e.sockets & (1u << socket));
}

template <bool kNext, class R>
[[gnu::always_inline]] inline void MulticoreSimulation::PrefetchBelow(const FirstLevel& f,
                                                                      uint64_t line) {
  const size_t n = levels_n_;  // (a local: a page's populating call would make it a reload)
  for (size_t i = 1; i < n; ++i)
    kNext ? f.levels[i]->PrefetchSetAndNext(line) : f.levels[i]->PrefetchSet(line);
  if (const Holders& h = holders_[f.socket]; h.active) {  // the set's bits, to be read and written
    const SetAssociativeCache& c = *f.levels[n - 1];
    for (uint64_t l = line; l <= line + kNext; ++l) {
      const uint8_t* b = h.cores.data() + c.FirstSlotOf(l);
      __builtin_prefetch(b, 1);
      __builtin_prefetch(b + c.ways() - 1, 1);
    }
  }
  if (const uint64_t k = line - info_base_; k < kDenseLines) {
    const R* e = Dense<R>() + k;
    const bool both = kNext && k + 1 < kDenseLines;
    info_pages_.Touch(e, (1 + both) * sizeof(R));
    __builtin_prefetch(e, 1);
    if (both) __builtin_prefetch(e + 1, 1);  // (most often the same host line)
  }
}

template <class R>
void MulticoreSimulation::AccessAs(int thread, uint64_t address, uint32_t size, bool write,
                                   bool first_missed) {
  using Bits = typename R::Bits;
  const int core = core_of_[thread];
  const int socket = core / m_.cores_per_socket;
  const Bits cbit = Bits{1} << core;
  const uint8_t sbit = static_cast<uint8_t>(1u << socket);
  ThreadStats& st = stats_[thread];
  const uint64_t first = address >> shift_;
  const uint64_t last = (address + (size ? size - 1 : 0)) >> shift_;
  ReserveSparse<R>(2 * (last - first + 1));
  if (first_missed) {  // the levels below will be looked up
    const FirstLevel& f = LevelsOf(thread);
    if (prefetching_)  // and a prefetcher's next line
      PrefetchBelow<true, R>(f, first);
    else
      PrefetchBelow<false, R>(f, first);
  }
  // Per line of the access (two when it straddles), its record, fetched at its first miss.
  R* info[2] = {nullptr, nullptr};
  bool missed_private = false, missed_shared = false;
  Owner* owner = &CoreOwner(core);
  size_t base = 0;          // the owner's first level
  bool owner_cold = false;  // a line of this access is new to the owner (decided at its first)
  bool missed_all = true;
  for (size_t i = 0; i < m_.levels.size(); ++i) {
    const bool shared = i >= private_levels_;
    if (i == private_levels_) owner = &SocketOwner(socket), base = private_levels_;
    const MachineLevel& ml = m_.levels[i];
    SetAssociativeCache& cache = owner->caches[i - base];
    CoreLevelStats& s = st.levels[i];
    ++s.accesses;
    if (i == base) owner_cold = false;
    bool hit = true, coherence = false;
    for (uint64_t l = first; l <= last; ++l) {
      if (i == 0 && first_missed) {  // HitFirst has looked it up (one line): a miss
        cache.InstallMissed(l);
      } else if (cache.Access(l)) {
        if (shared && ml.inclusive) SharedTook(socket, cache, l, true, core, true);
        if (ml.prefetch && owner->prefetched[i - base].Erase(l)) {
          ++s.prefetch_hits;
          R& e = Info<R>(l);  // its first demand touch: no longer new to the owner
          if (shared)
            e.seen_sockets |= sbit;
          else
            e.seen_cores |= cbit;
        }
        continue;
      }
      hit = false;
      if (ml.prefetch) Removed(*owner, i, cache.victim());
      R*& slot = info[l - first];
      if (!slot) slot = &Info<R>(l);
      R& e = *slot;
      if (!shared) {
        missed_private = true;
        if (i == base) owner_cold = !(e.seen_cores & cbit) || owner_cold, e.seen_cores |= cbit;
        coherence = (e.removed_cores & cbit) || coherence;
        e.cores |= cbit;
      } else {
        missed_shared = true;
        if (i == base) owner_cold = !(e.seen_sockets & sbit) || owner_cold, e.seen_sockets |= sbit;
        coherence = (e.removed_sockets & sbit) || coherence;
        e.sockets |= sbit;
        if (ml.inclusive) SharedTook(socket, cache, l, false, core, true);
      }
      if (ml.prefetch) owner->prefetched[i - base].Erase(l);
      if (ml.prefetch && !cache.Contains(l + 1)) {
        // The next line, into this level and every level below that lacks it (the request goes
        // down the hierarchy like a miss, so an inclusive level holds what is above it); not a
        // demand access anywhere, counted once, here.
        owner->prefetched[i - base].Insert(l + 1);
        ++s.prefetches;
        R& n = Info<R>(l + 1);  // held now: coherence must find it; not taken away
        for (size_t j = i; j < m_.levels.size(); ++j) {
          const bool sj = j >= private_levels_;
          Owner& oj = sj ? SocketOwner(socket) : CoreOwner(core);
          SetAssociativeCache& cj = oj.caches[sj ? j - private_levels_ : j];
          // (The core's private levels hold l + 1 now where the prefetcher is one of them.)
          const bool to_core = i < private_levels_;
          if (cj.Contains(l + 1)) {
            if (sj && m_.levels[j].inclusive) SharedTook(socket, cj, l + 1, true, core, to_core);
            continue;
          }
          cj.Access(l + 1);
          if (m_.levels[j].prefetch) Removed(oj, j, cj.victim());
          if (!sj) {
            n.cores |= cbit;
            n.removed_cores &= ~cbit;
          } else {
            n.sockets |= sbit;
            n.removed_sockets = static_cast<uint8_t>(n.removed_sockets & ~sbit);
            if (m_.levels[j].inclusive) SharedTook(socket, cj, l + 1, false, core, to_core);
          }
        }
      }
    }
    if (hit) {
      missed_all = false;
      break;
    }
    ++s.misses;
    if (owner_cold) ++s.cold;
    if (coherence) ++s.coherence;
    ++(write ? s.write_misses : s.read_misses);
  }
  for (R* e : info)  // the lines coherence took are back where this access missed
    if (e) {
      if (missed_private) e->removed_cores &= ~cbit;
      if (missed_shared) e->removed_sockets = static_cast<uint8_t>(e->removed_sockets & ~sbit);
    }
  if (missed_all) {
    const bool local = HomeSocket(first) == socket;
    ++(local ? st.memory_local : st.memory_remote);
  }
  if (write && coherent_)
    for (uint64_t l = first; l <= last; ++l) {
      R& e = info[l - first] ? *info[l - first] : Info<R>(l);
      if ((e.cores & ~cbit) || (e.sockets & ~sbit)) InvalidateOthers<R>(core, e, l);
    }
}

const MulticoreSimulation::FirstLevel& MulticoreSimulation::MakeLevels(int thread) {
  FirstLevel& f = first_of_thread_[thread];
  for (size_t i = 0; i < m_.levels.size(); ++i)
    f.levels[i] = i < private_levels_ ? &CoreOwner(f.core).caches[i]
                                      : &SocketOwner(f.socket).caches[i - private_levels_];
  f.levels_made = true;
  return f;
}

template <class R>
void MulticoreSimulation::MissPlain(int thread, uint64_t line, bool write) {
  using Bits = typename R::Bits;
  const FirstLevel& p = LevelsOf(thread);
  const size_t n = levels_n_;
  // The sets and records of the line and of the next line, asked now for a miss that has not
  // happened: a thread's first-level misses run along its arrays (the interior list, the offsets,
  // the triangles in order), so its next is often line + 1, whose sets and record are then in the
  // host's caches. A prefetch changes nothing simulated. (Issue 40: at 32 threads the lookups
  // below stalled on the sets' first host line, 55% of their samples, the line's own prefetch
  // too late to hide it.)
  PrefetchBelow<true, R>(p, line);
  R* e;
  if (line - info_base_ < kDenseLines) {
    e = Dense<R>() + (line - info_base_);
  } else {
    ReserveSparse<R>(1);
    e = &Info<R>(line);
  }
  // The levels first, down to the first that holds the line (`hit`; n: memory), then the record:
  // no level reads it, so its host miss overlaps their lookups instead of stalling before them.
  p.levels[0]->InstallMissedInline(line);
  size_t hit = n;
  for (size_t i = 1; i < n; ++i) {
    SetAssociativeCache& c = *p.levels[i];
    const bool took = c.AccessInline(line);
    if (reach_back_ >> i & 1) SharedTook(p.socket, c, line, took, p.core, true);
    if (took) {
      hit = i;
      break;
    }
  }
  // Each level that missed counts a miss, cold and coherence as its owner's first level decides
  // them (Access: the core's at the first private level, the socket's at the first shared one);
  // the record of removals changes only after.
  const Bits cbit = Bits{1} << p.core;
  const uint8_t sbit = static_cast<uint8_t>(1u << p.socket);
  ThreadStats& st = stats_[thread];
  auto missed = [&](size_t from, size_t to, uint64_t cold, uint64_t coherence) {
    for (size_t i = from; i < to; ++i) {
      CoreLevelStats& s = st.levels[i];
      ++s.accesses, ++s.misses, s.cold += cold, s.coherence += coherence;
      ++(write ? s.write_misses : s.read_misses);
    }
  };
  missed(0, std::min(hit, private_levels_), !(e->seen_cores & cbit),
         (e->removed_cores & cbit) != 0);
  e->seen_cores |= cbit;
  e->cores |= cbit;
  e->removed_cores &= ~cbit;
  if (hit > private_levels_) {  // the socket's first level missed too
    missed(private_levels_, hit, !(e->seen_sockets & sbit), (e->removed_sockets & sbit) != 0);
    e->seen_sockets |= sbit;
    e->sockets |= sbit;
    e->removed_sockets = static_cast<uint8_t>(e->removed_sockets & ~sbit);
  }
  if (hit < n)
    ++st.levels[hit].accesses;
  else
    ++(HomeSocket(line) == p.socket ? st.memory_local : st.memory_remote);
  if (write && coherent_ && ((e->cores & ~cbit) || (e->sockets & ~sbit)))
    InvalidateOthers<R>(p.core, *e, line);
}

void MulticoreSimulation::Consume(const meshreuse::Access* a, size_t n) {
  WithRecords([&](auto r) { ConsumeAs<decltype(r)>(a, n); });
}

// The record-bound paths, for each width (the header's inline code calls them).
#define MESHREUSE_RECORDS(R)                                                                   \
  template void MulticoreSimulation::AccessAs<MulticoreSimulation::R>(int, uint64_t, uint32_t, \
                                                                      bool, bool);             \
  template void MulticoreSimulation::MissPlain<MulticoreSimulation::R>(int, uint64_t, bool);   \
  template void MulticoreSimulation::WriteHitSlow<MulticoreSimulation::R>(int, uint64_t);      \
  template void MulticoreSimulation::FirstPrefetchHit<MulticoreSimulation::R>(int, uint64_t);
MESHREUSE_RECORDS(Byte)
MESHREUSE_RECORDS(Narrow)
MESHREUSE_RECORDS(Wide)
#undef MESHREUSE_RECORDS

}  // namespace meshreuse
