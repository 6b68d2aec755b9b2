// The lines each sweep touches and the miss floor; see sweep_footprint.h.
#include "analysis/sweep_footprint.h"

#include <algorithm>

#include "core/access.h"

namespace meshreuse {

void SweepFootprint::Begin(const StreamInfo& info) {
  canonical_ = info.canonical;
  sweep_ = 1;
  threads_.assign(static_cast<size_t>(std::max(info.threads, 1)), Thread(canonical_, line_bytes_));
  lines_.assign(threads_.size(), std::vector<uint64_t>(1, 0));
  recent_.assign(threads_.size(), kNoLine);
}

void SweepFootprint::BeginSweep(int sweep) {
  if (sweep <= 1) return;  // the first sweep keeps what came before it
  sweep_ = static_cast<uint32_t>(sweep);
  for (auto& l : lines_) l.resize(static_cast<size_t>(sweep), 0);
  std::fill(recent_.begin(), recent_.end(), kNoLine);  // a new sweep marks its lines anew
}

void SweepFootprint::Consume(const Access* a, size_t n) {
  const bool pow2 = line_bytes_ != 0 && (line_bytes_ & (line_bytes_ - 1)) == 0;
  const int shift = pow2 ? __builtin_ctz(line_bytes_) : 0;
  const uint32_t sweep = sweep_;
  for (size_t k = 0; k < n;) {  // a run of one thread's accesses at a time
    const size_t t = a[k].thread;
    if (t >= threads_.size()) {  // a stream announced with fewer threads: grow
      threads_.resize(t + 1, Thread(canonical_, line_bytes_));
      lines_.resize(t + 1, std::vector<uint64_t>(sweep_, 0));
      recent_.resize(t + 1, kNoLine);
    }
    Thread& marks = threads_[t];
    uint64_t recent = recent_[t], fresh = 0;
    for (; k < n && a[k].thread == t; ++k) {
      const uint64_t line = pow2 ? a[k].address >> shift : a[k].address / line_bytes_;
      if (line == recent) continue;  // the thread's line before: marked in this sweep already
      recent = line;
      uint32_t& last = marks.At(line);
      fresh += last != sweep;
      last = sweep;
    }
    recent_[t] = recent;
    lines_[t][sweep - 1] += fresh;
  }
}

std::vector<uint64_t> MissFloor(const std::vector<std::vector<uint64_t>>& lines,
                                const CacheSpec& cache, uint32_t line_bytes) {
  std::vector<uint64_t> floor;
  uint64_t held = 0;  // lines levels 1..i can hold
  for (const CacheLevel& c : cache.levels) {
    held += c.bytes / line_bytes;
    uint64_t f = 0;
    for (const std::vector<uint64_t>& t : lines)
      for (size_t s = 0; s < t.size(); ++s) f += s == 0 ? t[s] : (t[s] > held ? t[s] - held : 0);
    floor.push_back(f);
  }
  return floor;
}

}  // namespace meshreuse
