// P ranks of a message-passing run as P threads of one process (HaloThreads, ChunkThreads): each
// rank's body on a thread of its own; a rank that throws calls `fail`, which makes every rank
// blocked in the network throw RankThreadsFailed; the first real error is rethrown, not a rank's
// report that another failed. Header-only: core and reports share it.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace meshreuse {

struct RankThreadsFailed : std::runtime_error {
  RankThreadsFailed() : std::runtime_error("another rank failed") {}
};

inline void RunRankThreads(int32_t size, const std::function<void(int32_t rank)>& body,
                           const std::function<void()>& fail) {
  std::vector<std::exception_ptr> error(static_cast<size_t>(size));
  std::vector<std::thread> threads;
  auto run = [&](int32_t r) {
    try {
      body(r);
    } catch (...) {
      error[r] = std::current_exception();
      fail();
    }
  };
  try {
    for (int32_t r = 0; r < size; ++r) threads.emplace_back(run, r);
  } catch (...) {  // no thread to be had: stop those started
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

}  // namespace meshreuse
