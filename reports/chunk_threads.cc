// ChunkThreads: one mutex over the links, mailboxes and collectives; collectives counted in rounds
// (chunk_threads.h).
#include "reports/chunk_threads.h"

#include <sys/stat.h>

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <thread>

#include "core/rank_threads.h"
#include "tracer/input_stream.h"

namespace meshreuse {

class ChunkThreads::Endpoint : public ChunkTransport {
 public:
  Endpoint(ChunkThreads& net, int rank) : net_(net), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return net_.size_; }
  void SendIds(const uint64_t* ids, size_t n) override {
    if (rank_ + 1 >= net_.size_) throw std::logic_error("ChunkThreads: the last rank sends no ids");
    std::vector<uint64_t> block(ids, ids + n);  // copied outside the lock
    std::unique_lock<std::mutex> lock(net_.mu_);
    auto& q = net_.ids_[rank_ + 1];
    net_.Wait(lock, [&] { return q.size() < kDepth; });
    q.push_back(std::move(block));
    net_.cv_.notify_all();
  }
  size_t RecvIds(std::vector<uint64_t>* ids) override {
    if (rank_ == 0) throw std::logic_error("ChunkThreads: rank 0 receives no ids");
    std::unique_lock<std::mutex> lock(net_.mu_);
    auto& q = net_.ids_[rank_];
    net_.Wait(lock, [&] { return !q.empty(); });
    ids->swap(q.front());
    q.pop_front();
    net_.cv_.notify_all();
    return ids->size();
  }
  void SendBytes(int to, const std::string& bytes) override { PostBytes(to, std::string(bytes)); }
  void PostBytes(int to, std::string&& bytes) override {
    std::lock_guard<std::mutex> lock(net_.mu_);
    net_.bytes_[{rank_, to}].push_back(std::move(bytes));
    net_.cv_.notify_all();
  }
  std::string RecvBytes(int from) override {
    std::unique_lock<std::mutex> lock(net_.mu_);
    auto& box = net_.bytes_[{from, rank_}];
    net_.Wait(lock, [&] { return !box.empty(); });
    std::string b = std::move(box.front());
    box.pop_front();
    return b;
  }
  uint64_t SendSummary(int to, SummaryFile&& s) override {
    std::lock_guard<std::mutex> lock(net_.mu_);
    net_.summaries_[{rank_, to}].push_back(std::move(s));
    net_.cv_.notify_all();
    return 0;  // no bytes: the object changes hands
  }
  SummaryFile RecvSummary(int from, const std::string&) override {
    std::unique_lock<std::mutex> lock(net_.mu_);
    auto& box = net_.summaries_[{from, rank_}];
    net_.Wait(lock, [&] { return !box.empty(); });
    SummaryFile s = std::move(box.front());
    box.pop_front();
    return s;
  }
  std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v) override {
    const auto all = Collect(v);
    std::vector<uint64_t> m = all[0];
    for (const auto& x : all) {
      if (x.size() != m.size()) throw std::logic_error("ChunkThreads: lengths differ");
      for (size_t i = 0; i < m.size(); ++i) m[i] = std::max(m[i], x[i]);
    }
    return m;
  }
  std::vector<uint64_t> ExclusiveScanSum(const std::vector<uint64_t>& v) override {
    const auto all = Collect(v);
    std::vector<uint64_t> s(v.size(), 0);
    for (int r = 0; r < rank_; ++r) {
      if (all[r].size() != s.size()) throw std::logic_error("ChunkThreads: lengths differ");
      for (size_t i = 0; i < s.size(); ++i) s[i] += all[r][i];
    }
    return s;
  }

 private:
  // Every rank's vector, once all have arrived. A rank reads `results_` before the next
  // collective can complete: that needs this rank to arrive.
  std::vector<std::vector<uint64_t>> Collect(const std::vector<uint64_t>& mine) {
    std::unique_lock<std::mutex> lock(net_.mu_);
    const uint64_t round = net_.round_;
    net_.slots_.resize(static_cast<size_t>(net_.size_));
    net_.slots_[rank_] = mine;
    if (++net_.arrived_ == net_.size_) {
      net_.results_ = std::move(net_.slots_);
      net_.slots_.clear();
      net_.arrived_ = 0;
      ++net_.round_;
      net_.cv_.notify_all();
    }
    net_.Wait(lock, [&] { return net_.round_ != round; });
    return net_.results_;
  }
  ChunkThreads& net_;
  int rank_;
};

template <class Ready>
void ChunkThreads::Wait(std::unique_lock<std::mutex>& lock, Ready ready) {
  cv_.wait(lock, [&] { return failed_ || ready(); });
  if (failed_) throw RankThreadsFailed();
}

void ChunkThreads::Run(int size, const std::function<void(ChunkTransport&)>& body) {
  if (size < 1) throw std::invalid_argument("ChunkThreads: at least one rank");
  ChunkThreads net(size);
  RunRankThreads(
      size,
      [&](int rank) {
        Endpoint e(net, rank);
        body(e);
      },
      [&] {
        std::lock_guard<std::mutex> lock(net.mu_);
        net.failed_ = true;
        net.cv_.notify_all();
      });
}

bool CanAnalyzeInChunks(const AnalyzeConfig& cfg, const std::string& in) {
  if (in == "-" || (cfg.sample && (cfg.shards.s_max || cfg.shards.exact_below))) return false;
  struct stat st;
  if (::stat(in.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  try {
    const InputStream s(in);
    return !s.compressed() ||
           (s.seekable() && s.entry_points() >= static_cast<uint64_t>(std::max(cfg.threads, 1)));
  } catch (const std::exception&) {
    return false;  // the batched analyzer reports it
  }
}

AnalyzeResult AnalyzeChunksOnThreads(const AnalyzeConfig& cfg, int p, const Log& log) {
  AnalyzeConfig one = cfg;
  one.threads = 1;  // each chunk on its own thread
  AnalyzeResult result;
  const Log quiet;
  ChunkThreads::Run(p, [&](ChunkTransport& tx) {
    AnalyzeConfig mine = one;
    mine.transport = &tx;
    AnalyzeResult r = RunDistributed(mine, tx, tx.rank() == 0 ? log : quiet);
    if (tx.rank() == 0) result = std::move(r);
  });
  return result;
}

}  // namespace meshreuse
