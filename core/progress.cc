// Phase progress; see progress.h.
#include "core/progress.h"

#include <chrono>
#include <utility>

namespace meshreuse {

namespace {

thread_local PhaseProgress* g_phase = nullptr;

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

PhaseProgress::PhaseProgress(std::string what, ProgressListener listener)
    : outer_(g_phase), what_(std::move(what)), listener_(std::move(listener)) {
  start_ = last_ = Now();
  g_phase = listener_ ? this : outer_;
}

PhaseProgress::~PhaseProgress() {
  if (g_phase == this) g_phase = outer_;
}

void ReportProgress(uint64_t done, uint64_t total) {
  PhaseProgress* p = g_phase;
  if (!p) return;
  const double now = Now();
  if (now - p->last_ < 2.0) return;
  p->last_ = now;
  p->listener_(p->what_, done, total, now - p->start_);
}

}  // namespace meshreuse
