// The distribution of reuse distances of one stream: an exact count per distance, the cold count,
// the mean, quantiles, and tail counts for the miss model. Quantile X (DESIGN.md) = the smallest
// observed d such that at least a fraction X of the finite distances are <= d; X = 0 gives the
// smallest, X = 1 the largest. The binned view is exact below 64 and log2 bins beyond.
// Two layouts, one set of answers: dense (the analyzer's: one 32-bit counter per distance up to
// the largest seen, below the number of distinct ids; Add is one increment, a counter that wraps
// carries 2^32 into a map of its own, so counts stay exact 64-bit ones) and paged (UsePages:
// counters in pages of 4096 distances, each allocated when first touched; for the merges, whose
// distances reach the whole stream's distinct ids M but often fill a few ranges of them: a scan's
// every reuse is at M - 1). Readers go through ForEach / ForEachDown, in order of distance.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/table.h"

namespace meshreuse {

class ReuseHistogram {
 public:
  void Add(uint64_t d) {  // StackDistance's kCold (all ones) counts as cold
    if (d == ~uint64_t{0}) {
      ++cold_;
      return;
    }
    if (d >= counts_.size()) {  // paged: counts_ stays empty, so every paged add comes here
      if (paged_) return AddPaged(d, 1);
      Grow(d);  // within the reserved capacity when Reserve() was right
    }
    if (__builtin_expect(++counts_[d] == 0, 0)) Carry(d, 1);
    ++finite_;
    sum_ += d;
  }
  void AddCount(uint64_t d, uint64_t n) {  // n accesses at distance d (or cold)
    if (d == ~uint64_t{0}) {
      cold_ += n;
      return;
    }
    if (!n) return;
    if (d >= counts_.size()) {
      if (paged_) return AddPaged(d, n);
      Grow(d);
    }
    const uint64_t low = uint64_t{counts_[d]} + (n & kLow);
    counts_[d] = static_cast<uint32_t>(low);
    if (const uint64_t carry = (n >> 32) + (low >> 32)) Carry(d, carry);
    finite_ += n;
    sum_ += static_cast<unsigned __int128>(d) * n;
  }
  // The paged layout; only before anything is added (std::logic_error otherwise).
  void UsePages();
  bool paged() const { return paged_; }
  void Merge(const ReuseHistogram& o);
  // Distances are below the number of distinct ids: with that number known (vertex ids), one
  // exact allocation instead of doubling. Dense only (a paged histogram ignores it).
  void Reserve(uint64_t distinct) {
    if (!paged_) counts_.reserve(distinct);
  }

  uint64_t accesses() const { return finite_ + cold_; }
  uint64_t finite() const { return finite_; }
  uint64_t cold() const { return cold_; }
  double mean() const;  // of the finite distances, the double nearest sum/finite; NaN when none
  unsigned __int128 sum() const { return sum_; }  // of the finite distances, exact
  uint64_t max() const;                           // largest finite distance (0 when none)
  // Throws std::invalid_argument for x outside [0, 1] and std::domain_error when there are no
  // finite distances.
  uint64_t Quantile(double x) const;
  uint64_t CountAtLeast(uint64_t d) const;  // finite distances >= d
  // f(d, count) for every distance with a count, in increasing d.
  template <class F>
  void ForEach(F f) const {
    if (!paged_) {
      auto c = carries_.begin();
      for (size_t d = 0; d < counts_.size(); ++d) {
        uint64_t n = counts_[d];
        if (c != carries_.end() && c->first == d) n += (c++)->second << 32;
        if (n) f(static_cast<uint64_t>(d), n);
      }
      return;
    }
    for (size_t p = 0; p < pages_.size(); ++p)
      if (const uint64_t* c = pages_[p].get())
        for (uint64_t i = 0; i < kPage; ++i)
          if (c[i]) f(p * kPage + i, c[i]);
  }
  // f(d, count) in decreasing d while f returns true.
  template <class F>
  void ForEachDown(F f) const {
    if (!paged_) {
      auto c = carries_.rbegin();
      for (size_t d = counts_.size(); d > 0; --d) {
        uint64_t n = counts_[d - 1];
        if (c != carries_.rend() && c->first == d - 1) n += (c++)->second << 32;
        if (n && !f(static_cast<uint64_t>(d - 1), n)) return;
      }
      return;
    }
    for (size_t p = pages_.size(); p > 0; --p)
      if (const uint64_t* c = pages_[p - 1].get())
        for (uint64_t i = kPage; i > 0; --i)
          if (c[i - 1] && !f((p - 1) * kPage + i - 1, c[i - 1])) return;
  }
  std::vector<std::pair<uint64_t, uint64_t>> Pairs() const;  // ForEach's (d, count), collected
  // Bytes its counters hold (the dense array, or the allocated pages and their index).
  uint64_t counter_bytes() const;
  static constexpr uint64_t kDenseCounterBytes = sizeof(uint32_t);  // counts_'s, a distance

  struct Bin {
    uint64_t lo, hi, count;  // distances lo..hi inclusive
  };
  std::vector<Bin> Binned(uint64_t exact_below = 64) const;
  // Its rows, each `key` (the caller's identifying cells) then lo, hi, count: one per bin of
  // Binned(exact_below), then one "cold", "cold", count row when there are cold accesses. Every
  // command writes histograms this way (one schema, one plotting script).
  void AppendRows(Table* t, const std::vector<std::string>& key, uint64_t exact_below = 64) const;

 private:
  static constexpr uint64_t kPage = 4096;
  static constexpr uint64_t kLow = 0xffffffff;
  void Grow(uint64_t d);
  void AddPaged(uint64_t d, uint64_t n);
  void Carry(uint64_t d, uint64_t wraps);  // out of line: the add stays small
  // 32-bit counters, not 64: half the bytes that every access touches at a random place (at 10^6
  // uniform ids, 8 MB of 64-bit counters beside the stack's 4 MB pushed two threads' analyses out
  // of the shared L3 and made each 1.3-1.5x slower, where 4 MB did not; measured).
  std::vector<uint32_t> counts_;
  std::map<uint64_t, uint64_t> carries_;  // distance -> how many times its counter wrapped
  bool paged_ = false;
  std::vector<std::unique_ptr<uint64_t[]>> pages_;
  uint64_t finite_ = 0, cold_ = 0;
  unsigned __int128 sum_ = 0;  // exact: distances are integers (long double was x87, and slow)
};

// The miss-ratio curve of a fully associative LRU cache, exact: misses(c) = cold + distances >= c.
// One point per capacity where the curve changes (c = 0, then d + 1 for every observed d), so the
// curve between points is flat.
struct MrcPoint {
  uint64_t capacity, misses;
};
std::vector<MrcPoint> MissRatioCurve(const ReuseHistogram& h);

std::string ToDecimal(unsigned __int128 v);

// Mean reuse distance over time: each iteration (sweep) of the stream cut into `steps` equal
// parts (an iteration shorter than that: one step per access), as the paper's carabiner profile
// figure. Needs each iteration's length in advance. Accesses are placed by their position in the
// stream, so partial profiles of consecutive chunks (the parallel analyzer) merge exactly.
class ReuseProfile {
 public:
  ReuseProfile() = default;
  ReuseProfile(std::vector<uint64_t> iteration_lengths, int steps = 100);
  void Add(uint64_t d) { AddAt(next_++, d); }           // the access after the previous Add
  void AddAt(uint64_t position, uint64_t d) {           // position in the stream, 0-based
    if (position >= step_lo_ && position < step_hi_) {  // the same step as before: inline
      Step& st = steps_[step_];
      ++st.accesses;
      if (d == ~uint64_t{0})
        ++st.cold;
      else
        st.sum += d;
      return;
    }
    AddAtSlow(position, d);
  }
  void SetNext(uint64_t position) { next_ = position; }  // where the next Add() goes
  void Skip() { ++next_; }                               // the next Add() goes one position further
  uint64_t next() const { return next_; }
  // The same iterations and steps, every count zero: a partial profile for one chunk.
  ReuseProfile EmptyCopy() const;
  void Merge(const ReuseProfile& o);  // o: an EmptyCopy() of this one, filled
  // Adds counts to step i (a stored partial profile); false when there is no such step.
  bool AddToStep(size_t i, uint64_t accesses, uint64_t cold, unsigned __int128 sum) {
    if (i >= steps_.size()) return false;
    steps_[i].accesses += accesses, steps_[i].cold += cold, steps_[i].sum += sum;
    return true;
  }
  struct Step {
    int iteration;  // 1-based
    int step;       // 0-based
    uint64_t accesses = 0, cold = 0;
    unsigned __int128 sum = 0;  // of finite distances, exact
    double mean() const;
  };
  const std::vector<Step>& steps() const { return steps_; }
  bool enabled() const { return !lengths_.empty(); }
  // Its rows, each `key` then iteration, step, accesses, cold, mean (full precision; empty when
  // the step has no finite distance).
  void AppendRows(Table* t, const std::vector<std::string>& key) const;

 private:
  void AddAtSlow(uint64_t position, uint64_t d);
  std::vector<uint64_t> lengths_;
  std::vector<uint64_t> starts_;  // position of each iteration's first access; back() = total
  int nsteps_ = 100;
  std::vector<Step> steps_;
  std::vector<size_t> first_;  // index of each iteration's first step
  size_t iter_ = 0;            // the iteration of the last AddAt (a cursor: accesses come in order)
  uint64_t next_ = 0;
  size_t step_ = 0;  // the step of positions [step_lo_, step_hi_)
  uint64_t step_lo_ = 0, step_hi_ = 0;
};

}  // namespace meshreuse
