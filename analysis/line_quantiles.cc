// LineQuantiles; see line_quantiles.h.
#include "analysis/line_quantiles.h"

#include <cstring>
#include <stdexcept>

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
  slots_ = (depth + 15) / 16 * 16;  // vectors of 16 byte ranks
  wide_ = slots_ > 128;             // ranks up to 127 in a signed byte
  if (wide_) slots_ = (depth + 7) / 8 * 8;
}

void LineQuantiles::Begin(const StreamInfo& info) {
  canonical_ = info.canonical;
  streams_.clear();  // each stream made at its first access
}

LineQuantiles::Stream& LineQuantiles::At(size_t t) {
  if (t >= streams_.size()) streams_.resize(t + 1);
  if (!streams_[t]) {
    streams_[t] =
        std::make_unique<Stream>(canonical_, line_bytes_, slots_, wide_ ? sizeof(int16_t) : 1);
    uint8_t* rank = streams_[t]->rank.data();
    for (uint32_t j = 0; j < slots_; ++j) {  // the empty slots ranked in order
      const int16_t r16 = static_cast<int16_t>(j);
      const int8_t r8 = static_cast<int8_t>(j);
      if (wide_)
        std::memcpy(rank + 2 * j, &r16, 2);
      else
        std::memcpy(rank + j, &r8, 1);
    }
  }
  return *streams_[t];
}

namespace {

// The LRU update of the ranks rank[0..slots) (a multiple of the vector's lanes) for the slot of
// rank r: every rank below r one more, rank r 0. kFind: returns the slot whose rank was r
// (otherwise 0).
template <class R, bool kFind>
inline __attribute__((always_inline)) uint32_t Promote(uint8_t* rank, uint32_t slots, R r) {
  uint32_t found = 0;
#if defined(__SSE2__)
  constexpr bool k8 = sizeof(R) == 1;
  constexpr uint32_t kLanes = 16 / sizeof(R);
  const __m128i x = k8 ? _mm_set1_epi8(static_cast<char>(r)) : _mm_set1_epi16(r);
  for (uint32_t i = 0; i < slots; i += kLanes) {
    __m128i* p = reinterpret_cast<__m128i*>(rank + i * sizeof(R));
    const __m128i v = _mm_load_si128(p);
    const __m128i eq = k8 ? _mm_cmpeq_epi8(v, x) : _mm_cmpeq_epi16(v, x);
    const __m128i lt = k8 ? _mm_cmplt_epi8(v, x) : _mm_cmplt_epi16(v, x);  // -1 where below
    _mm_store_si128(p, _mm_andnot_si128(eq, k8 ? _mm_sub_epi8(v, lt) : _mm_sub_epi16(v, lt)));
    if constexpr (kFind)
      if (const int m = _mm_movemask_epi8(eq))
        found = i + static_cast<uint32_t>(__builtin_ctz(static_cast<unsigned>(m))) / sizeof(R);
  }
#else
  for (uint32_t j = 0; j < slots; ++j) {
    R v;
    std::memcpy(&v, rank + j * sizeof(R), sizeof(R));
    if (v == r) found = j;
    v = v == r ? R(0) : static_cast<R>(v < r ? v + 1 : v);
    std::memcpy(rank + j * sizeof(R), &v, sizeof(R));
  }
#endif
  return kFind ? found : 0;
}

}  // namespace

template <class R, uint32_t K>
inline void LineQuantiles::Add(Stream& s, uint64_t line) {
  const uint32_t slots = K ? K : slots_;
  ++s.accesses;
  if (s.front == line) {  // a repeat, over a third of a kernel's accesses: nothing changes
    ++s.below[0];
    return;
  }
  s.front = line;
  uint16_t& m = s.mark.At(line);
  if (m >= 2) {  // held: its distance is its rank
    R r;
    std::memcpy(&r, s.rank.data() + (m - 2u) * sizeof(R), sizeof(R));
    ++s.below[static_cast<uint32_t>(r)];
    Promote<R, false>(s.rank.data(), slots, r);
    return;
  }
  // Not held: cold, or a reuse at slots_ (>= depth) or more. It takes the slot of the highest
  // rank.
  if (m == 0) ++s.cold;
  const uint32_t j = Promote<R, true>(s.rank.data(), slots, static_cast<R>(slots - 1));
  m = static_cast<uint16_t>(j + 2);
  if (s.line[j] != kNone) s.mark.At(s.line[j]) = 1;  // (after m: At may move the marks)
  s.line[j] = line;
}

template <class R, uint32_t K>
void LineQuantiles::ConsumeAs(const Access* a, size_t n) {
  Stream* s = nullptr;
  int thread = -1;
  for (size_t i = 0; i < n; ++i) {
    const Access& x = a[i];
    if (x.thread != thread) thread = x.thread, s = &At(x.thread);
    const uint64_t first = x.address >> shift_;
    const uint64_t last = (x.address + (x.size ? x.size - 1 : 0)) >> shift_;
    Add<R, K>(*s, first);
    if (last != first) Add<R, K>(*s, last);
  }
}

void LineQuantiles::Consume(const Access* a, size_t n) {
  // The report's depth (32 slots) with its loop's count fixed at compile time.
  if (wide_)
    ConsumeAs<int16_t, 0>(a, n);
  else if (slots_ == 32)
    ConsumeAs<int8_t, 32>(a, n);
  else
    ConsumeAs<int8_t, 0>(a, n);
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
