// IdIndex, ChunkResolver, ResolveChunk and StreamedChain; see streamed_chain.h.
#include "analysis/streamed_chain.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/mix.h"

namespace meshreuse {

namespace {
constexpr uint64_t kEmptyKey = ~uint64_t{0};  // reserved by the analyzer: never an id
}  // namespace

IdIndex::IdIndex(const std::vector<uint64_t>& ids) {
  if (ids.size() >= kAbsent) throw std::length_error("IdIndex: too many ids");
  if (ids.empty()) return;
  const auto [lo, hi] = std::minmax_element(ids.begin(), ids.end());
  // The stride every id shares from the least (addresses: their alignment or a scan's step).
  uint64_t spread = 0;
  for (uint64_t id : ids) spread |= id - *lo;
  shift_ = spread ? std::min(32, __builtin_ctzll(spread)) : 0;
  const uint64_t range = (*hi - *lo) >> shift_;  // ids are distinct, so range >= size - 1
  if (range < 4 * ids.size() + 65536) {
    lo_ = *lo;
    mask_ = (uint64_t{1} << shift_) - 1;
    direct_.assign(range + 1, kAbsent);
    for (size_t k = 0; k < ids.size(); ++k)
      direct_[(ids[k] - lo_) >> shift_] = static_cast<uint32_t>(k);
    return;
  }
  direct_mode_ = false;
  size_t cap = 16;
  while (cap < 2 * ids.size()) cap *= 2;
  slots_.assign(cap, Slot{kEmptyKey, kAbsent});
  const size_t mask = cap - 1;
  for (size_t k = 0; k < ids.size(); ++k) {
    size_t j = Mix64(ids[k]) & mask;
    while (slots_[j].key != kEmptyKey) j = (j + 1) & mask;
    slots_[j] = Slot{ids[k], static_cast<uint32_t>(k)};
  }
}

uint32_t IdIndex::FindHashed(uint64_t id) const {
  if (slots_.empty()) return kAbsent;
  const size_t mask = slots_.size() - 1;
  for (size_t j = Mix64(id) & mask;; j = (j + 1) & mask) {
    const Slot& s = slots_[j];
    if (s.key == id) return s.index;
    if (s.key == kEmptyKey) return kAbsent;
  }
}

ChunkResolver::ChunkResolver(const ChunkSummary& s) : s_(s) {}

void ChunkResolver::Filter(const uint64_t* ids, size_t n, std::vector<uint64_t>* out) {
  if (n == 0) return;
  if (!indexed_) {  // the first chunk, before which the stack is empty, never gets here
    index_ = IdIndex(s_.first_ids);
    pos_.assign(s_.first_ids.size(), kNotFound);
    rank_.assign(s_.first_ids.size(), 0);
    indexed_ = true;
  }
  for (size_t i = 0; i < n; ++i) {
    const uint32_t k = index_.Find(ids[i]);
    if (k == IdIndex::kAbsent) {
      out->push_back(ids[i]);
    } else {
      pos_[k] = seen_ + i;
      rank_[k] = found_++;
    }
  }
  seen_ += n;
}

static_assert(StackDistance::kCold == ~uint64_t{0}, "ChunkResolver's cold distance");

std::vector<uint64_t> ChunkResolver::FirstTouchDistances() const {
  std::vector<uint64_t> d(s_.first_ids.size());
  ForEachFirstTouchDistance([&d](size_t k, uint64_t dist) { d[k] = dist; });
  return d;
}

std::vector<uint64_t> ResolveChunk(const ChunkSummary& s, std::vector<uint64_t>* stack) {
  ChunkResolver r(s);
  std::vector<uint64_t> after;
  after.reserve(stack->size() + s.stack.size());
  r.Filter(stack->data(), stack->size(), &after);
  after.insert(after.end(), s.stack.begin(), s.stack.end());
  stack->swap(after);
  return r.FirstTouchDistances();
}

namespace {

// Blocks of the stack between two chunks: a bounded queue, so memory stays at a few blocks per
// link whatever the stack's size.
class Link {
 public:
  static constexpr size_t kDepth = 4;
  explicit Link(std::atomic<bool>* stop) : stop_(stop) {}
  void Push(std::vector<uint64_t> block) {
    std::unique_lock<std::mutex> l(m_);
    cv_.wait(l, [&] { return q_.size() < kDepth || stop_->load(); });
    if (stop_->load()) throw Stopped();
    q_.push_back(std::move(block));
    cv_.notify_all();
  }
  void Close() {
    std::lock_guard<std::mutex> l(m_);
    closed_ = true;
    cv_.notify_all();
  }
  bool Pop(std::vector<uint64_t>* block) {  // false at the end of the stream
    std::unique_lock<std::mutex> l(m_);
    cv_.wait(l, [&] { return !q_.empty() || closed_ || stop_->load(); });
    if (stop_->load()) throw Stopped();
    if (q_.empty()) return false;
    *block = std::move(q_.front());
    q_.pop_front();
    cv_.notify_all();
    return true;
  }
  void Wake() {
    std::lock_guard<std::mutex> l(m_);
    cv_.notify_all();
  }
  struct Stopped {};

 private:
  std::atomic<bool>* stop_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::vector<uint64_t>> q_;
  bool closed_ = false;
};

}  // namespace

void StreamedChain(int p, std::vector<uint64_t>* stack, const ChunkAnalyse& analyse,
                   const ChunkFinish& finish, size_t block) {
  if (p < 1) throw std::invalid_argument("StreamedChain: at least one chunk");
  block = std::max<size_t>(block, 1);
  std::atomic<bool> stop{false};
  std::vector<std::unique_ptr<Link>> links;  // links[c]: chunk c -> chunk c + 1
  for (int c = 0; c + 1 < p; ++c) links.push_back(std::make_unique<Link>(&stop));
  std::vector<uint64_t> after;  // what the last chunk forwards
  std::vector<std::exception_ptr> errors(p);

  auto run = [&](int c) {
    try {
      const ChunkSummary s = analyse(c);
      ChunkResolver r(s);
      std::vector<uint64_t> out;
      auto forward = [&](bool last_piece) {
        if (c + 1 == p) {
          after.insert(after.end(), out.begin(), out.end());
          out.clear();
        } else if (!out.empty() && (last_piece || out.size() >= block)) {
          links[c]->Push(std::move(out));
          out = std::vector<uint64_t>();
        }
      };
      if (c == 0) {
        for (size_t at = 0; at < stack->size(); at += block) {
          r.Filter(stack->data() + at, std::min(block, stack->size() - at), &out);
          forward(false);
        }
      } else {
        std::vector<uint64_t> in;
        while (links[c - 1]->Pop(&in)) {
          r.Filter(in.data(), in.size(), &out);
          forward(false);
        }
      }
      for (size_t at = 0; at < s.stack.size(); at += block) {
        out.insert(out.end(), s.stack.begin() + at,
                   s.stack.begin() + std::min(s.stack.size(), at + block));
        forward(false);
      }
      forward(true);
      if (c + 1 < p) links[c]->Close();
      finish(c, s, r.FirstTouchDistances());
    } catch (Link::Stopped&) {
      // another chunk failed: its error is the one reported
    } catch (...) {
      errors[c] = std::current_exception();
      stop = true;
      for (auto& l : links) l->Wake();
    }
  };
  std::vector<std::thread> threads;
  try {
    for (int c = 1; c < p; ++c) threads.emplace_back(run, c);
  } catch (...) {  // no thread to be had: stop those started
    stop = true;
    for (auto& l : links) l->Wake();
    for (std::thread& t : threads) t.join();
    throw;
  }
  run(0);
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  stack->swap(after);
}

}  // namespace meshreuse
