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
}

void LineQuantiles::Begin(const StreamInfo& info) {
  canonical_ = info.canonical;
  streams_.clear();  // each stream made at its first access
}

LineQuantiles::Stream& LineQuantiles::At(size_t t) {
  if (t >= streams_.size()) streams_.resize(t + 1);
  if (!streams_[t]) streams_[t] = std::make_unique<Stream>(canonical_, line_bytes_, depth_);
  return *streams_[t];
}

// Moves `line` to the front of `top` and answers where it was among its first `blocks` x 8 entries
// (blocks x 8 when not there: then every entry moved one down, the last of them out). One pass of
// blocks of eight entries, each compared and shifted in registers and stored as it was loaded.
// (A scan with a branch per entry, then memmove, took 16 ns an access on lake's smart-laplacian
// stream in a probe, the whole LRU stack 15; what made the array pay in the report was mostly
// Add's repeat check, below.) SSE2 (x86-64's baseline): a 64-bit lane equals when both its 32-bit
// halves do.
#if defined(__SSE2__)
inline uint32_t MoveToFront(uint64_t* top, uint32_t blocks, uint64_t line) {
  const __m128i want = _mm_set1_epi64x(static_cast<long long>(line));
  auto eq = [&](__m128i v) {
    const __m128i m = _mm_cmpeq_epi32(v, want);
    return static_cast<uint64_t>(
        _mm_movemask_epi8(_mm_and_si128(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(2, 3, 0, 1)))));
  };
  // Lane i of the shifted block is entry i - 1: (the previous vector's high lane, this one's low).
  auto shift = [](__m128i before, __m128i v) {
    return _mm_castpd_si128(_mm_shuffle_pd(_mm_castsi128_pd(before), _mm_castsi128_pd(v), 1));
  };
  __m128i carry = want;  // its high lane enters at entry 0
  for (uint32_t b = 0; b < blocks; ++b) {
    __m128i* p = reinterpret_cast<__m128i*>(top + 8 * b);
    const __m128i v0 = _mm_loadu_si128(p), v1 = _mm_loadu_si128(p + 1);
    const __m128i v2 = _mm_loadu_si128(p + 2), v3 = _mm_loadu_si128(p + 3);
    const __m128i s0 = shift(carry, v0), s1 = shift(v0, v1), s2 = shift(v1, v2), s3 = shift(v2, v3);
    const uint64_t m = eq(v0) | eq(v1) << 16 | eq(v2) << 32 | eq(v3) << 48;
    if (!m) {
      _mm_storeu_si128(p, s0), _mm_storeu_si128(p + 1, s1);
      _mm_storeu_si128(p + 2, s2), _mm_storeu_si128(p + 3, s3);
      carry = v3;
      continue;
    }
    // Found at entry j of the block: entries up to j take the shifted values, the rest stay.
    const int j = __builtin_ctzll(m) / 8;
    const __m128i jj = _mm_set1_epi32(j);
    auto keep = [&](__m128i old, __m128i moved, int k) {  // entries 2k, 2k + 1
      const __m128i after = _mm_cmpgt_epi32(_mm_set_epi32(2 * k + 1, 2 * k + 1, 2 * k, 2 * k), jj);
      return _mm_or_si128(_mm_and_si128(after, old), _mm_andnot_si128(after, moved));
    };
    _mm_storeu_si128(p, keep(v0, s0, 0)), _mm_storeu_si128(p + 1, keep(v1, s1, 1));
    _mm_storeu_si128(p + 2, keep(v2, s2, 2)), _mm_storeu_si128(p + 3, keep(v3, s3, 3));
    return 8 * b + static_cast<uint32_t>(j);
  }
  return 8 * blocks;
}
#else
inline uint32_t MoveToFront(uint64_t* top, uint32_t blocks, uint64_t line) {
  const uint32_t n = 8 * blocks;
  uint32_t d = 0;
  while (d < n && top[d] != line) ++d;
  std::memmove(top + 1, top, sizeof(uint64_t) * (d < n ? d : n - 1));
  top[0] = line;
  return d;
}
#endif

inline void LineQuantiles::Add(Stream& s, uint64_t line) {
  ++s.accesses;
  if (s.top[0] == line) {  // a repeat, over a third of a kernel's accesses: nothing moves
    ++s.below[0];
    return;
  }
  // The blocks that hold the top's lines, and while it is not full the entry after them: a line
  // not there moves the others one down into it.
  const uint32_t blocks = s.held < depth_ ? s.held / 8 + 1 : (depth_ + 7) / 8;
  const uint32_t d = MoveToFront(s.top.data(), blocks, line);
  if (d < s.held) {
    ++s.below[d];
    return;
  }
  // Beyond the top (or found in the padding past depth, where the last line fell before): cold,
  // or a reuse at depth or more.
  uint8_t& mark = s.seen.At(line);
  if (!mark) mark = 1, ++s.cold;
  if (s.held < depth_) ++s.held;
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
