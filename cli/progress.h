// Progress lines on stderr (what, how far, how long); silent with --quiet. Results go to stdout.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace meshreuse::cli {

class Progress {
 public:
  explicit Progress(bool quiet) : quiet_(quiet), start_(Clock::now()) {}
  void Say(const std::string& what) const {
    if (quiet_) return;
    std::fprintf(stderr, "[%7.1fs] %s\n", Elapsed(), what.c_str());
    std::fflush(stderr);
  }
  double Elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  bool quiet() const { return quiet_; }

 private:
  using Clock = std::chrono::steady_clock;
  bool quiet_;
  Clock::time_point start_;
};

}  // namespace meshreuse::cli
