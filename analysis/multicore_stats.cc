// The many-core simulator's counts: per level and thread, their sums and differences, the cost
// model's cycles (the paper's equation 2 per thread), the sweeps' marks and the rows of its table
// (multicore_sim.h); multicore_sim.cc simulates the caches, this file reads what it counted.
#include <string>
#include <vector>

#include "analysis/multicore_sim.h"

namespace meshreuse {

CoreLevelStats& CoreLevelStats::operator+=(const CoreLevelStats& o) {
  accesses += o.accesses, misses += o.misses, cold += o.cold, read_misses += o.read_misses;
  write_misses += o.write_misses, coherence += o.coherence;
  inclusion_victims += o.inclusion_victims, prefetches += o.prefetches;
  prefetch_hits += o.prefetch_hits;
  return *this;
}

CoreLevelStats CoreLevelStats::operator-(const CoreLevelStats& o) const {
  CoreLevelStats d;
  d.accesses = accesses - o.accesses, d.misses = misses - o.misses, d.cold = cold - o.cold;
  d.read_misses = read_misses - o.read_misses, d.write_misses = write_misses - o.write_misses;
  d.coherence = coherence - o.coherence;
  d.inclusion_victims = inclusion_victims - o.inclusion_victims;
  d.prefetches = prefetches - o.prefetches, d.prefetch_hits = prefetch_hits - o.prefetch_hits;
  return d;
}

ThreadStats& ThreadStats::operator+=(const ThreadStats& o) {
  if (levels.size() < o.levels.size()) levels.resize(o.levels.size());
  for (size_t i = 0; i < o.levels.size(); ++i) levels[i] += o.levels[i];
  memory_local += o.memory_local, memory_remote += o.memory_remote;
  invalidations_sent += o.invalidations_sent;
  return *this;
}

ThreadStats ThreadStats::operator-(const ThreadStats& o) const {
  ThreadStats d;
  d.levels.resize(levels.size());
  for (size_t i = 0; i < levels.size(); ++i)
    d.levels[i] = i < o.levels.size() ? levels[i] - o.levels[i] : levels[i];
  d.memory_local = memory_local - o.memory_local;
  d.memory_remote = memory_remote - o.memory_remote;
  d.invalidations_sent = invalidations_sent - o.invalidations_sent;
  return d;
}

namespace {
double Cycles(const ThreadStats& s, const Machine& m, bool high) {
  double c = 0;
  for (size_t i = 0; i < s.levels.size() && i < m.levels.size(); ++i) {
    const LatencyRange& l = m.levels[i].cache.latency;
    c += static_cast<double>(s.levels[i].accesses) * (high ? l.high : l.low);
  }
  return c + static_cast<double>(s.memory_local) * m.memory_local +
         static_cast<double>(s.memory_remote) * m.memory_remote;
}
}  // namespace

double ThreadStats::CyclesLow(const Machine& m) const { return Cycles(*this, m, false); }
double ThreadStats::CyclesHigh(const Machine& m) const { return Cycles(*this, m, true); }

void MulticoreSimulation::BeginSweep(int) { marks_.push_back(stats_); }

ThreadStats MulticoreSimulation::SweepStats(int thread, size_t s) const {
  const ThreadStats& start = marks_.at(s)[thread];
  const ThreadStats& end = s + 1 < marks_.size() ? marks_[s + 1][thread] : stats_[thread];
  return end - start;
}

std::vector<std::string> MulticoreSimulation::Columns() {
  return {"input",
          "ordering",
          "machine",
          "placement",
          "threads",
          "thread",
          "core",
          "socket",
          "sweep",
          "level",
          "accesses",
          "hits",
          "misses",
          "cold",
          "coherence",
          "inclusion_victims",
          "prefetches",
          "prefetch_hits",
          "read_misses",
          "write_misses",
          "cycles_at_low_latency",
          "cycles_at_high_latency"};
}

void MulticoreSimulation::AppendRows(Table* t, bool last_sweep_only) const {
  const bool last = last_sweep_only && !marks_.empty();
  for (int th = 0; th < threads(); ++th) {
    const ThreadStats s = last ? SweepStats(th, marks_.size() - 1) : stats_[th];
    const std::vector<std::string> key = {info_.input,
                                          info_.ordering,
                                          m_.name,
                                          PlacementName(placement_),
                                          std::to_string(threads()),
                                          std::to_string(th),
                                          std::to_string(core_of_[th]),
                                          std::to_string(core_of_[th] / m_.cores_per_socket),
                                          last ? std::to_string(marks_.size()) : "all"};
    auto row = [&](const std::string& level, std::vector<std::string> cells) {
      std::vector<std::string> r = key;
      r.push_back(level);
      r.insert(r.end(), cells.begin(), cells.end());
      t->AddRow(r);
    };
    for (size_t i = 0; i < m_.levels.size(); ++i) {
      const CoreLevelStats& l = s.levels[i];
      row(m_.levels[i].cache.name,
          {std::to_string(l.accesses), std::to_string(l.accesses - l.misses),
           std::to_string(l.misses), std::to_string(l.cold), std::to_string(l.coherence),
           std::to_string(l.inclusion_victims), std::to_string(l.prefetches),
           std::to_string(l.prefetch_hits), std::to_string(l.read_misses),
           std::to_string(l.write_misses), "", ""});
    }
    row("memory_local",
        {std::to_string(s.memory_local), "", "", "", "", "", "", "", "", "", "", ""});
    row("memory_remote",
        {std::to_string(s.memory_remote), "", "", "", "", "", "", "", "", "", "", ""});
    row("total", {std::to_string(s.levels.empty() ? 0 : s.levels[0].accesses), "", "", "", "", "",
                  "", "", "", "", ExactNumber(s.CyclesLow(m_)), ExactNumber(s.CyclesHigh(m_))});
  }
}

}  // namespace meshreuse
