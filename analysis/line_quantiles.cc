// LineQuantiles; see line_quantiles.h.
#include "analysis/line_quantiles.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "analysis/reuse_histogram.h"

namespace meshreuse {

LineQuantiles::LineQuantiles(uint32_t line_bytes, uint32_t depth)
    : line_bytes_(line_bytes), depth_(depth) {
  if (line_bytes == 0 || (line_bytes & (line_bytes - 1)) != 0)
    throw std::invalid_argument("LineQuantiles: the line size must be a power of two");
  if (depth < 1 || depth > 4096)
    throw std::invalid_argument("LineQuantiles: depth must be 1..4096");
  shift_ = __builtin_ctz(line_bytes);
  slots_ = (depth + 3) / 4 * 4;
}

void LineQuantiles::Begin(const StreamInfo& info) {
  canonical_ = info.canonical;
  streams_.clear();  // each stream made at its first access
}

LineQuantiles::Stream& LineQuantiles::At(size_t t) {
  if (t >= streams_.size()) streams_.resize(t + 1);
  if (!streams_[t]) streams_[t] = std::make_unique<Stream>(canonical_, line_bytes_, slots_);
  return *streams_[t];
}

namespace {

// How many of stamp[0..n) (n a multiple of 4) exceed x.
inline uint32_t CountAbove(const int32_t* stamp, uint32_t n, int32_t x) {
#if defined(__SSE2__)
  const __m128i k = _mm_set1_epi32(x);
  auto above = [&](uint32_t i) {  // a true compare is -1 in its lane
    return _mm_cmpgt_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(stamp + i)), k);
  };
  __m128i acc = _mm_setzero_si128(), acc2 = _mm_setzero_si128();  // two chains
  uint32_t i = 0;
  for (; i + 8 <= n; i += 8)
    acc = _mm_sub_epi32(acc, above(i)), acc2 = _mm_sub_epi32(acc2, above(i + 4));
  if (i < n) acc = _mm_sub_epi32(acc, above(i));
  acc = _mm_add_epi32(acc, acc2);
  acc = _mm_add_epi32(acc, _mm_shuffle_epi32(acc, _MM_SHUFFLE(1, 0, 3, 2)));
  acc = _mm_add_epi32(acc, _mm_shuffle_epi32(acc, _MM_SHUFFLE(2, 3, 0, 1)));
  return static_cast<uint32_t>(_mm_cvtsi128_si32(acc));
#else
  uint32_t c = 0;
  for (uint32_t i = 0; i < n; ++i) c += stamp[i] > x;
  return c;
#endif
}

// The slot of the smallest stamp (the first of equals: an empty slot while one is left).
inline uint32_t Oldest(const int32_t* stamp, uint32_t n) {
#if defined(__SSE2__)
  auto min = [](__m128i a, __m128i b) {
    const __m128i lt = _mm_cmplt_epi32(a, b);
    return _mm_or_si128(_mm_and_si128(lt, a), _mm_andnot_si128(lt, b));
  };
  auto at = [&](uint32_t i) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(stamp + i));
  };
  __m128i m = at(0);
  for (uint32_t i = 4; i < n; i += 4) m = min(m, at(i));
  m = min(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(1, 0, 3, 2)));
  m = min(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(2, 3, 0, 1)));  // every lane the minimum
  for (uint32_t i = 0;; i += 4)
    if (const int eq = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(at(i), m))))
      return i + static_cast<uint32_t>(__builtin_ctz(static_cast<unsigned>(eq)));
#else
  uint32_t v = 0;
  for (uint32_t i = 1; i < n; ++i) v = stamp[i] < stamp[v] ? i : v;
  return v;
#endif
}

// stamp[j] = x, stored as the whole vector of four that holds it (stamp 16-byte aligned): the next
// access's loads of that vector then take it from the store, where a 4-byte store under a 16-byte
// load would make the load wait until the store reached the host's cache.
inline void SetStamp(int32_t* stamp, uint32_t j, int32_t x) {
#if defined(__SSE2__)
  __m128i* p = reinterpret_cast<__m128i*>(stamp + (j & ~3u));
  const __m128i lane =
      _mm_cmpeq_epi32(_mm_set_epi32(3, 2, 1, 0), _mm_set1_epi32(static_cast<int>(j & 3)));
  _mm_store_si128(p, _mm_or_si128(_mm_and_si128(lane, _mm_set1_epi32(x)),
                                  _mm_andnot_si128(lane, _mm_load_si128(p))));
#else
  stamp[j] = x;
#endif
}

}  // namespace

// The stamps renumbered 1.. in their order (empty slots stay 0) when the clock reaches its
// limit: only their order is ever compared.
void LineQuantiles::Renumber(Stream& s) const {
  std::vector<std::pair<int32_t, uint32_t>> order;
  for (uint32_t j = 0; j < slots_; ++j)
    if (s.stamp[j] != 0) order.emplace_back(s.stamp[j], j);
  std::sort(order.begin(), order.end());
  for (size_t k = 0; k < order.size(); ++k) s.stamp[order[k].second] = static_cast<int32_t>(k + 1);
  s.clock = static_cast<int32_t>(order.size());
}

inline void LineQuantiles::Add(Stream& s, uint64_t line) {
  ++s.accesses;
  if (s.front == line) {  // a repeat, over a third of a kernel's accesses: nothing changes
    ++s.below[0];
    return;
  }
  s.front = line;
  if (__builtin_expect(s.clock >= clock_limit_, 0)) Renumber(s);
  const int32_t now = ++s.clock;
  uint16_t& m = s.mark.At(line);
  if (m >= 2) {  // held: its distance is the count of more recent slots
    const uint32_t j = m - 2u;
    ++s.below[CountAbove(s.stamp.data(), slots_, s.stamp[j])];
    SetStamp(s.stamp.data(), j, now);
    return;
  }
  // Not held: cold, or a reuse at slots_ (>= depth) or more. It takes the oldest slot.
  if (m == 0) ++s.cold;
  const uint32_t j = Oldest(s.stamp.data(), slots_);
  m = static_cast<uint16_t>(j + 2);
  if (s.line[j] != kNone) s.mark.At(s.line[j]) = 1;  // (after m: At may move the marks)
  s.line[j] = line;
  SetStamp(s.stamp.data(), j, now);
}

void LineQuantiles::Consume(const Access* a, size_t n) {
  Stream* s = nullptr;
  int thread = -1;
  for (size_t i = 0; i < n; ++i) {
    const Access& x = a[i];
    if (x.thread != thread) thread = x.thread, s = &At(x.thread);
    const uint64_t first = x.address >> shift_;
    const uint64_t last = (x.address + (x.size ? x.size - 1 : 0)) >> shift_;
    Add(*s, first);
    if (last != first) Add(*s, last);
  }
}

const LineQuantiles::Stream* LineQuantiles::Find(int t) const {
  return t >= 0 && static_cast<size_t>(t) < streams_.size() ? streams_[t].get() : nullptr;
}

uint64_t LineQuantiles::accesses(int t) const {
  const Stream* s = Find(t);
  return s ? s->accesses : 0;
}

uint64_t LineQuantiles::cold(int t) const {
  const Stream* s = Find(t);
  return s ? s->cold : 0;
}

std::optional<uint64_t> LineQuantiles::Quantile(int t, double x) const {
  const Stream* found = Find(t);
  if (!found) return std::nullopt;
  const Stream& s = *found;
  // The histogram's own quantile, with every finite distance at or beyond depth counted at depth:
  // an answer below depth is the true one, an answer of depth means "depth or more".
  ReuseHistogram h;
  uint64_t small = 0;
  for (uint32_t d = 0; d < depth_; ++d) h.AddCount(d, s.below[d]), small += s.below[d];
  h.AddCount(depth_, s.accesses - s.cold - small);
  if (h.finite() == 0) return std::nullopt;
  const uint64_t q = h.Quantile(x);
  if (q >= depth_) return std::nullopt;
  return q;
}

}  // namespace meshreuse
