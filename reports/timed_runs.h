// What a timed run of the smoother is and how it is timed, shared by `compare` (compare.h), the
// speedups computed on its rows (speedup.h) and the report (report.h): the timing options (thread
// counts, rounds, the clock the ratios use, the smoother's options) and the rows (each mesh x
// ordering x threads with its rounds).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/permutation.h"
#include "core/smoother.h"
#include "reports/run_info.h"
#include "reports/timing.h"

namespace meshreuse {

// The clock that Speedup and Gain are computed on: wall time (what a user waits for; the right one
// for scaling, on a quiet machine) or the thread CPU time of the sweeps summed over threads (the
// work an ordering costs, steadier where other work shares the cores).
enum class TimeClock { kWall, kCpu };
const char* ClockName(TimeClock c);          // "wall", "cpu"
TimeClock ParseClock(const std::string& s);  // throws UsageError

// How the smoother is timed: on each thread count, `repeat` rounds after an untimed warm-up (or,
// with repeat_auto, rounds until every speedup is within +-2%, at most repeat_cap).
struct TimingOptions {
  std::vector<int> threads = {1};
  int repeat = 5;  // rounds, at least 3
  bool repeat_auto = false;
  int repeat_cap = 15;
  // The untimed warm-up: each (ordering, threads) computed, applied and smoothed this many sweeps
  // (at most max_iters) before the first timed round. A run applies its layout afresh and its
  // threads start anew, so what a warm-up leaves behind is the process's state (the working
  // arrays' pages, the thread pool, the code in the caches), which a few sweeps give as a whole
  // run does: measured in reports/docs/timings.md (a timed round first after 2 sweeps is no
  // slower than the rounds after it).
  int warmup_sweeps = 2;
  // Throws UsageError for a warm-up outside 1..1000 sweeps (compare and the report, before any
  // work).
  void CheckWarmup() const;
  TimeClock clock = TimeClock::kWall;  // of the speedups and gains
  SmoothOptions smooth;                // tol, max_iters, mode; threads are taken from `threads`
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  // threads, repeat, repeat_cap, clock, mode, quality, tol, max_iters, triangle_order: run.json's.
  void AddJson(Json* j) const;
};

struct CompareRound {
  int sweeps = 0;
  double total_wall = 0, total_cpu = 0;  // all sweeps of the run
  double sweep_wall = 0, sweep_cpu = 0;  // medians over the run's sweeps
  double order = 0, apply = 0;           // computing the ordering, applying it to the working copy
};

struct CompareRow {
  std::string mesh, ordering;  // ordering: its label
  int threads = 1;
  int32_t vertices = 0, triangles = 0;
  double apply_first_seconds = 0;  // the first apply, into new arrays (page faults included)
  EdgeSpan span;                   // locality of the ordering (permutation.h)
  std::vector<CompareRound> rounds;
  double final_quality = 0;  // of the first round
  // Over the rounds: seconds. `sweep` is the per-sweep median (wall), `sweep_cpu` its thread CPU
  // time (summed over the threads), `total` the time to convergence.
  Spread order, apply, total, sweep, sweep_cpu;
  double cpu_per_wall = NAN;  // median over rounds of CPU / (wall x threads) of the sweeps
  double cv = NAN;            // coefficient of variation of the rounds' per-sweep medians (wall)
  Spread speedup_vs_ori1;     // T_ori(1) / T (per-sweep medians, wall); NaN without ori at 1
  Spread gain_vs_bfs;         // (T_bfs - T) / T_bfs at the same threads; NaN without bfs
  // Counters (CompareConfig::counter_events that count here): per event, the sum over threads
  // and sweeps of each round, and its median over the rounds.
  std::vector<std::string> counter_events;
  std::vector<std::vector<long long>> counters;  // [round][event]
  std::vector<double> counter_medians;           // [event]
  // The rounds' values of one kind, in round order.
  std::vector<double> Values(double CompareRound::*field) const;
};

}  // namespace meshreuse
