// reorder_cost: computing and applying each ordering (medians over the rounds after a warm-up,
// with spreads), and both in per-sweep medians of ORI on the same mesh, with intervals (the
// paper's "Discussion on reordering cost": about one sweep for RDR).
#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportReorderCost(const ReportData& d) {
  using namespace report;
  if (!d.cfg.timing) return {Table({}), "", "", true};
  ReportPart p;
  std::vector<std::string> head = {"mesh", "ordering"};
  for (const char* n : {"order_ms", "apply_ms"}) Append(&head, SpreadColumns(n));
  Append(&head, {"apply_first_ms", "ori_sweep_ms"});
  for (const char* n : {"order_sweeps", "apply_sweeps"}) Append(&head, SpreadColumns(n));
  head.push_back("paper_order_sweeps");
  p.table = Table(head);
  for (const ReportMesh& m : d.meshes)
    for (const std::string& ord : d.orderings) {
      const CompareRow* r = d.Time(m.name, ord, 1);
      if (!r) continue;
      const CompareRow* o = d.Time(m.name, "ori", 1);
      std::vector<std::string> row = {m.name, ord};
      Append(&row, SpreadCells(r->order, 1e3));
      Append(&row, SpreadCells(r->apply, 1e3));
      Append(&row, {ExactNumber(1e3 * r->apply_first_seconds),
                    o ? ExactNumber(1e3 * o->sweep.median) : ""});
      for (double CompareRound::*f : {&CompareRound::order, &CompareRound::apply})
        Append(&row,
               SpreadCells(o ? RatioOfMedians(r->Values(f), o->Values(&CompareRound::sweep_wall),
                                              d.cfg.seed + 7)
                             : Spread()));
      row.push_back(ord == "rdr" ? Num(paper::kRdrCostSweeps, 0) : "");
      p.table.AddRow(row);
    }
  p.note =
      "Computing the ordering and applying it (into the reused working copy; the first apply, "
      "into new arrays, apart), medians over the rounds after an untimed warm-up, and both in "
      "per-sweep medians of ORI on the same mesh with their 95% intervals. The paper: RDR costs "
      "about one ORI sweep.";
  return p;
}

}  // namespace meshreuse
