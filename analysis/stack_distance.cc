// StackDistance; see stack_distance.h.
#include "analysis/stack_distance.h"

#include <algorithm>
#include <stdexcept>

namespace meshreuse {

namespace {
constexpr uint64_t kEmptyKey = std::numeric_limits<uint64_t>::max();
inline uint64_t Mix(uint64_t x) {  // SplitMix64 finaliser
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
inline uint32_t Popcount(uint64_t x) { return static_cast<uint32_t>(__builtin_popcountll(x)); }
}  // namespace

StackDistance::StackDistance(uint64_t dense_limit, uint32_t min_capacity)
    : dense_limit_(std::min<uint64_t>(dense_limit, kHashedBit)),
      min_capacity_(std::max<uint32_t>(128, (min_capacity + 63) & ~63u)) {
  // A small window to start with: a stream's memory follows its own accesses (a trace announcing
  // 256 thread streams with a handful of records each costs a few kilobytes per stream).
  capacity_ = 128;
  bits_.assign(capacity_ / 64, 0);
  owner_.assign(capacity_, 0);
  block_.assign((bits_.size() + 63) / 64, 0);
  super_.assign((block_.size() + 63) / 64, 0);
  keys_.assign(16, kEmptyKey);
  slots_.assign(16, 0);
}

size_t StackDistance::MemoryBytes() const {
  return dense_last_.capacity() * 4 + hashed_last_.capacity() * 4 + keys_.capacity() * 8 +
         slots_.capacity() * 4 + bits_.capacity() * 8 + owner_.capacity() * 4 +
         block_.capacity() * 4 + super_.capacity() * 4;
}

uint32_t& StackDistance::LastOfSlow(uint64_t id, uint32_t* key) {
  if (id < dense_limit_) {
    if (id >= dense_last_.size())
      dense_last_.resize(
          std::max<uint64_t>(id + 1, std::min<uint64_t>(dense_limit_, 2 * dense_last_.size())),
          kNone);
    *key = static_cast<uint32_t>(id);
    return dense_last_[id];
  }
  if (id == kEmptyKey) throw std::invalid_argument("id 2^64-1 is reserved");
  if (2 * (hash_used_ + 1) > keys_.size()) {  // grow at load 1/2
    std::vector<uint64_t> k(keys_.size() * 2, kEmptyKey);
    std::vector<uint32_t> s(keys_.size() * 2);
    const size_t mask = k.size() - 1;
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != kEmptyKey) {
        size_t j = Mix(keys_[i]) & mask;
        while (k[j] != kEmptyKey) j = (j + 1) & mask;
        k[j] = keys_[i];
        s[j] = slots_[i];
      }
    keys_.swap(k);
    slots_.swap(s);
  }
  const size_t mask = keys_.size() - 1;
  size_t j = Mix(id) & mask;
  while (keys_[j] != kEmptyKey && keys_[j] != id) j = (j + 1) & mask;
  if (keys_[j] == kEmptyKey) {
    if (hashed_last_.size() >= kHashedBit - 1) throw std::length_error("too many distinct ids");
    keys_[j] = id;
    slots_[j] = static_cast<uint32_t>(hashed_last_.size());
    hashed_last_.push_back(kNone);
    ++hash_used_;
  }
  *key = kHashedBit | slots_[j];
  return hashed_last_[slots_[j]];
}

uint64_t StackDistance::CountBlocks(uint32_t b, uint32_t be) const {
  uint64_t n = 0;
  while (b < be && (b & 63)) n += block_[b++];
  while (b + 64 <= be) n += super_[b >> 6], b += 64;
  while (b < be) n += block_[b++];
  return n;
}

uint64_t StackDistance::CountWords(uint32_t w, uint32_t we) const {
  uint64_t n = 0;
  if (we - w > 128) {  // far: whole blocks by their counts
    while (w & 63) n += Popcount(bits_[w++]);
    const uint32_t be = we >> 6;
    n += CountBlocks(w >> 6, be);
    w = be << 6;
  }
  while (w < we) n += Popcount(bits_[w++]);
  return n;
}

uint64_t StackDistance::CountLive(uint32_t a, uint32_t b) const {
  if (a >= b) return 0;
  const uint32_t wa = a >> 6, wb = (b - 1) >> 6;
  const uint64_t lo_mask = ~uint64_t{0} << (a & 63);
  const uint64_t hi_mask = ~uint64_t{0} >> (63 - ((b - 1) & 63));
  if (wa == wb) return Popcount(bits_[wa] & lo_mask & hi_mask);
  return Popcount(bits_[wa] & lo_mask) + Popcount(bits_[wb] & hi_mask) + CountWords(wa + 1, wb);
}

uint64_t StackDistance::Access(uint64_t id) {
  ++accesses_;
  uint32_t key;
  uint32_t& last = LastOf(id, &key);
  uint64_t d;
  if (last == kNone) {
    d = kCold;
    ++distinct_;
  } else {
    const uint32_t p = last;
    d = CountLive(p + 1, t_);
    bits_[p >> 6] &= ~(uint64_t{1} << (p & 63));
    --block_[p >> 12];
    --super_[p >> 18];
  }
  if (t_ == capacity_) Compact();  // renumbers `last` of every live id, not its storage
  bits_[t_ >> 6] |= uint64_t{1} << (t_ & 63);
  ++block_[t_ >> 12];
  ++super_[t_ >> 18];
  owner_[t_] = key;
  last = t_;
  ++t_;
  return d;
}

void StackDistance::Compact() {
  ++compactions_;
  const uint64_t live = distinct_ - 1;  // the id being accessed has no marker right now
  // A window of 4x the live markers: compaction (O(window)) then runs once per 3x live accesses;
  // the window costs 4 bytes of owner_ per position, so 16 bytes per distinct id.
  // The floor (min_capacity, fewer compactions) applies once the stream is that long, so the
  // window never exceeds 4x the larger of the distinct ids and the accesses so far.
  uint64_t want =
      std::max<uint64_t>(std::min<uint64_t>(min_capacity_, 4 * accesses_), 4 * live + 64);
  want = (want + 63) & ~uint64_t{63};
  if (want >= kHashedBit) throw std::length_error("too many distinct ids for the analyzer");
  std::vector<uint32_t> owner(want);
  uint32_t k = 0;
  for (uint32_t w = 0; w < bits_.size(); ++w)
    for (uint64_t x = bits_[w]; x; x &= x - 1) {
      const uint32_t key = owner_[w * 64 + __builtin_ctzll(x)];
      owner[k] = key;
      if (key & kHashedBit)
        hashed_last_[key & ~kHashedBit] = k;
      else
        dense_last_[key] = k;
      ++k;
    }
  owner_.swap(owner);
  capacity_ = static_cast<uint32_t>(want);
  bits_.assign(capacity_ / 64, 0);
  block_.assign((bits_.size() + 63) / 64, 0);
  super_.assign((block_.size() + 63) / 64, 0);
  for (uint32_t i = 0; i < k; ++i) {
    bits_[i >> 6] |= uint64_t{1} << (i & 63);
    ++block_[i >> 12];
    ++super_[i >> 18];
  }
  t_ = k;
}

}  // namespace meshreuse
