// SetAssociativeCache's out-of-line parts (set_associative_cache.h): the geometry's checks, the
// blocks, the tags kept from the first that needs them, the slow installs, renumbering and
// invalidation.
#include "analysis/set_associative_cache.h"

#include <algorithm>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace meshreuse {

void SetAssociativeCache::CheckGeometry(uint64_t bytes, uint32_t ways, uint32_t line_bytes) {
  if (line_bytes == 0 || ways == 0 || bytes == 0 || bytes % (uint64_t{line_bytes} * ways) != 0)
    throw UsageError("a cache of " + std::to_string(bytes) + " B cannot have " +
                     std::to_string(ways) + " ways of " + std::to_string(line_bytes) +
                     " B lines (the size must be a multiple of ways x line size)");
}

SetAssociativeCache::SetAssociativeCache(uint64_t bytes, uint32_t ways, uint32_t line_bytes,
                                         Replacement policy)
    : policy_(policy) {
  CheckGeometry(bytes, ways, line_bytes);
  sets_ = bytes / line_bytes / ways;
  ways_ = ways;
  groups_ = GroupsOf(ways);
  padded_ = 4 * groups_;
  block_bytes_ = 8 * uint64_t{padded_};
  pow2_ = (sets_ & (sets_ - 1)) == 0;
  mask_ = sets_ - 1;
  // 64 B more, so that the sets start on a host cache line: a set of up to eight ways is one.
  if (sets_ > (SIZE_MAX - 64) / block_bytes_) throw std::bad_alloc();
  block_.reset(static_cast<uint8_t*>(std::calloc(1, sets_ * block_bytes_ + 64)));
  if (!block_) throw std::bad_alloc();
  base_ = block_.get() + (64 - reinterpret_cast<uintptr_t>(block_.get()) % 64) % 64;
  if (sets_ * block_bytes_ >= (uint64_t{64} << 10)) pages_.Reset(base_, sets_ * block_bytes_);
  for (uint32_t k = 1; k < 4; ++k) pad_lanes_[k] = k >= 4 - (padded_ - ways_) ? 0x7fffffff : 0;
}

void SetAssociativeCache::KeepTags() {
  const uint64_t n = sets_ * padded_;  // at most 4 * kMaxLines
  tags_.reset(static_cast<uint64_t*>(std::calloc(n, sizeof(uint64_t))));
  if (!tags_) throw std::bad_alloc();
  for (uint64_t i = 0; i < sets_; ++i) {
    const uint32_t* sig = reinterpret_cast<const uint32_t*>(base_ + i * block_bytes_);
    for (uint32_t w = 0; w < ways_; ++w)
      if (sig[w]) tags_[i * padded_ + w] = high_ << 32 | sig[w];
  }
  if (n * sizeof(uint64_t) >= (uint64_t{64} << 10))
    tag_pages_.Reset(tags_.get(), n * sizeof(uint64_t));
  tagged_ = true;
}

template <uint32_t G>
void SetAssociativeCache::InstallSlow(Set s, uint64_t tag) {
  if (!tagged_ && (static_cast<uint32_t>(tag) == 0 || (high_ != kNoHigh && tag >> 32 != high_)))
    KeepTags();
  if (high_ == kNoHigh) high_ = tag >> 32;
  // SigTag's range from now on: the signatures of high_'s half, while no tag is kept.
  sig_lo_ = tagged_ ? 0 : (high_ << 32) + 1;
  sig_span_ = tagged_ ? 0 : (uint64_t{1} << 32) - 1;
  uint64_t* const t = tagged_ ? TagsOf(s) : nullptr;
  uint32_t v = 0;
  if (policy_ == Replacement::kRandom) {
    uint32_t held = 0;  // the ways in use are the first `held` (the old array's positions)
    while (held < ways_ && (t ? t[held] : s.sig[held]) != 0) ++held;
    if (held < ways_) {
      v = held;
    } else {
      rng_ ^= rng_ << 13, rng_ ^= rng_ >> 7, rng_ ^= rng_ << 17;  // xorshift64, seeded
      v = static_cast<uint32_t>(rng_ % ways_);
    }
  } else {
    v = Oldest<G>(s.stamp);  // an empty way's stamp is 0
    s.stamp[v] = Tick();
  }
  if (t) {
    victim_ = t[v] - 1;  // ~0 when the way was empty
    t[v] = tag;
  } else {
    victim_ = s.sig[v] ? (high_ << 32 | s.sig[v]) - 1 : ~uint64_t{0};
  }
  s.sig[v] = static_cast<uint32_t>(tag);
}

template void SetAssociativeCache::InstallSlow<0>(Set, uint64_t);
template void SetAssociativeCache::InstallSlow<1>(Set, uint64_t);
template void SetAssociativeCache::InstallSlow<2>(Set, uint64_t);
template void SetAssociativeCache::InstallSlow<3>(Set, uint64_t);
template void SetAssociativeCache::InstallSlow<4>(Set, uint64_t);
template void SetAssociativeCache::InstallSlow<6>(Set, uint64_t);
template void SetAssociativeCache::InstallSlow<8>(Set, uint64_t);

void SetAssociativeCache::Renumber() {
  // Each set's stamps become 1..k in their order (0, empty, stays): every later comparison within
  // a set, the only kind there is, comes out as before. A set never written reads as zeros
  // (calloc's shared zero page) and is left unwritten.
  std::vector<std::pair<uint32_t, uint32_t>> order;
  for (uint64_t i = 0; i < sets_; ++i) {
    uint32_t* stamp = reinterpret_cast<uint32_t*>(base_ + i * block_bytes_) + padded_;
    order.clear();
    for (uint32_t w = 0; w < ways_; ++w)
      if (stamp[w] != 0) order.emplace_back(stamp[w], w);
    std::sort(order.begin(), order.end());
    for (uint32_t k = 0; k < order.size(); ++k) stamp[order[k].second] = k + 1;
  }
  clock_ = ways_;
}

bool SetAssociativeCache::Invalidate(uint64_t line) {
  const Set s = SetOf(line);
  const uint32_t w = Find<0>(s, line + 1);
  if (w == kNone) return false;
  uint64_t* const t = tagged_ ? TagsOf(s) : nullptr;
  if (policy_ == Replacement::kRandom) {  // positions: the ways after it move up
    for (uint32_t j = w; j + 1 < ways_; ++j) {
      if (t) t[j] = t[j + 1];
      s.sig[j] = s.sig[j + 1];
    }
    if (t) t[ways_ - 1] = 0;
    s.sig[ways_ - 1] = 0;
  } else {
    if (t) t[w] = 0;
    s.sig[w] = 0, s.stamp[w] = 0;
  }
  return true;
}

}  // namespace meshreuse
