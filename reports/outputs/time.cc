// time: the time to convergence on one thread per mesh and ordering (the data of the paper's
// Figure 8), the per-sweep time on both clocks, each with its spread over the rounds, and the
// per-sweep speedups against ORI and BFS with their intervals and verdicts.
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportTime(const ReportData& d) {
  using namespace report;
  if (!d.cfg.timing) return {Table({}), "", "", true};
  ReportPart p;
  std::vector<std::string> head = {"mesh", "ordering", "rounds", "sweeps"};
  for (const char* n : {"total_s", "sweep_ms", "sweep_cpu_ms"}) Append(&head, SpreadColumns(n));
  for (const char* n : {"speedup_vs_ori", "speedup_vs_bfs"}) {
    Append(&head, SpreadColumns(n));
    head.push_back(std::string(n) + "_verdict");
  }
  p.table = Table(head);
  for (const ReportMesh& m : d.meshes)
    for (const std::string& ord : d.orderings) {
      const CompareRow* r = d.Time(m.name, ord, 1);
      if (!r) continue;
      std::vector<std::string> row = {m.name, ord, Int(r->rounds.size()),
                                      Int(r->rounds.empty() ? 0 : r->rounds[0].sweeps)};
      Append(&row, SpreadCells(r->total));
      Append(&row, SpreadCells(r->sweep, 1e3));
      Append(&row, SpreadCells(r->sweep_cpu, 1e3));
      for (const char* ref : {"ori", "bfs"}) {
        const Spread s = Speedup(d.Time(m.name, ref, 1), r, d.cfg.seed, d.cfg.clock);
        Append(&row, SpreadCells(s));
        row.push_back(VerdictCell(s));
      }
      p.table.AddRow(row);
    }
  p.note =
      "Medians over interleaved rounds (after an untimed warm-up) of the time to convergence "
      "(tol " +
      ExactNumber(d.cfg.smooth.tol) +
      ") and of the per-sweep time, wall and "
      "thread CPU, one thread; `_min`/`_max` the rounds' extremes, `_lo`/`_hi` the 95% "
      "interval of the median. Speedups are ratios of per-sweep medians (" +
      ClockName(d.cfg.clock) +
      " clock) within each mesh, "
      "with their intervals; a verdict is *not distinguishable* when the interval holds 1.";
  return p;
}

}  // namespace meshreuse
