// HaloThreads: mailboxes under one mutex; collectives counted in rounds (halo_threads.h).
#include "core/halo_threads.h"

#include <stdexcept>

#include "core/rank_threads.h"

namespace meshreuse {

class HaloThreads::Endpoint : public HaloTransport {
 public:
  Endpoint(HaloThreads& net, int32_t rank) : net_(net), rank_(rank) {}
  int32_t rank() const override { return rank_; }
  int32_t size() const override { return net_.size_; }
  void Send(int32_t to, const double* data, size_t n) override {
    std::lock_guard<std::mutex> lock(net_.mu_);
    net_.box_[{rank_, to}].emplace_back(data, data + n);
    net_.cv_.notify_all();
  }
  void Recv(int32_t from, double* data, size_t n) override {
    std::unique_lock<std::mutex> lock(net_.mu_);
    auto& box = net_.box_[{from, rank_}];
    net_.Wait(lock, [&] { return !box.empty(); });
    if (box.front().size() != n) throw std::logic_error("HaloThreads: message size mismatch");
    std::copy(box.front().begin(), box.front().end(), data);
    box.pop_front();
  }
  void Flush() override {}  // Send copies
  FixedSum SumAll(const FixedSum& mine) override {
    std::unique_lock<std::mutex> lock(net_.mu_);
    const uint64_t round = net_.round_;
    net_.acc_.Add(mine);
    if (++net_.arrived_ == net_.size_) {
      net_.sum_ = net_.acc_;
      net_.acc_ = FixedSum();
      Complete();
    }
    net_.Wait(lock, [&] { return net_.round_ != round; });
    return net_.sum_;
  }
  std::vector<std::string> Gather(const std::string& mine) override {
    std::vector<std::string> all = AllGather(mine);
    if (rank_ != 0) all.clear();
    return all;
  }
  // A rank reads `gathered_` before the next collective can complete: that needs it to arrive.
  std::vector<std::string> AllGather(const std::string& mine) override {
    std::unique_lock<std::mutex> lock(net_.mu_);
    const uint64_t round = net_.round_;
    net_.slots_.resize(net_.size_);
    net_.slots_[rank_] = mine;
    if (++net_.arrived_ == net_.size_) {
      net_.gathered_ = std::move(net_.slots_);
      net_.slots_.clear();
      Complete();
    }
    net_.Wait(lock, [&] { return net_.round_ != round; });
    return net_.gathered_;
  }

 private:
  void Complete() {
    net_.arrived_ = 0;
    ++net_.round_;
    net_.cv_.notify_all();
  }
  HaloThreads& net_;
  int32_t rank_;
};

template <class Ready>
void HaloThreads::Wait(std::unique_lock<std::mutex>& lock, Ready ready) {
  cv_.wait(lock, [&] { return failed_ || ready(); });
  if (failed_) throw RankThreadsFailed();
}

void HaloThreads::Fail() {
  std::lock_guard<std::mutex> lock(mu_);
  failed_ = true;
  cv_.notify_all();
}

void HaloThreads::Run(int32_t size, const std::function<void(HaloTransport&)>& body) {
  HaloThreads net(size);
  RunRankThreads(
      size,
      [&](int32_t r) {
        Endpoint e(net, r);
        body(e);
      },
      [&] { net.Fail(); });
}

}  // namespace meshreuse
