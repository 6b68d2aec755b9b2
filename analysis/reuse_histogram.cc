// ReuseHistogram and ReuseProfile; see reuse_histogram.h.
#include "analysis/reuse_histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "analysis/stack_distance.h"

namespace meshreuse {

static_assert(StackDistance::kCold == ~uint64_t{0}, "Add() tests for cold by value");

void ReuseHistogram::Grow(uint64_t d) {
  // By a quarter: the counts are zero-filled (resident) to their size.
  const uint64_t want = std::max<uint64_t>(d + 1, counts_.size() + counts_.size() / 4 + 1024);
  counts_.resize(counts_.capacity() > d ? std::min<uint64_t>(want, counts_.capacity()) : want, 0);
}

void ReuseHistogram::Carry(uint64_t d, uint64_t wraps) { carries_[d] += wraps; }

void ReuseHistogram::UsePages() {
  if (accesses() || !counts_.empty()) throw std::logic_error("ReuseHistogram: pages after adds");
  paged_ = true;
}

void ReuseHistogram::AddPaged(uint64_t d, uint64_t n) {
  const uint64_t p = d / kPage;
  if (p >= pages_.size()) pages_.resize(p + 1);
  if (!pages_[p]) pages_[p].reset(new uint64_t[kPage]());
  pages_[p][d % kPage] += n;
  finite_ += n;
  sum_ += static_cast<unsigned __int128>(d) * n;
}

std::vector<std::pair<uint64_t, uint64_t>> ReuseHistogram::Pairs() const {
  std::vector<std::pair<uint64_t, uint64_t>> out;
  ForEach([&](uint64_t d, uint64_t n) { out.emplace_back(d, n); });
  return out;
}

uint64_t ReuseHistogram::counter_bytes() const {
  // A map node: the pair, three links and a colour, rounded to the allocator's 16 bytes.
  uint64_t b = counts_.capacity() * kDenseCounterBytes + pages_.capacity() * sizeof(pages_[0]) +
               carries_.size() * 64;
  for (const auto& p : pages_)
    if (p) b += kPage * sizeof(uint64_t);
  return b;
}

void ReuseHistogram::Merge(const ReuseHistogram& o) {
  if (!paged_ && !o.paged_) {
    if (o.counts_.size() > counts_.size()) counts_.resize(o.counts_.size(), 0);
    for (size_t d = 0; d < o.counts_.size(); ++d) {
      const uint32_t n = counts_[d] + o.counts_[d];
      if (n < counts_[d]) ++carries_[d];
      counts_[d] = n;
    }
    for (const auto& [d, c] : o.carries_) carries_[d] += c;
    finite_ += o.finite_;
    sum_ += o.sum_;
  } else {
    o.ForEach([this](uint64_t d, uint64_t n) { AddCount(d, n); });
  }
  cold_ += o.cold_;
}

double ReuseHistogram::mean() const {
  if (!finite_) return NAN;
  // Integer part exactly, then the remainder: the quotient to within an ulp of the double.
  const unsigned __int128 q = sum_ / finite_, r = sum_ % finite_;
  return static_cast<double>(static_cast<long double>(q) +
                             static_cast<long double>(r) / static_cast<long double>(finite_));
}

std::vector<MrcPoint> MissRatioCurve(const ReuseHistogram& h) {
  std::vector<MrcPoint> out;
  uint64_t misses = h.accesses();
  out.push_back({0, misses});
  h.ForEach([&](uint64_t d, uint64_t n) {
    misses -= n;
    out.push_back({d + 1, misses});
  });
  return out;
}

std::string ToDecimal(unsigned __int128 v) {
  std::string s;
  do {
    s.insert(s.begin(), static_cast<char>('0' + static_cast<int>(v % 10)));
    v /= 10;
  } while (v);
  return s;
}

uint64_t ReuseHistogram::max() const {
  uint64_t top = 0;
  ForEachDown([&](uint64_t d, uint64_t) {
    top = d;
    return false;
  });
  return top;
}

uint64_t ReuseHistogram::Quantile(double x) const {
  if (!(x >= 0.0 && x <= 1.0)) throw std::invalid_argument("a quantile must be between 0 and 1");
  if (finite_ == 0) throw std::domain_error("no finite reuse distances");
  // The smallest observed d with cum(d) >= x * finite. x is a double (0.4 is
  // 0.4000000000000000222), so x * n can exceed the integer it stands for by a few ulps: allow
  // 1e-12 * n, far below one access for any trace we can hold.
  const long double need = static_cast<long double>(x) * static_cast<long double>(finite_) -
                           1e-12L * static_cast<long double>(finite_);
  uint64_t cum = 0, found = 0;
  bool done = false;
  ForEach([&](uint64_t d, uint64_t n) {
    if (done) return;
    cum += n;
    if (static_cast<long double>(cum) >= need) found = d, done = true;
  });
  return done ? found : max();
}

uint64_t ReuseHistogram::CountAtLeast(uint64_t d) const {
  uint64_t n = 0;
  ForEachDown([&](uint64_t e, uint64_t c) {
    if (e < d) return false;
    n += c;
    return true;
  });
  return n;
}

std::vector<ReuseHistogram::Bin> ReuseHistogram::Binned(uint64_t exact_below) const {
  std::vector<Bin> bins;
  const uint64_t top = max();
  for (uint64_t d = 0; d < exact_below && d <= top; ++d) bins.push_back({d, d, 0});
  for (uint64_t lo = exact_below; lo <= top && finite_; lo *= 2) {
    bins.push_back({lo, 2 * lo - 1, 0});
    if (lo == 0) break;
  }
  // Each count into its bin: exact ones by index, then doubling ranges in order.
  size_t b = 0;
  ForEach([&](uint64_t d, uint64_t n) {
    while (b < bins.size() && bins[b].hi < d) ++b;
    if (b < bins.size()) bins[b].count += n;
  });
  return bins;
}

ReuseProfile::ReuseProfile(std::vector<uint64_t> lengths, int steps)
    : lengths_(std::move(lengths)), nsteps_(steps) {
  // An iteration of n accesses gets min(steps, n) steps, so the profile never holds more steps
  // than accesses: its memory follows the trace, whatever sweep count a header claims.
  starts_.push_back(0);
  for (size_t i = 0; i < lengths_.size(); ++i) {
    first_.push_back(steps_.size());
    const int k = static_cast<int>(std::min<uint64_t>(nsteps_, lengths_[i]));
    for (int s = 0; s < k; ++s) steps_.push_back({static_cast<int>(i + 1), s});
    const uint64_t end = starts_.back() + lengths_[i];
    starts_.push_back(end < starts_.back() ? ~uint64_t{0} : end);  // saturate: a hostile header
  }
}

void ReuseProfile::AddAtSlow(uint64_t position, uint64_t d) {
  Step* st;
  {
    if (lengths_.empty() || position >= starts_.back()) return;  // past the announced length
    if (position < starts_[iter_] || position >= starts_[iter_ + 1]) {
      if (position >= starts_[iter_ + 1] &&
          position < starts_[std::min(iter_ + 2, lengths_.size())])
        ++iter_;  // the next iteration: the common case when accesses come in order
      else
        iter_ = static_cast<size_t>(std::upper_bound(starts_.begin(), starts_.end(), position) -
                                    starts_.begin()) -
                1;
    }
    // Step s of an iteration of len accesses in k steps holds positions p with
    // floor(p k / len) = s, i.e. p in [ceil(s len / k), ceil((s + 1) len / k)).
    using U = unsigned __int128;
    const uint64_t pos = position - starts_[iter_], len = lengths_[iter_];
    const uint64_t k = std::min<uint64_t>(nsteps_, len);
    const uint64_t s = static_cast<uint64_t>(U{pos} * k / len);
    step_ = first_[iter_] + s;
    step_lo_ = starts_[iter_] + static_cast<uint64_t>((U{s} * len + k - 1) / k);
    step_hi_ = starts_[iter_] + static_cast<uint64_t>((U{s + 1} * len + k - 1) / k);
    st = &steps_[step_];
  }
  ++st->accesses;
  if (d == StackDistance::kCold)
    ++st->cold;
  else
    st->sum += d;
}

ReuseProfile ReuseProfile::EmptyCopy() const {
  ReuseProfile p = *this;
  for (Step& s : p.steps_) s.accesses = s.cold = 0, s.sum = 0;
  p.iter_ = 0;
  p.next_ = 0;
  p.step_lo_ = p.step_hi_ = 0;
  return p;
}

void ReuseProfile::Merge(const ReuseProfile& o) {
  for (size_t i = 0; i < steps_.size() && i < o.steps_.size(); ++i) {
    steps_[i].accesses += o.steps_[i].accesses;
    steps_[i].cold += o.steps_[i].cold;
    steps_[i].sum += o.steps_[i].sum;
  }
}

double ReuseProfile::Step::mean() const {
  const uint64_t f = accesses - cold;
  return f ? static_cast<double>(static_cast<long double>(sum) / f) : NAN;
}

void ReuseHistogram::AppendRows(Table* t, const std::vector<std::string>& key,
                                uint64_t exact_below) const {
  auto row = [&](std::string lo, std::string hi, uint64_t count) {
    std::vector<std::string> r = key;
    r.insert(r.end(), {std::move(lo), std::move(hi), std::to_string(count)});
    t->AddRow(std::move(r));
  };
  for (const Bin& b : Binned(exact_below)) row(std::to_string(b.lo), std::to_string(b.hi), b.count);
  if (cold_) row("cold", "cold", cold_);
}

void ReuseProfile::AppendRows(Table* t, const std::vector<std::string>& key) const {
  for (const Step& st : steps_) {
    char mean[40] = "";
    if (st.accesses > st.cold) std::snprintf(mean, sizeof mean, "%.17g", st.mean());
    std::vector<std::string> r = key;
    r.insert(r.end(), {std::to_string(st.iteration), std::to_string(st.step),
                       std::to_string(st.accesses), std::to_string(st.cold), mean});
    t->AddRow(std::move(r));
  }
}

}  // namespace meshreuse
