// StackDistance; see stack_distance.h.
#include "analysis/stack_distance.h"

#include <algorithm>
#include <stdexcept>

#include "core/mix.h"

namespace meshreuse {

namespace {
constexpr uint64_t kEmptyKey = std::numeric_limits<uint64_t>::max();
inline uint32_t Popcount(uint64_t x) { return static_cast<uint32_t>(__builtin_popcountll(x)); }
constexpr uint32_t kGroup = 512;
}  // namespace

StackDistance::StackDistance(uint64_t dense_ids, uint32_t min_capacity)
    : dense_ids_(std::min<uint64_t>(dense_ids, kHashedBit)),
      min_capacity_(std::max<uint32_t>(kGroup, (min_capacity + kGroup - 1) & ~(kGroup - 1))) {
  window_set_ = dense_ids_ > 0;  // a known-dense range: entry i is id i
  // A small window to start with: a stream's memory follows its own accesses (a trace announcing
  // 256 thread streams with a handful of records each costs a few kilobytes per stream).
  capacity_ = kGroup;
  bits_.assign(capacity_ / 64, 0);
  owner_.Resize(capacity_);
  tree_.assign(capacity_ / kGroup + 1, 0);
  keys_.assign(16, kEmptyKey);
  slots_.assign(16, 0);
}

size_t StackDistance::MemoryBytes() const {
  return dense_last_.capacity() * 4 + hashed_last_.capacity() * 4 + free_slots_.capacity() * 4 +
         keys_.capacity() * 8 + slots_.capacity() * 4 + bits_.capacity() * 8 + owner_.size() * 4 +
         tree_.capacity() * 4;
}

uint32_t* StackDistance::FindHashed(uint64_t id, size_t* slot_index) {
  const size_t mask = keys_.size() - 1;
  size_t j = Mix64(id) & mask;
  while (keys_[j] != kEmptyKey && keys_[j] != id) j = (j + 1) & mask;
  *slot_index = j;
  return keys_[j] == id ? &hashed_last_[slots_[j]] : nullptr;
}

void StackDistance::GrowDense(uint64_t index) {
  const uint64_t old = dense_last_.size();
  const uint64_t cap = index < dense_ids_ ? dense_ids_ : kHashedBit;
  // Growth by a quarter, not a doubling: the array is written (resident) to its size, and at the
  // end of a stream a doubling leaves up to half of it unused.
  dense_last_.resize(std::max<uint64_t>(index + 1, std::min<uint64_t>(cap, old + old / 4 + 1024)),
                     kNone);
  MoveHashedIntoArray();
}

void StackDistance::GrowDown(uint64_t entries) {
  // The window's start moves down: every entry and every direct marker's key moves up by
  // `entries` (O(array + window), so by at least a quarter of the array at a time).
  dense_last_.insert(dense_last_.begin(), entries, kNone);
  base_ -= entries << shift_;
  for (uint32_t w = 0; w < bits_.size(); ++w)
    for (uint64_t x = bits_[w]; x; x &= x - 1) {
      uint32_t& key = owner_[w * 64 + __builtin_ctzll(x)];
      if (!(key & kHashedBit)) key += static_cast<uint32_t>(entries);
    }
  MoveHashedIntoArray();
}

void StackDistance::MoveHashedIntoArray() {
  if (hash_used_ == 0) return;
  // Hashed ids now inside the array move there (their markers' owners too), each deleted from the
  // table where it stands (backward shift, O(its cluster)): rebuilding the whole table per growth
  // step, as before, cost about a fifth of the time on a stride-64 address scan.
  const uint64_t now = dense_last_.size();
  for (size_t j = 0; j < keys_.size();) {
    const uint64_t i = keys_[j] == kEmptyKey ? kHashedBit : WindowIndex(keys_[j]);
    if (i >= now) {
      ++j;
      continue;
    }
    const uint32_t slot = slots_[j];
    const uint32_t pos = hashed_last_[slot];
    dense_last_[i] = pos;
    if (pos != kNone) owner_[pos] = static_cast<uint32_t>(i);
    hashed_last_[slot] = kNone;
    EraseAt(j);  // may move a later entry into j: look at j again
  }
}

void StackDistance::SetWindow() {
  std::vector<uint64_t> ids;
  for (uint64_t k : keys_)
    if (k != kEmptyKey) ids.push_back(k);
  // The stride: the largest 2^s (s <= 32) that three quarters of the ids share a residue modulo
  // (a few ids of another alignment or another region must not decide it).
  shift_ = 0;
  uint64_t residue = 0;
  std::vector<uint64_t> r(ids.size());
  for (uint32_t sh = 32; sh > 0; --sh) {
    const uint64_t m = (uint64_t{1} << sh) - 1;
    for (size_t i = 0; i < ids.size(); ++i) r[i] = ids[i] & m;
    std::sort(r.begin(), r.end());
    size_t best = 0;
    for (size_t i = 0, j = 0; i < r.size(); i = j) {
      while (j < r.size() && r[j] == r[i]) ++j;
      if (j - i > best) best = j - i, residue = r[i];
    }
    if (4 * best >= 3 * ids.size()) {
      shift_ = sh;
      break;
    }
  }
  mask_ = (uint64_t{1} << shift_) - 1;
  residue = shift_ ? residue : 0;
  // The base: 32 Ki strides below the median of the ids on the stride (the window grows down as
  // well as up, so the ids below it come in as they are met).
  std::vector<uint64_t> on;
  for (uint64_t id : ids)
    if ((id & mask_) == residue) on.push_back(id);
  std::nth_element(on.begin(), on.begin() + on.size() / 2, on.end());
  const uint64_t median = on[on.size() / 2];
  constexpr uint64_t kSlack = 1u << 15;
  base_ = median >= (kSlack << shift_) ? median - (kSlack << shift_) : residue;
  window_set_ = true;
}

void StackDistance::EraseAt(size_t j) {
  free_slots_.push_back(slots_[j]);
  const size_t mask = keys_.size() - 1;
  size_t hole = j;
  for (size_t i = (j + 1) & mask; keys_[i] != kEmptyKey; i = (i + 1) & mask) {
    const size_t home = Mix64(keys_[i]) & mask;
    // Move i into the hole unless its home lies cyclically in (hole, i].
    const bool stays = hole <= i ? (home > hole && home <= i) : (home > hole || home <= i);
    if (!stays) {
      keys_[hole] = keys_[i];
      slots_[hole] = slots_[i];
      hole = i;
    }
  }
  keys_[hole] = kEmptyKey;
  --hash_used_;
}

uint32_t& StackDistance::LastOfSlow(uint64_t id, uint32_t* key) {
  // Not covered by the array (the inline path takes those). Once 64 ids are held in the table the
  // window is chosen from them; then grow the array over `id` when `id` is in the known-dense
  // range, or when the array would stay within 8 entries per distinct id (+ 64 Ki).
  if (!window_set_ && hash_used_ >= 64) SetWindow();  // 64 ids held now (a sampler removes some)
  if (window_set_) {
    const uint64_t i = WindowIndex(id);
    if (i < dense_last_.size()) {  // covered since SetWindow (the array may be empty before)
      *key = static_cast<uint32_t>(i);
      return dense_last_[i];
    }
    if (id < dense_ids_ || (i < kHashedBit && i < 8 * (distinct_ + 8192))) {
      GrowDense(i);
      *key = static_cast<uint32_t>(i);
      return dense_last_[i];
    }
    // Below the window, on its stride: grow it down while it stays within the same bound.
    if (dense_ids_ == 0 && id < base_ && ((base_ - id) & mask_) == 0) {
      const uint64_t need = (base_ - id) >> shift_, size = dense_last_.size();
      const uint64_t grow = std::min(std::max(need, size / 4 + 1024), base_ >> shift_);
      if (size + grow < std::min<uint64_t>(kHashedBit, 8 * (distinct_ + 8192))) {
        GrowDown(grow);
        const uint64_t j = WindowIndex(id);
        *key = static_cast<uint32_t>(j);
        return dense_last_[j];
      }
    }
  }
  if (id == kEmptyKey) throw std::invalid_argument("id 2^64-1 is reserved");
  if (2 * (hash_used_ + 1) > keys_.size()) {  // grow at load 1/2
    std::vector<uint64_t> k(keys_.size() * 2, kEmptyKey);
    std::vector<uint32_t> s(keys_.size() * 2);
    const size_t mask = k.size() - 1;
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != kEmptyKey) {
        size_t j = Mix64(keys_[i]) & mask;
        while (k[j] != kEmptyKey) j = (j + 1) & mask;
        k[j] = keys_[i];
        s[j] = slots_[i];
      }
    keys_.swap(k);
    slots_.swap(s);
  }
  size_t j;
  if (uint32_t* last = FindHashed(id, &j)) {
    *key = kHashedBit | slots_[j];
    return *last;
  }
  uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    if (hashed_last_.size() >= kHashedBit - 1) throw std::length_error("too many distinct ids");
    slot = static_cast<uint32_t>(hashed_last_.size());
    hashed_last_.push_back(kNone);
  }
  keys_[j] = id;
  slots_[j] = slot;
  ++hash_used_;
  *key = kHashedBit | slot;
  return hashed_last_[slot];
}

uint64_t StackDistance::LiveAfter(uint32_t p) const {
  const uint32_t wp = p >> 6, wt = t_ >> 6;
  const uint64_t above_p = ~uint64_t{1} << (p & 63);  // bits > p within its word (p&63 < 63 ok)
  const uint64_t below_t = (uint64_t{1} << (t_ & 63)) - 1;
  if (wp == wt) return Popcount(bits_[wp] & above_p & below_t);
  if (wt - wp <= kShortWords) {
    uint64_t n = Popcount(bits_[wp] & above_p);
    for (uint32_t w = wp + 1; w < wt; ++w) n += Popcount(bits_[w]);
    if (wt < bits_.size()) n += Popcount(bits_[wt] & below_t);
    return n;
  }
  // Far: live total - live up to and including p. p's group is closed (it is more than a group
  // before t_), so the tree holds every group before it.
  const uint32_t g = p >> kGroupShift;
  uint64_t upto = 0;
  for (uint32_t i = g; i > 0; i -= i & (0u - i)) upto += static_cast<uint32_t>(tree_[i]);
  for (uint32_t w = g << 3; w < wp; ++w) upto += Popcount(bits_[w]);
  upto += Popcount(bits_[wp] & (~uint64_t{0} >> (63 - (p & 63))));
  return live_ - upto;
}

template <bool kDistance>
uint64_t StackDistance::Visit(uint64_t id) {
  ++accesses_;
  uint32_t key;
  uint32_t& last = LastOf(id, &key);
  uint64_t d = kCold;
  if (last == kNone) {
    ++distinct_;
  } else if (last + 1 == t_) {
    // Its marker is the newest: the top of the stack, distance 0, and moving it to the top
    // changes no later count (no marker lies between the two times). About half of a
    // smoother's line accesses repeat the line before them; they cost no marker, so the window
    // fills (and compacts) more slowly too.
    return 0;
  } else {
    const uint32_t p = last;
    if (kDistance) d = LiveAfter(p);
    ClearMarker(p);
    --live_;
  }
  if (t_ == capacity_) Compact();  // renumbers `last` of every live id, not its storage
  if ((t_ & (kGroup - 1)) == 0 && t_ > 0) CloseGroups();
  bits_[t_ >> 6] |= uint64_t{1} << (t_ & 63);
  owner_[t_] = key;
  last = t_;
  ++t_;
  ++live_;
  return d;
}

template uint64_t StackDistance::Visit<true>(uint64_t);
template uint64_t StackDistance::Visit<false>(uint64_t);

bool StackDistance::Remove(uint64_t id) {
  uint32_t* last = nullptr;
  size_t j = 0;
  const uint64_t i = WindowIndex(id);
  const bool direct = i < dense_last_.size();
  if (direct) {
    if (dense_last_[i] != kNone) last = &dense_last_[i];
  } else if (id != kEmptyKey) {
    last = FindHashed(id, &j);
  }
  if (!last || *last == kNone) return false;
  ClearMarker(*last);
  --live_;
  *last = kNone;
  if (!direct) EraseAt(j);  // backward-shift deletion keeps probing exact
  return true;
}

std::vector<uint64_t> StackDistance::StackBottomUp() const {
  std::vector<uint64_t> slot_id;  // hashed slot -> id, built on demand
  if (!hashed_last_.empty()) {
    slot_id.assign(hashed_last_.size(), 0);
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != kEmptyKey) slot_id[slots_[i]] = keys_[i];
  }
  std::vector<uint64_t> out;
  out.reserve(live_);
  for (uint32_t w = 0; w < bits_.size(); ++w)
    for (uint64_t x = bits_[w]; x; x &= x - 1) {
      const uint32_t key = owner_[w * 64 + __builtin_ctzll(x)];
      out.push_back(key & kHashedBit ? slot_id[key & ~kHashedBit]
                                     : base_ + (uint64_t{key} << shift_));
    }
  return out;
}

void StackDistance::CloseGroups() {
  for (; closed_ < (t_ >> kGroupShift); ++closed_) {
    uint32_t n = 0;
    for (uint32_t w = closed_ << 3; w < (closed_ + 1) << 3; ++w) n += Popcount(bits_[w]);
    if (n) TreeAdd(closed_, static_cast<int32_t>(n));
  }
}

void StackDistance::TouchAll(const uint64_t* ids, size_t n) {
  if (n * 8 < live_ || n < 4096) {
    for (size_t i = 0; i < n; ++i) Touch(ids[i]);
    return;
  }
  // Take the ids out of the stack (bits only: the tree is rebuilt), renumber what is left, then
  // append them in order.
  accesses_ += n;
  for (size_t i = 0; i < n; ++i) {
    uint32_t key;
    uint32_t& last = LastOf(ids[i], &key);
    if (last == kNone) {
      ++distinct_;
    } else {
      bits_[last >> 6] &= ~(uint64_t{1} << (last & 63));
      --live_;
    }
    last = kNone;
  }
  Compact(n);
  for (size_t i = 0; i < n; ++i) {
    uint32_t key;
    uint32_t& last = LastOf(ids[i], &key);
    if (last != kNone) throw std::invalid_argument("TouchAll: the ids must be distinct");
    bits_[t_ >> 6] |= uint64_t{1} << (t_ & 63);
    owner_[t_] = key;
    last = t_++;
    ++live_;
  }
  // The appended markers are all live: groups wholly below t_ are full.
  for (; closed_ < (t_ >> kGroupShift); ++closed_) TreeAdd(closed_, static_cast<int32_t>(kGroup));
}

void StackDistance::Compact(uint64_t extra) {
  ++compactions_;
  // A window of kWindow x the live markers: compaction (O(window)) then runs once per
  // (kWindow - 1) x live accesses; the window costs 4 bytes of owner_ per position. At 2x, 8 bytes
  // per distinct id and two positions scanned per access (4x: 16 bytes, 1.33 positions; measured
  // no slower on the mesh traces, issue 12, while a third of `analyze MESH`'s analyzer memory).
  // The floor (min_capacity, fewer compactions) applies once the stream is that long, so the
  // window never exceeds kWindow x the larger of the live ids and the accesses so far.
  constexpr uint64_t kWindow = 2;
  uint64_t want = std::max<uint64_t>(std::min<uint64_t>(min_capacity_, kWindow * accesses_),
                                     kWindow * (live_ + extra) + 64);
  want = (want + kGroup - 1) & ~uint64_t{kGroup - 1};
  if (want >= kHashedBit) throw std::length_error("too many distinct ids for the analyzer");
  // In place: live markers move down in position order (k never passes the position read), then
  // the window takes its new size by realloc.
  uint32_t k = 0;
  for (uint32_t w = 0; w < bits_.size(); ++w)
    for (uint64_t x = bits_[w]; x; x &= x - 1) {
      const uint32_t key = owner_[w * 64 + __builtin_ctzll(x)];
      owner_[k] = key;
      if (key & kHashedBit)
        hashed_last_[key & ~kHashedBit] = k;
      else
        dense_last_[key] = k;
      ++k;
    }
  owner_.Resize(want);
  capacity_ = static_cast<uint32_t>(want);
  bits_.assign(capacity_ / 64, 0);
  for (uint32_t i = 0; i < k; ++i) bits_[i >> 6] |= uint64_t{1} << (i & 63);
  // Every group wholly below k is full: build the tree over them in O(groups).
  tree_.assign(capacity_ / kGroup + 1, 0);
  closed_ = k >> kGroupShift;
  for (uint32_t i = 1; i < tree_.size(); ++i) {
    if (i <= closed_) tree_[i] += static_cast<int32_t>(kGroup);
    const uint32_t parent = i + (i & (0u - i));
    if (parent < tree_.size()) tree_[parent] += tree_[i];
  }
  t_ = k;
}

}  // namespace meshreuse
