// InputFile::Read on a pipe whose writer is slow while a signal handler installed without
// SA_RESTART fires (libFuzzer's timer did so in CI): the read must wait on and return every byte
// the writer sends, not fail with "read error: Interrupted system call".
#include "core/input_file.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <string>
#include <thread>

namespace meshreuse {
namespace {

std::atomic<int> g_caught{0};
void Count(int) { g_caught.fetch_add(1); }

TEST(InputFile, PipeReadSurvivesASignalWithoutRestart) {
  struct sigaction sa {
  }, old{};
  sa.sa_handler = Count;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocked read returns EINTR
  ASSERT_EQ(::sigaction(SIGUSR1, &sa, &old), 0);
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pthread_t reader = ::pthread_self();
  const std::string payload(1000, 'x');
  std::atomic<bool> reading{false};
  std::thread writer([&] {
    while (!reading.load()) std::this_thread::yield();
    // Interrupt the reader while it waits on the empty pipe, a few times, then write.
    for (int k = 0; k < 5; ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      ::pthread_kill(reader, SIGUSR1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    for (size_t at = 0; at < payload.size();) {
      const ssize_t n =
          ::write(fds[1], payload.data() + at, std::min<size_t>(100, payload.size() - at));
      if (n <= 0) break;
      at += static_cast<size_t>(n);
    }
    ::close(fds[1]);
  });
  std::string got(2000, '\0');
  size_t n = 0;
  std::string error;
  try {
    InputFile f("/proc/self/fd/" + std::to_string(fds[0]));
    EXPECT_EQ(f.size(), -1);
    reading = true;
    n = f.Read(&got[0], got.size());
  } catch (const InputError& e) {
    error = e.problem();
  }
  writer.join();
  ::close(fds[0]);
  ::sigaction(SIGUSR1, &old, nullptr);
  EXPECT_EQ(error, "");
  EXPECT_GE(g_caught.load(), 1);
  EXPECT_EQ(n, payload.size());
  EXPECT_EQ(got.substr(0, n), payload);
}

}  // namespace
}  // namespace meshreuse
