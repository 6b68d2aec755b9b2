// ThreadCommunicator: mailboxes under one mutex; the all-gather counted in rounds
// (thread_communicator.h).
#include "core/ranks/thread_communicator.h"

#include <omp.h>

#include <exception>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "core/error.h"

namespace meshreuse {

namespace {

// Each rank's body on a thread of its own; a rank that throws calls `fail`.
void RunRankThreads(int32_t size, const std::function<void(int32_t rank)>& body,
                    const std::function<void()>& fail) {
  std::vector<std::exception_ptr> error(static_cast<size_t>(size));
  std::vector<std::thread> threads;
  auto run = [&](int32_t r) {
    try {
      // A rank is one thread: its OpenMP regions (reading, building its mesh) run on it alone, not
      // a team per rank (4096 ranks x a team's threads exhaust the process's limits).
      omp_set_num_threads(1);
      body(r);
    } catch (...) {
      error[r] = std::current_exception();
      fail();
    }
  };
  try {
    for (int32_t r = 0; r < size; ++r) threads.emplace_back(run, r);
  } catch (const std::system_error& e) {  // no thread to be had: stop those started
    fail();
    for (std::thread& t : threads) t.join();
    throw EnvironmentError("ranks as threads",
                           "could start " + std::to_string(threads.size()) + " of " +
                               std::to_string(size) + " rank threads (" + e.what() +
                               "): this process's limits allow fewer (--ranks)");
  } catch (...) {
    fail();
    for (std::thread& t : threads) t.join();
    throw;
  }
  for (std::thread& t : threads) t.join();
  for (int pass = 0; pass < 2; ++pass)
    for (int32_t r = 0; r < size; ++r)
      if (error[r]) {
        try {
          std::rethrow_exception(error[r]);
        } catch (const RankThreadsFailed&) {
          if (pass == 0) continue;
          throw;
        }
      }
}

}  // namespace

class ThreadCommunicator::Endpoint : public Communicator {
 public:
  Endpoint(ThreadCommunicator& net, int32_t rank) : net_(net), rank_(rank) {}
  int32_t rank() const override { return rank_; }
  int32_t size() const override { return net_.size_; }
  void Send(int32_t to, std::string&& bytes) override {
    Put(to, Message{std::move(bytes), nullptr});
  }
  std::string Recv(int32_t from) override {
    Message m = Take(from);
    if (m.object) throw std::logic_error("ThreadCommunicator: an object where bytes were expected");
    return std::move(m.bytes);
  }
  std::vector<std::string> AllGather(const std::string& mine) override {
    std::unique_lock<std::mutex> lock(net_.mu_);
    const uint64_t round = net_.round_;
    net_.slots_.resize(static_cast<size_t>(net_.size_));
    net_.slots_[rank_] = mine;
    if (++net_.arrived_ == net_.size_) {
      net_.gathered_ = std::move(net_.slots_);
      net_.slots_.clear();
      net_.arrived_ = 0;
      ++net_.round_;
      net_.cv_.notify_all();
    }
    // A rank reads `gathered_` before the next all-gather can complete: that needs it to arrive.
    net_.Wait(lock, [&] { return net_.round_ != round; });
    return net_.gathered_;
  }
  bool SharesMemory() const override { return true; }
  void SendObject(int32_t to, std::shared_ptr<void> object) override {
    if (!object) throw std::logic_error("ThreadCommunicator: no object to send");
    Put(to, Message{std::string(), std::move(object)});
  }
  std::shared_ptr<void> RecvObject(int32_t from) override {
    Message m = Take(from);
    if (!m.object) throw std::logic_error("ThreadCommunicator: bytes where an object was expected");
    return std::move(m.object);
  }

 private:
  void Check(int32_t other) const {
    if (other < 0 || other >= net_.size_ || other == rank_)
      throw std::logic_error("ThreadCommunicator: no link to rank " + std::to_string(other));
  }
  void Put(int32_t to, Message&& m) {
    Check(to);
    std::unique_lock<std::mutex> lock(net_.mu_);
    auto& link = net_.Link(rank_, to);
    net_.Wait(lock, [&] { return link.size() < kDepth; });
    link.push_back(std::move(m));
    net_.cv_.notify_all();
  }
  Message Take(int32_t from) {
    Check(from);
    std::unique_lock<std::mutex> lock(net_.mu_);
    auto& link = net_.Link(from, rank_);
    net_.Wait(lock, [&] { return !link.empty(); });
    Message m = std::move(link.front());
    link.pop_front();
    net_.cv_.notify_all();  // a sender may be waiting for room
    return m;
  }
  ThreadCommunicator& net_;
  int32_t rank_;
};

template <class Ready>
void ThreadCommunicator::Wait(std::unique_lock<std::mutex>& lock, Ready ready) {
  cv_.wait(lock, [&] { return failed_ || ready(); });
  if (failed_) throw RankThreadsFailed();
}

void ThreadCommunicator::Run(int32_t size, const std::function<void(Communicator&)>& body) {
  if (size < 1) throw std::invalid_argument("ThreadCommunicator: at least one rank");
  ThreadCommunicator net(size);
  RunRankThreads(
      size,
      [&](int32_t r) {
        Endpoint e(net, r);
        body(e);
      },
      [&] {
        std::lock_guard<std::mutex> lock(net.mu_);
        net.failed_ = true;
        net.cv_.notify_all();
      });
}

}  // namespace meshreuse
