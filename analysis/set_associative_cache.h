// One level of the set-associative simulators (cache_sim.h's per-stream hierarchy,
// multicore_sim.h's machine): `sets` sets of `ways` lines under LRU (valgrind's rules,
// cache_sim.h), FIFO or seeded random replacement, its sets laid out for SIMD lookups, with the hit
// loop both simulators run on their first level (HitRun) and the prefetches their misses ask
// (PrefetchSet). Issue 40 made it three times faster than the most-recent-first array it replaced,
// every choice the same (reports/docs/simulator-performance.md).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <type_traits>
#include <vector>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "analysis/cache_model.h"
#include "analysis/writable_pages.h"
#include "tracer/access_stream.h"

namespace meshreuse {

// One level. Lines are addresses >> log2(line bytes).
//
// Layout (issue 40: a hit in a few instructions, no branch on the data). A set is a block of its
// ways' 32-bit signatures (the low half of the tag, line + 1), which SSE2 compares four at a
// time, then their 32-bit stamps: a set of up to eight ways is one host cache line, of 24 ways
// three. While every tag installed has one high half and a low half other than 0 (a stream
// within 2^32 lines: every trace of the smoother), a signature is the whole tag and 0 an empty
// way, so no tag is kept: a hit reads one block, and a miss names its victim from it. The first
// tag that breaks this (a raw trace of a program's heap and stack) makes the level keep its tags
// (line + 1; 0 = an empty way) in an array beside, written from the signatures then, which
// confirm every signature's match from then on (two lines of one set share a signature only 2^32
// lines apart). Tags stay where they were installed:
//   - LRU: a way's stamp is the level's clock at its last use (0 = empty), so a hit is one store,
//     and a miss replaces the smallest stamp (found by SIMD minimum, no branch on the data): an
//     empty way while one is left, else the least recently used. The order of the stamps is the
//     recency list of valgrind's MRU-first array (the form this class had before, and the naive
//     reference of the tests); an invalidated way becomes empty, the others keep their order, as
//     the array's ways after it moved up.
//   - FIFO: the stamp is the clock at installation; a hit does not change it.
//   - random: the ways keep the old array's positions (an install fills the first empty way, else
//     way rng % ways; an invalidation moves the ways after it up), so seeded runs replace the same
//     lines.
// Only the order of stamps within a set matters, so when the clock reaches its limit (2^31 - 2, or
// a test's) every set's stamps are renumbered 1..k in their order and the clock goes on from the
// largest: the same choices, with stamps that fit 32 bits (and compare as signed, as SSE2 does).
// Ways are padded to a multiple of four with signature 0 and tag 0 (never confirmed: a tag is
// never 0, and without tags no signature looked up is 0); the padding's stamps read as the largest
// (never the victim).
class SetAssociativeCache {
 public:
  // Lines a level may hold: its blocks are allocated up front (calloc: pages as they are touched;
  // 8 B a way, 16 with tags, so at most 1 GiB), and a level of more lines is a mistake (1 B lines
  // in a GiB cache), refused naming the level.
  static constexpr uint64_t kMaxLines = uint64_t{1} << 26;
  // Throws UsageError unless bytes is a multiple of line_bytes * ways.
  SetAssociativeCache(uint64_t bytes, uint32_t ways, uint32_t line_bytes,
                      Replacement policy = Replacement::kLru);
  // The same check, without building the cache.
  static void CheckGeometry(uint64_t bytes, uint32_t ways, uint32_t line_bytes);
  // Groups of four ways (the padded set); and f(std::integral_constant<uint32_t, G>) with G that
  // count where it is a common one (4 to 32 ways), else 0 (any count, known at run time): a loop
  // calling a lookup for many accesses dispatches once, and the lookup's loop unrolls.
  uint32_t groups() const { return groups_; }
  static uint32_t GroupsOf(uint32_t ways) {
    return static_cast<uint32_t>((uint64_t{ways} + 3) / 4);
  }
  // kMax: the most groups fixed. A simulator's hit loop on its first level (HitRun's eight
  // variants, times the many-core simulator's records, prefetch and coherence) fixes only 4 (16
  // ways, the first levels there are), to compile fewer copies of it.
  template <uint32_t kMax = 8, class F>
  static decltype(auto) WithGroups(uint32_t groups, F&& f) {
    using U = uint32_t;
    switch (groups) {
      case 1:
        return f(std::integral_constant<U, 1>());  // up to 4 ways
      case 2:
        return f(std::integral_constant<U, 2>());  // 8
      case 3:
        return f(std::integral_constant<U, 3>());  // 12
      case 4:
        return f(std::integral_constant<U, 4>());  // 16
      case 6:
        if constexpr (kMax >= 6) return f(std::integral_constant<U, 6>());  // 24
        break;
      case 8:
        if constexpr (kMax >= 8) return f(std::integral_constant<U, 8>());  // 32
        break;
      default:
        break;
    }
    return f(std::integral_constant<U, 0>());
  }
  // Looks `line` up; on a hit moves it to the front of its set, on a miss installs it there
  // (evicting the least recently used). Returns true on a hit.
  bool Access(uint64_t line) {
    return WithGroups(groups_, [&](auto g) {
      if (Hit<decltype(g)::value>(line)) return true;
      Install<decltype(g)::value>(SetOf(line), line + 1);
      return false;
    });
  }
  // Access with the lookup in the caller: a simulator's miss path, which looks up a level or two
  // below at every first-level miss (issue 40: the call and its dispatch were a fifth of such a
  // lookup's instructions by callgrind).
  [[gnu::always_inline]] bool AccessInline(uint64_t line) {
    auto go = [&](auto g) __attribute__((always_inline)) {
      if (Hit<decltype(g)::value>(line)) return true;
      Install<decltype(g)::value>(SetOf(line), line + 1);
      return false;
    };
    switch (groups_) {  // the report's machines' levels below the first: 8, 16 and 24 ways
      case 2:
        return go(std::integral_constant<uint32_t, 2>());
      case 4:
        return go(std::integral_constant<uint32_t, 4>());
      case 6:
        return go(std::integral_constant<uint32_t, 6>());
      default:
        return Access(line);
    }
  }
  // A hit does what Access does; a miss changes nothing and returns false. G: groups(), or 0.
  template <uint32_t G>
  [[gnu::always_inline]] bool Hit(uint64_t line) {
    const Set s = SetOf(line);  // a set never touched: its signatures 0, never confirmed
    const uint32_t w = Find<G>(s, line + 1);
    if (w == kNone) return false;
    if (policy_ == Replacement::kLru) s.stamp[w] = Tick();
    return true;
  }
  // Hit over a run (issue 40: statistics per batch, the clock in a register): for i = from, from
  // + 1, ... below n, line_of(i, line) sets access i's one line and returns true (false: not one
  // this loop may take), and each that hits is done as Hit does it (but the run's last line again
  // takes no new stamp: no order in any set changes, and only that order is ever compared), then
  // on_hit(i, line) is called (it must not touch this level). At a miss, on_miss(i, line) is
  // called with nothing changed: it returns false to end the run there, or true once it has done
  // the whole access, the line installed here (by InstallMissed, so with the newest stamp), and
  // the run goes on. Returns the first i not taken (line_of's false, a miss on_miss declined, the
  // clock near its limit, or the level's tags changed by a miss); nothing of it has changed. G:
  // groups(), or 0. (Inline in the caller with its loop, so that the caller's functions' fields,
  // such as the stream, stay in registers, which a stamp's store would make the loop reload.)
  template <uint32_t G, class LineOf, class OnHit, class OnMiss>
  [[gnu::always_inline]] size_t HitRun(size_t from, size_t n, LineOf&& line_of, OnHit&& on_hit,
                                       OnMiss&& on_miss) {
    // The loop's variants fixed at compile time (set by mask or remainder; a hit's stamp or not;
    // the tags kept or not), so that a hit is a few dozen instructions.
    const bool tick = policy_ == Replacement::kLru;
    auto run = [&](auto pow2, auto tagged) __attribute__((always_inline)) {
      constexpr bool kPow2 = decltype(pow2)::value, kSig = !decltype(tagged)::value;
      return tick ? Run<G, kPow2, true, kSig>(from, n, line_of, on_hit, on_miss)
                  : Run<G, kPow2, false, kSig>(from, n, line_of, on_hit, on_miss);
    };
    using Yes = std::true_type;
    using No = std::false_type;
    if (pow2_) return tagged_ ? run(Yes(), Yes()) : run(Yes(), No());
    return tagged_ ? run(No(), Yes()) : run(No(), No());
  }
  template <uint32_t G, class LineOf, class OnHit>
  size_t HitRun(size_t from, size_t n, LineOf&& line_of, OnHit&& on_hit) {
    return HitRun<G>(from, n, line_of, on_hit, [](size_t, uint64_t) { return false; });
  }
  // Whether the last HitRun stopped at a miss: at an access line_of took, whose line this level
  // does not hold. Nothing changed, as after Hit's false: the caller need not look it up again.
  bool run_missed() const { return run_missed_; }
  // What Access does after a miss, for a caller whose Hit just returned false.
  void InstallMissed(uint64_t line) {
    WithGroups(groups_, [&](auto g) { Install<decltype(g)::value>(SetOf(line), line + 1); });
  }
  // InstallMissed with the install in the caller, for a simulator's miss path (as AccessInline).
  [[gnu::always_inline]] void InstallMissedInline(uint64_t line) {
    auto go = [&](auto g) __attribute__((always_inline)) {
      Install<decltype(g)::value>(SetOf(line), line + 1);
    };
    if (groups_ == 2)  // 8 ways: the report's machines' first levels
      go(std::integral_constant<uint32_t, 2>());
    else
      InstallMissed(line);
  }
  // Asks the host to bring `line`'s set into its caches (no change to the level): a caller that
  // knows it will look the line up here soon, after other work, overlaps the set's host misses.
  // The set's pages are made writable first (WritablePages; levels of 64 KiB or more).
  void PrefetchSet(uint64_t line) {
    const uint64_t set = pow2_ ? (line & mask_) : (line % sets_);
    const uint8_t* b = base_ + set * block_bytes_;
    pages_.Touch(b, block_bytes_);
    __builtin_prefetch(b, 1);  // (a set of up to eight ways is one host line)
    for (uint64_t o = 64; o < block_bytes_; o += 64) __builtin_prefetch(b + o, 1);
    if (tagged_) {
      const uint64_t* t = tags_.get() + set * padded_;
      tag_pages_.Touch(t, 8 * uint64_t{padded_});
      __builtin_prefetch(t, 1);
    }
  }
  // PrefetchSet(line) and PrefetchSet(line + 1) in one (a first-level miss of the many-core
  // simulator asks for both): the two sets are neighbours unless line's is the last, so one pages'
  // check and one run of prefetches over both blocks (issue 40: two calls of the general form,
  // the record's with them, were 238 instructions a miss by callgrind at 32 threads).
  void PrefetchSetAndNext(uint64_t line) {
    const uint64_t set = pow2_ ? (line & mask_) : (line % sets_);
    if (__builtin_expect(set + 1 == sets_, 0)) {  // line + 1's set is the first
      PrefetchSet(line);
      PrefetchSet(line + 1);
      return;
    }
    const uint8_t* b = base_ + set * block_bytes_;
    pages_.Touch(b, 2 * block_bytes_);
    for (uint64_t o = 0; o < 2 * block_bytes_; o += 64) __builtin_prefetch(b + o, 1);
    if (tagged_) {
      const uint64_t* t = tags_.get() + set * padded_;
      tag_pages_.Touch(t, 16 * uint64_t{padded_});
      __builtin_prefetch(t, 1);
      __builtin_prefetch(t + 2 * padded_ - 1, 1);
    }
  }
  // The line the last missing Access evicted, ~0 if it filled an empty way.
  uint64_t victim() const { return victim_; }
  // Whether `line` is held (no change to the set's order).
  bool Contains(uint64_t line) const { return Find<0>(SetOf(line), line + 1) != kNone; }
  // Removes `line` if held (the ways after it move up in the recency list): coherence and
  // inclusion. Returns whether it was held.
  bool Invalidate(uint64_t line);
  // Where `line` is held: its set's index times the padded ways, plus its way (< slots()); ~0 if
  // not held. A line keeps its slot while held, except under kRandom, whose invalidation moves the
  // ways after it up (a caller keeping data per slot uses LRU or FIFO levels).
  uint64_t SlotOf(uint64_t line) const {
    return WithGroups(groups_, [&](auto g) {
      const Set s = SetOf(line);
      const uint32_t w = Find<decltype(g)::value>(s, line + 1);
      return w == kNone ? ~uint64_t{0} : s.index * padded_ + w;
    });
  }
  uint64_t slots() const { return sets_ * padded_; }
  // The first slot of `line`'s set (its ways' slots follow).
  uint64_t FirstSlotOf(uint64_t line) const {
    return (pow2_ ? (line & mask_) : (line % sets_)) * padded_;
  }
  // f(line) for every line held, in no particular order.
  template <class F>
  void ForEachLine(F&& f) const {
    for (uint64_t i = 0; i < sets_; ++i) {
      const uint32_t* sig = reinterpret_cast<const uint32_t*>(base_ + i * block_bytes_);
      for (uint32_t w = 0; w < ways_; ++w) {
        if (tagged_) {
          if (const uint64_t t = tags_[i * padded_ + w]) f(t - 1);
        } else if (sig[w]) {
          f((high_ << 32 | sig[w]) - 1);
        }
      }
    }
  }
  uint64_t sets() const { return sets_; }
  uint32_t ways() const { return ways_; }
  // Tests: renumber the stamps when the clock reaches `limit` (>= ways + 1) instead of 2^31 - 2.
  void LimitClockForTest(uint32_t limit) { limit_ = limit; }

 private:
  static constexpr uint32_t kNone = ~0u;
  struct Set {
    uint32_t* sig;
    uint32_t* stamp;
    uint64_t index;
  };
  Set SetOf(uint64_t line) const {
    const uint64_t i = pow2_ ? (line & mask_) : (line % sets_);
    uint32_t* sig = reinterpret_cast<uint32_t*>(base_ + i * block_bytes_);
    return {sig, sig + padded_, i};
  }
  uint64_t* TagsOf(const Set& s) const { return tags_.get() + s.index * padded_; }  // tagged_
  // From now on the tags are kept: written from the signatures (every held way's tag is high_'s
  // half and its signature).
  void KeepTags();
  // The clock after one more use or install; stamps renumbered first at the limit.
  uint32_t Tick() {
    if (__builtin_expect(clock_ >= limit_, 0)) Renumber();
    return ++clock_;
  }
  void Renumber();
  // The way with the smallest stamp (the first of equals: the first empty way), padding excluded.
  // G: groups(), or 0.
  template <uint32_t G>
  uint32_t Oldest(const uint32_t* stamp) const {
    const uint32_t n = G ? G : groups_;
#ifdef __SSE2__
    // Stamps are below 2^31 - 1, so signed compares order them; the padding's lanes read as
    // 2^31 - 1 (pad_lanes_).
    const __m128i high = _mm_load_si128(reinterpret_cast<const __m128i*>(pad_lanes_));
    auto group = [&](uint32_t g) {
      const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(stamp + 4 * g));
      return g + 1 == n ? _mm_or_si128(v, high) : v;
    };
    auto min = [](__m128i a, __m128i b) {
      const __m128i lt = _mm_cmplt_epi32(a, b);
      return _mm_or_si128(_mm_and_si128(lt, a), _mm_andnot_si128(lt, b));
    };
    __m128i m = group(0);
    for (uint32_t g = 1; g < n; ++g) m = min(m, group(g));
    m = min(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = min(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(2, 3, 0, 1)));  // every lane the minimum
    for (uint32_t g = 0;; ++g)
      if (const int eq = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(group(g), m))))
        return 4 * g + static_cast<uint32_t>(__builtin_ctz(static_cast<unsigned>(eq)));
#else
    uint32_t v = 0;
    for (uint32_t i = 1; i < ways_; ++i) v = stamp[i] < stamp[v] ? i : v;
    (void)n;
    return v;
#endif
  }
  // Whether, with no tags kept, `tag` is its signature: high_'s half and a low half other than 0
  // (one subtraction and compare: sig_lo_ and sig_span_ follow high_ and tagged_; no tag passes
  // before the first install or once tags are kept).
  bool SigTag(uint64_t tag) const { return tag - sig_lo_ < sig_span_; }
  // Bit i set where x[i] == key, for 4 * n values (n <= 8).
  static uint32_t Matches(const uint32_t* x, uint32_t n, uint32_t key) {
    uint32_t m = 0;
#ifdef __SSE2__
    const __m128i k = _mm_set1_epi32(static_cast<int>(key));
    for (uint32_t g = 0; g < n; ++g) {
      const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(x + 4 * g));
      m |= static_cast<uint32_t>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(v, k))))
           << (4 * g);
    }
#else
    for (uint32_t i = 0; i < 4 * n; ++i) m |= static_cast<uint32_t>(x[i] == key) << i;
#endif
    return m;
  }
  // The way holding `tag`, or kNone: the ways whose signature matches, confirmed on the tag
  // where tags are kept (without them, a tag of high_'s half and a low half other than 0 is its
  // signature). G: the groups fixed at compile time (0: groups_, any count).
  template <uint32_t G>
  uint32_t Find(Set s, uint64_t tag) const {
    const uint32_t groups = G ? G : groups_;
    if (!tagged_ && !SigTag(tag)) return kNone;
    const uint64_t* t = tagged_ ? TagsOf(s) : nullptr;
    for (uint32_t g = 0; g < groups; g += 8)
      for (uint32_t m =
               Matches(s.sig + 4 * g, std::min(8u, groups - g), static_cast<uint32_t>(tag));
           m; m &= m - 1) {
        const uint32_t w = 4 * g + static_cast<uint32_t>(__builtin_ctz(m));
        if (!t || t[w] == tag) return w;
      }
    return kNone;
  }
  // A miss: the victim chosen, the tag in its way. Inline for the common case (LRU or FIFO, no
  // tags kept, the tag its signature), InstallSlow otherwise (random, tags, a first tag).
  template <uint32_t G>
  [[gnu::always_inline]] void Install(Set s, uint64_t tag) {
    if (__builtin_expect(!SigTag(tag) || policy_ == Replacement::kRandom, 0))
      return InstallSlow<G>(s, tag);
    const uint32_t v = Oldest<G>(s.stamp);  // an empty way's stamp is 0
    s.stamp[v] = Tick();
    victim_ = s.sig[v] ? (high_ << 32 | s.sig[v]) - 1 : ~uint64_t{0};
    s.sig[v] = static_cast<uint32_t>(tag);
  }
  template <uint32_t G>
  void InstallSlow(Set s, uint64_t tag);
  // kSig (no tags kept): a signature's match is the tag's for a line whose tag's high half is
  // high_ and whose low half is not 0 (an empty way's signature); other lines end the run.
  template <uint32_t G, bool kPow2, bool kTick, bool kSig, class LineOf, class OnHit, class OnMiss>
  [[gnu::always_inline]] size_t Run(size_t from, size_t n, LineOf& line_of, OnHit& on_hit,
                                    OnMiss& on_miss) {
    // The level's fields in locals: a stamp's store could alias them, and they would be reloaded
    // at every access. With kTick, at most limit_ - clock_ stamps (then Tick renumbers).
    uint32_t clock = clock_;
    if (kTick) n = std::min<size_t>(n, from + (clock < limit_ ? limit_ - clock : 0));
    uint8_t* const block = base_;
    // With G fixed, a set's size and the offsets in it are constants.
    const uint64_t sets = sets_, mask = mask_, bytes = G ? 32 * G : block_bytes_;
    const uint64_t* const tags = tags_.get();
    const uint32_t padded = G ? 4 * G : padded_, groups = G ? G : groups_;
    const uint64_t sig_lo = sig_lo_, sig_span = sig_span_;
    // The line of the run's last hit: still held (nothing else touches this level during the
    // run), and its stamp is already the largest of its set, so another use of it changes no
    // order in any set: no lookup, no stamp (about half of a smoother's accesses).
    uint64_t last = ~uint64_t{0};
    size_t i = from;
    bool missed = false;
    for (; i < n; ++i) {
      uint64_t line;
      if (!line_of(i, line)) break;
      if (line == last) {
        on_hit(i, line);
        continue;
      }
      const uint64_t set = kPow2 ? (line & mask) : (line % sets);
      uint32_t* const sig = reinterpret_cast<uint32_t*>(block + set * bytes);
      uint32_t w = kNone;
      if (kSig) {
        const uint64_t t1 = line + 1;
        if (t1 - sig_lo < sig_span)  // else not SigTag: not held
          for (uint32_t g = 0; g < groups && w == kNone; g += 8)
            if (const uint32_t m =
                    Matches(sig + 4 * g, std::min(8u, groups - g), static_cast<uint32_t>(t1)))
              w = 4 * g + static_cast<uint32_t>(__builtin_ctz(m));
      } else {
        for (uint32_t g = 0; g < groups && w == kNone; g += 8)
          for (uint32_t m =
                   Matches(sig + 4 * g, std::min(8u, groups - g), static_cast<uint32_t>(line + 1));
               m; m &= m - 1) {
            const uint32_t k = 4 * g + static_cast<uint32_t>(__builtin_ctz(m));
            if (tags[set * padded + k] == line + 1) {
              w = k;
              break;
            }
          }
      }
      if (__builtin_expect(w == kNone, 0)) {
        // The miss done by the caller, on the level as it is (its clock stored, then taken back).
        clock_ = clock;
        if (!on_miss(i, line)) {
          missed = true;
          break;
        }
        clock = clock_;
        // A first tag of another high half, or tags kept from now on, change what this loop
        // assumed; and the rest of the run's stamps, n - i - 1 at most, must stay below the limit.
        if (sig_lo_ != sig_lo || sig_span_ != sig_span || tagged_ == kSig ||
            (kTick && limit_ - clock <= n - i)) {
          ++i;
          break;
        }
        last = line;  // installed with the newest stamp
        continue;
      }
      if (kTick) sig[padded + w] = ++clock;
      last = line;
      on_hit(i, line);
    }
    clock_ = clock;
    run_missed_ = missed;
    return i;
  }

  uint64_t sets_, mask_;
  uint32_t ways_, padded_, groups_;  // padded_: ways rounded up to a multiple of 4, groups_ = /4
  uint64_t block_bytes_;             // a set: padded_ signatures and stamps
  bool pow2_;
  Replacement policy_;
  uint32_t clock_ = 0;  // the last stamp given (LRU, FIFO)
  uint32_t limit_ = (uint32_t{1} << 31) - 2;
  uint64_t rng_ = 0x9E3779B97F4A7C15ull;
  uint64_t victim_ = ~uint64_t{0};
  // The high half of the first tag installed (kNoHigh before), and whether tags are kept (a tag
  // of another half, or of a low half 0, has been installed since).
  static constexpr uint64_t kNoHigh = ~uint64_t{0};
  uint64_t high_ = kNoHigh;
  bool tagged_ = false;
  bool run_missed_ = false;
  uint64_t sig_lo_ = 0, sig_span_ = 0;     // SigTag's range: (high_ << 32) + 1 and 2^32 - 1, or 0
  alignas(16) int32_t pad_lanes_[4] = {};  // Oldest: 2^31 - 1 in the last group's padding lanes
  // The sets' blocks, from calloc, whose large blocks are fresh zero pages: a level costs memory
  // only for the sets a stream touches, so 256 streams of a few accesses each do not hold 256
  // copies of a 24 MiB L3's tags. All zero is a set of empty ways.
  struct Free {
    void operator()(void* p) const { std::free(p); }
  };
  std::unique_ptr<uint8_t[], Free> block_;
  uint8_t* base_ = nullptr;  // the first set: block_ rounded up to 64 B
  WritablePages pages_;
  struct FreeTags {
    void operator()(uint64_t* p) const { std::free(p); }
  };
  std::unique_ptr<uint64_t[], FreeTags> tags_;  // padded_ a set, where tagged_
  WritablePages tag_pages_;
};

// HitRun's line_of over a stream's accesses, for both simulators: access i's line, when it is
// thread t's and within one line (the offset in the line plus the size reaches at most its end; a
// size of 0 is one byte). Held by value, so its fields stay in registers.
struct OneLineOf {
  const meshreuse::Access* a;
  uint8_t t;
  int shift;
  bool operator()(size_t i, uint64_t& line) const {
    const uint64_t x = a[i].address, bytes = uint64_t{1} << shift;
    line = x >> shift;
    return (a[i].thread == t) & ((x & (bytes - 1)) + a[i].size <= bytes);
  }
};

}  // namespace meshreuse
