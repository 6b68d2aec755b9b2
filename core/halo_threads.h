// A HaloTransport between threads of one process: P ranks as P threads, messages through
// mailboxes. The distributed smoother's tests run its real schedule with it (no MPI needed), and a
// user without MPI can run P parts in one process. A rank that throws fails the network: every
// rank blocked in it throws too, so a failure never hangs.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/halo_smoother.h"

namespace meshreuse {

class HaloThreads {
 public:
  // Runs body(transport) for ranks 0..size-1, each on a thread of its own, and rethrows the first
  // exception a rank threw.
  static void Run(int32_t size, const std::function<void(HaloTransport&)>& body);

 private:
  class Endpoint;
  explicit HaloThreads(int32_t size) : size_(size) {}
  void Fail();
  template <class Ready>
  void Wait(std::unique_lock<std::mutex>& lock, Ready ready);

  int32_t size_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool failed_ = false;
  std::map<std::pair<int32_t, int32_t>, std::deque<std::vector<double>>> box_;
  int32_t arrived_ = 0;
  uint64_t round_ = 0;
  FixedSum acc_, sum_;
  std::vector<std::string> slots_, gathered_;
};

}  // namespace meshreuse
