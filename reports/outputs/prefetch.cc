// prefetch: how much a next-line prefetcher changes the one-thread misses, and how much of the gap
// between our simulated misses and the paper's measured ones (its Table 3, PAPI counters on the
// Westmere-EX, whose L1 and L2 prefetch) it explains: per mesh x ordering x level, the warm
// sweep's misses without and with the prefetcher (thousands), the prefetch hits (misses it hid),
// the paper's measurement where the mesh has the paper's size, and explained = (without - with)
// / (without - paper) when ours are above the paper's.
#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportPrefetch(const ReportData& d) {
  using namespace report;
  if (d.machine.empty() || d.cfg.prefetch_levels.empty()) return {Table({}), "", "", true};
  Table t({"mesh", "ordering", "level", "misses_k", "prefetch_misses_k", "fewer_pct",
           "prefetch_hits_k", "paper_misses_k", "explained_pct"});
  std::vector<double> explained;
  for (const ReportMesh& m : d.meshes)
    for (const std::string& ord : d.orderings) {
      const MachineRun* off = d.Machine(m.name, ord, "compact", 1, false);
      const MachineRun* on = d.Machine(m.name, ord, "compact", 1, true);
      if (!off || !on) continue;
      const auto paper =
          paper::Sized(m.name, m.vertices) ? paper::Table3(m.name, ord) : std::nullopt;
      for (size_t i = 0; i < off->total.levels.size() && i < on->total.levels.size(); ++i) {
        const double a = static_cast<double>(off->total.levels[i].misses) / 1e3;
        const double b = static_cast<double>(on->total.levels[i].misses) / 1e3;
        const double hits = static_cast<double>(on->total.levels[i].prefetch_hits) / 1e3;
        const double pm = paper && off->total.levels.size() == 3 ? (*paper)[i] : NAN;
        const double ex = std::isfinite(pm) && a > pm ? 100 * (a - b) / (a - pm) : NAN;
        if (std::isfinite(ex)) explained.push_back(ex);
        t.AddRow({m.name, ord, off->level_names[i], Num(a, 1), Num(b, 1),
                  Pct(100 * (1 - Ratio(b, a))), Num(hits, 1), Num(pm, 1), Pct(ex)});
      }
    }
  ReportPart part;
  part.table = t;
  part.note =
      "One thread on `" + d.cfg.machine +
      "`, the warm sweep without and with a next-line "
      "prefetcher at " +
      d.cfg.prefetch_levels +
      " (a demand miss of line L brings L+1 into that level and those below it). The paper's "
      "misses are its PAPI "
      "measurements (Table 3), on a machine whose L1 and L2 prefetch; explained: the share of our "
      "excess over them that the prefetcher removes (mean " +
      (explained.empty() ? std::string("-") : Pct(Mean(explained)) + "%") + " over " +
      std::to_string(explained.size()) + " mesh x ordering x level cells).";
  return part;
}

}  // namespace meshreuse
