// Hardware counters through PAPI (analysis of the paper's Figure 7 and Table 3): cache misses,
// cycles and instructions around the timed sweeps, one event set per OpenMP thread
// (PAPI_thread_init), kept per thread and summed.
// Availability is decided by doing, not by asking: each requested event is added to an event set,
// started and stopped once; the ones that survive are counted, the others are dropped with PAPI's
// reason. On a virtual machine PAPI initialises but every preset is unavailable: then available()
// is false, reason() says why in one line (PAPI's own words), and callers carry on with the
// simulator, labelling its numbers "simulated". Software events (perf::TASK-CLOCK) count
// everywhere perf_event does, which lets tests exercise the whole path on such machines.
// Built without PAPI (no libpapi-dev), every instance is unavailable with that reason.
// Usage: construct before the parallel work, pass as SmoothOptions::region (it is a SweepRegion:
// each thread starts its own event set on Enter and stops and accumulates it on Exit).
#pragma once

#include <string>
#include <vector>

#include "core/access.h"

namespace meshreuse {

// The presets the validation asks for, in this order: L1 data misses, L2 data misses, L3 total
// misses (the Westmere-EX events the paper used), then cycles and instructions.
std::vector<std::string> DefaultCounterEvents();

class PapiCounters : public SweepRegion {
 public:
  // Probes `events`; threads: the most OpenMP threads that will call Enter/Exit.
  PapiCounters(const std::vector<std::string>& events, int threads);
  ~PapiCounters() override;
  PapiCounters(const PapiCounters&) = delete;
  PapiCounters& operator=(const PapiCounters&) = delete;

  bool available() const { return !events_.empty(); }
  const std::string& reason() const { return reason_; }               // why events were dropped
  const std::vector<std::string>& events() const { return events_; }  // those that count
  const std::vector<std::string>& dropped() const { return dropped_; }

  void Enter(int thread) override;
  void Exit(int thread) override;

  // Accumulated values: [thread][event], and summed over threads.
  const std::vector<std::vector<long long>>& per_thread() const { return values_; }
  std::vector<long long> Sum() const;
  // An error in a thread's start or stop (PAPI's message), empty if none.
  const std::string& error() const { return error_; }
  // "PAPI 7.0.0.0", or why there is none.
  static std::string Version();

 private:
  std::vector<std::string> events_, dropped_;
  std::string reason_, error_;
  std::vector<int> sets_;  // per thread, PAPI_NULL until the thread's first Enter
  std::vector<std::vector<long long>> values_;
};

// Where PAPI stands for these events, probed once: whether any counts, and why some do not (empty
// when all count, or when no event is asked for).
struct CounterNote {
  bool available = false;
  std::string note;
};
CounterNote ProbeCounters(const std::vector<std::string>& events, int threads = 1);

}  // namespace meshreuse
