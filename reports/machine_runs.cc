// Many-core simulation runs summarised; see machine_runs.h.
#include "reports/machine_runs.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "reports/report_data.h"

namespace meshreuse {

using report::Int;
using report::Num;
using report::Pct;
using report::Ratio;

MachineRun CollectMachineRun(const MulticoreSimulation& sim, const std::string& mesh,
                             const std::string& ordering, bool prefetch) {
  MachineRun r;
  r.mesh = mesh, r.ordering = ordering, r.prefetch = prefetch;
  r.placement = PlacementName(sim.placement());
  r.threads = sim.threads();
  for (const MachineLevel& l : sim.machine().levels) r.level_names.push_back(l.cache.name);
  for (int t = 0; t < sim.threads(); ++t) {
    const ThreadStats s = sim.sweeps() ? sim.SweepStats(t, sim.sweeps() - 1) : sim.Stats(t);
    r.total += s;
    r.cycles_low = std::max(r.cycles_low, s.CyclesLow(sim.machine()));
    r.cycles_high = std::max(r.cycles_high, s.CyclesHigh(sim.machine()));
  }
  return r;
}

const MachineRun* FindMachineRun(const std::vector<MachineRun>& runs, const std::string& mesh,
                                 const std::string& ordering, const std::string& placement,
                                 int threads, bool prefetch) {
  for (const MachineRun& r : runs)
    if (r.mesh == mesh && r.ordering == ordering && r.threads == threads &&
        r.prefetch == prefetch && (r.placement == placement || r.threads == 1))
      return &r;
  return nullptr;
}

namespace {

double Cycles(const MachineRun* r, int high) {
  return r == nullptr ? NAN : high ? r->cycles_high : r->cycles_low;
}

}  // namespace

PredictedRatios Predict(const std::vector<MachineRun>& runs, const std::string& mesh,
                        const std::string& ordering, const std::string& placement, int threads) {
  PredictedRatios p;
  const MachineRun* r = FindMachineRun(runs, mesh, ordering, placement, threads);
  for (int h = 0; h < 2; ++h) {
    const double c = Cycles(r, h);
    p.speedup[h] = Ratio(Cycles(FindMachineRun(runs, mesh, "ori", placement, 1), h), c);
    p.self_speedup[h] = Ratio(Cycles(FindMachineRun(runs, mesh, ordering, placement, 1), h), c);
    p.gain_vs_ori_pct[h] =
        ordering == "ori"
            ? NAN
            : 100 *
                  (1 - Ratio(c, Cycles(FindMachineRun(runs, mesh, "ori", placement, threads), h)));
    p.gain_vs_bfs_pct[h] =
        ordering == "bfs"
            ? NAN
            : 100 *
                  (1 - Ratio(c, Cycles(FindMachineRun(runs, mesh, "bfs", placement, threads), h)));
  }
  return p;
}

Table MachineSummaryTable(const std::vector<MachineRun>& runs) {
  std::vector<std::string> head = {"input",
                                   "ordering",
                                   "placement",
                                   "threads",
                                   "cycles_at_low_latency",
                                   "cycles_at_high_latency",
                                   "speedup_at_low_latency",
                                   "speedup_at_high_latency",
                                   "self_speedup_at_low_latency",
                                   "self_speedup_at_high_latency",
                                   "gain_vs_ori_pct_at_low_latency",
                                   "gain_vs_ori_pct_at_high_latency",
                                   "gain_vs_bfs_pct_at_low_latency",
                                   "gain_vs_bfs_pct_at_high_latency"};
  const std::vector<std::string> levels =
      runs.empty() ? std::vector<std::string>{} : runs[0].level_names;
  for (const std::string& l : levels) head.push_back(l + "_misses");
  for (const char* c : {"memory_accesses", "remote_pct", "coherence_misses", "coherence_pct"})
    head.push_back(c);
  Table t(head);
  for (const MachineRun& r : runs) {
    if (r.prefetch) continue;
    const PredictedRatios p = Predict(runs, r.mesh, r.ordering, r.placement, r.threads);
    std::vector<std::string> row = {r.mesh,
                                    r.ordering,
                                    r.placement,
                                    Int(r.threads),
                                    Num(r.cycles_low, 0),
                                    Num(r.cycles_high, 0),
                                    Num(p.speedup[0], 2),
                                    Num(p.speedup[1], 2),
                                    Num(p.self_speedup[0], 2),
                                    Num(p.self_speedup[1], 2),
                                    Pct(p.gain_vs_ori_pct[0]),
                                    Pct(p.gain_vs_ori_pct[1]),
                                    Pct(p.gain_vs_bfs_pct[0]),
                                    Pct(p.gain_vs_bfs_pct[1])};
    uint64_t coherence = 0;
    for (const CoreLevelStats& l : r.total.levels) row.push_back(Int(l.misses));
    if (!r.total.levels.empty()) coherence = r.total.levels[0].coherence;
    const uint64_t memory = r.total.memory_local + r.total.memory_remote;
    row.push_back(Int(memory));
    row.push_back(
        Pct(100 * Ratio(static_cast<double>(r.total.memory_remote), static_cast<double>(memory))));
    row.push_back(Int(coherence));
    row.push_back(Pct(
        100 * Ratio(static_cast<double>(coherence),
                    r.total.levels.empty() ? 0 : static_cast<double>(r.total.levels[0].misses))));
    t.AddRow(row);
  }
  return t;
}

std::vector<std::string> MachineSentences(const std::vector<MachineRun>& runs) {
  std::vector<std::string> out;
  int top = 0;
  for (const MachineRun& r : runs) top = std::max(top, r.threads);
  for (const MachineRun& r : runs) {
    if (r.prefetch || r.threads != top) continue;
    const std::string ref = r.ordering == "bfs" ? "ori" : "bfs";
    const MachineRun* b = FindMachineRun(runs, r.mesh, ref, r.placement, r.threads);
    const PredictedRatios p = Predict(runs, r.mesh, r.ordering, r.placement, r.threads);
    std::string s = (r.ordering.empty() ? "the trace" : r.ordering) + " at " + Int(r.threads) +
                    " thread(s), " + r.placement + " (" + r.mesh + "): ";
    if (std::isfinite(p.speedup[0]))
      s += "Speedup " + Num(p.speedup[0], 1) + "-" + Num(p.speedup[1], 1) + "; ";
    else
      s += "no Speedup (it needs ori at 1 thread: --orderings ori,... --threads 1,...); ";
    if (!b || b->total.levels.empty() || r.total.levels.empty()) {
      s += "no " + ref + " run at " + Int(r.threads) + " thread(s) to compare it with";
      out.push_back(s);
      continue;
    }
    const double gain = ref == "bfs" ? p.gain_vs_bfs_pct[0] : p.gain_vs_ori_pct[0];
    s += "gain vs " + ref + " " + Pct(gain) + "% (low latency). Against " + ref + "'s: ";
    // The three drivers the cost model sees, each as this ordering's count against ref's.
    const size_t last = r.total.levels.size() - 1;
    const double mine[3] = {static_cast<double>(r.total.levels[0].coherence),
                            static_cast<double>(r.total.levels[last].misses),
                            static_cast<double>(r.total.memory_remote)};
    const double theirs[3] = {static_cast<double>(b->total.levels[0].coherence),
                              static_cast<double>(b->total.levels[last].misses),
                              static_cast<double>(b->total.memory_remote)};
    const char* what[3] = {"coherence misses", "last-level misses", "remote memory accesses"};
    int driver = 0;
    double most = 0;
    for (int k = 0; k < 3; ++k) {
      s += std::string(k ? ", " : "") + what[k] + " " + Grouped(static_cast<long long>(mine[k])) +
           " vs " + Grouped(static_cast<long long>(theirs[k]));
      const double change = std::fabs(mine[k] - theirs[k]);
      if (change > most) most = change, driver = k;
    }
    s += most > 0 ? std::string("; the largest difference: ") + what[driver] : "; no difference";
    out.push_back(s);
  }
  return out;
}

}  // namespace meshreuse
