// Progress lines on stderr (what, how far, how long); silent with --quiet. Results go to stdout.
#pragma once

#include <algorithm>
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
  // "what: 42% (12.3 s, about 17.0 s left)", at most every 2 s.
  void Fraction(const std::string& what, double done, double seconds) const {
    if (quiet_ || !(done > 0) || seconds - last_ < 2.0) return;
    last_ = seconds;
    char b[160];
    std::snprintf(b, sizeof b, "%s: %.0f%% (%.1f s, about %.1f s left)", what.c_str(),
                  100 * std::min(done, 1.0), seconds, seconds * (1 - std::min(done, 1.0)) / done);
    Say(b);
  }
  double Elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  bool quiet() const { return quiet_; }

 private:
  using Clock = std::chrono::steady_clock;
  bool quiet_;
  Clock::time_point start_;
  mutable double last_ = 0;
};

}  // namespace meshreuse::cli
