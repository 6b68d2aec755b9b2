// A Communicator between threads of one process: P ranks as P threads, every link a mailbox
// (bounded at kDepth messages, communicator.h), the collectives counted in rounds under one mutex.
// The distributed smoother's, refinement's and analysis's tests run their real schedules on it
// without MPI, `meshreuse analyze TRACE --threads P` analyses a file as P chunks on it, and a user
// without MPI runs P parts in one process (`smooth-ranks`). Objects change hands without being
// encoded (SharesMemory). A rank that throws fails the network: every rank blocked in it throws
// RankThreadsFailed, and the first real error is rethrown, not a rank's report that another
// failed.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/ranks/communicator.h"

namespace meshreuse {

// What a rank blocked in the network throws when another rank failed.
struct RankThreadsFailed : std::runtime_error {
  RankThreadsFailed() : std::runtime_error("another rank failed") {}
};

class ThreadCommunicator {
 public:
  // Runs body(communicator) for ranks 0..size-1, each on a thread of its own, and rethrows the
  // first exception a rank threw.
  static void Run(int32_t size, const std::function<void(Communicator&)>& body);

 private:
  class Endpoint;
  struct Message {
    std::string bytes;
    std::shared_ptr<void> object;
  };
  explicit ThreadCommunicator(int32_t size) : size_(size) {}
  template <class Ready>
  void Wait(std::unique_lock<std::mutex>& lock, Ready ready);
  std::deque<Message>& Link(int32_t from, int32_t to) { return links_[{from, to}]; }

  int32_t size_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool failed_ = false;
  std::map<std::pair<int32_t, int32_t>, std::deque<Message>> links_;  // (from, to); as used
  int32_t arrived_ = 0;
  uint64_t round_ = 0;
  std::vector<std::string> slots_, gathered_;
};

}  // namespace meshreuse
