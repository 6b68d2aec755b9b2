// Progress of a long phase (reading a mesh, writing one, refining), for whoever listens: the
// runners (reports/) set a listener for the calling thread around a phase (PhaseProgress), and the
// core's loops report how far they are (ReportProgress, a clock read: a loop calls it every few
// thousand items or per block), so the core stays free of logging. Without a listener a report
// costs a thread-local load. The listener is called at most every 2 s, and only once the phase
// has lasted 2 s.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace meshreuse {

// (what, done, total, seconds): "reading X", units done of `total` (bytes, vertices, ...; total
// 0 when unknown), seconds since the phase began.
using ProgressListener =
    std::function<void(const std::string& what, uint64_t done, uint64_t total, double seconds)>;

class PhaseProgress {
 public:
  PhaseProgress(std::string what, ProgressListener listener);
  ~PhaseProgress();
  PhaseProgress(const PhaseProgress&) = delete;
  PhaseProgress& operator=(const PhaseProgress&) = delete;

 private:
  PhaseProgress* outer_;

 public:  // for ReportProgress
  std::string what_;
  ProgressListener listener_;
  double start_ = 0, last_ = 0;
};

// How far the current phase is on this thread: `done` units of `total` (0: unknown).
void ReportProgress(uint64_t done, uint64_t total);

}  // namespace meshreuse
