// Keeps a library's chatter off standard output: while a StdoutToStderr lives, whatever is
// written to stdout (file descriptor 1, and C stdio's stdout, flushed on both edges) goes to
// stderr. Used around METIS, which may printf; a command's stdout then holds only its result
// (--json and --csv stay parseable). One guard at a time in the process (a mutex): the redirection
// is process-wide, and METIS keeps its random state in globals, so two ranks of
// `meshreuse smooth-ranks` (threads) calling it at once would interleave both. Not safe against
// other threads printing meanwhile: the distributed smoother's rank 0 prints only after a
// collective that every rank reaches past its METIS calls.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <mutex>

namespace meshreuse {

class StdoutToStderr {
 public:
  StdoutToStderr() : lock_(Mutex()) {
    std::fflush(stdout);
    saved_ = ::dup(1);
    if (saved_ >= 0 && ::dup2(2, 1) < 0) {
      ::close(saved_);
      saved_ = -1;
    }
  }
  ~StdoutToStderr() {
    std::fflush(stdout);
    if (saved_ >= 0) {
      ::dup2(saved_, 1);
      ::close(saved_);
    }
  }
  StdoutToStderr(const StdoutToStderr&) = delete;
  StdoutToStderr& operator=(const StdoutToStderr&) = delete;

 private:
  static std::mutex& Mutex() {
    static std::mutex mu;
    return mu;
  }
  std::lock_guard<std::mutex> lock_;
  int saved_ = -1;
};

}  // namespace meshreuse
