// scaling: Speedup(p) = T_ori(1) / T_ord(p) and Gain(p) against ORI and BFS per mesh, ordering and
// thread count (the data of the paper's Figures 10, 12 and 13), on per-sweep medians (wall), each
// with its interval and verdict.
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportScaling(const ReportData& d) {
  using namespace report;
  if (!d.cfg.timing) return {Table({}), "", "", true};
  ReportPart p;
  std::vector<std::string> head = {"mesh", "ordering", "threads"};
  Append(&head, SpreadColumns("sweep_ms"));
  Append(&head, SpreadColumns("speedup"));
  head.push_back("speedup_verdict");
  for (const char* n : {"gain_vs_ori_pct", "gain_vs_bfs_pct"}) {
    Append(&head, SpreadColumns(n));
    head.push_back(std::string(n) + "_verdict");
  }
  p.table = Table(head);
  for (const std::string& ord : d.orderings)
    for (int th : d.cfg.threads)
      for (const ReportMesh& m : d.meshes) {
        const CompareRow* r = d.Time(m.name, ord, th);
        if (!r) continue;
        std::vector<std::string> row = {m.name, ord, Int(th)};
        Append(&row, SpreadCells(r->sweep, 1e3));
        const Spread s = Speedup(d.Time(m.name, "ori", 1), r, d.cfg.seed, d.cfg.clock);
        Append(&row, SpreadCells(s));
        row.push_back(VerdictCell(s));
        for (const char* ref : {"ori", "bfs"}) {
          const Spread g = Gain(d.Time(m.name, ref, th), r, d.cfg.seed, d.cfg.clock);
          Append(&row, SpreadCells(g, 100));
          row.push_back(VerdictCell(g, true));
        }
        p.table.AddRow(row);
      }
  return p;
}

}  // namespace meshreuse
