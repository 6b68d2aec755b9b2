// machine.csv: every many-core simulation of the report (mesh x ordering x placement x threads,
// and one thread with the prefetcher), the warm sweep summed over the threads, one row per level
// then memory_local and memory_remote; served = the accesses a level answered (hits; memory: all
// it received), the input of Figure 11 (accesses served by L2, L3 and memory against the cores).
// cycles_low/high: the cost model's cycles of the slowest thread, on every row of a run.
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportMachineData(const ReportData& d) {
  using namespace report;
  if (d.machine.empty()) return {Table({}), "", "", true};
  Table t({"mesh", "ordering", "placement", "threads", "prefetch", "level", "accesses", "served",
           "misses", "coherence", "inclusion_victims", "prefetches", "prefetch_hits",
           "cycles_at_low_latency", "cycles_at_high_latency"});
  for (const MachineRun& r : d.machine) {
    const std::vector<std::string> key = {r.mesh, r.ordering, r.placement, Int(r.threads),
                                          r.prefetch ? "on" : "off"};
    const std::vector<std::string> cycles = {ExactNumber(r.cycles_low), ExactNumber(r.cycles_high)};
    for (size_t i = 0; i < r.total.levels.size(); ++i) {
      const CoreLevelStats& s = r.total.levels[i];
      std::vector<std::string> row = key;
      Append(&row,
             {r.level_names[i], Int(s.accesses), Int(s.accesses - s.misses), Int(s.misses),
              Int(s.coherence), Int(s.inclusion_victims), Int(s.prefetches), Int(s.prefetch_hits)});
      Append(&row, cycles);
      t.AddRow(row);
    }
    for (const auto& [name, n] :
         {std::pair<const char*, uint64_t>{"memory_local", r.total.memory_local},
          {"memory_remote", r.total.memory_remote}}) {
      std::vector<std::string> row = key;
      Append(&row, {name, Int(n), Int(n), "", "", "", "", ""});
      Append(&row, cycles);
      t.AddRow(row);
    }
  }
  return {t, "", "", false};
}

}  // namespace meshreuse
