// Keeps a library's chatter off standard output: while a StdoutToStderr lives, whatever is
// written to stdout (file descriptor 1, and C stdio's stdout, flushed on both edges) goes to
// stderr. Used around METIS, which may printf; a command's stdout then holds only its result
// (--json and --csv stay parseable). Not thread-safe with other writers of stdout: the library
// calls it guards run while nothing else prints.
#pragma once

#include <unistd.h>

#include <cstdio>

namespace meshreuse {

class StdoutToStderr {
 public:
  StdoutToStderr() {
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
  int saved_ = -1;
};

}  // namespace meshreuse
