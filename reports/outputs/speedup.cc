// speedup: the mean over the meshes of the one-thread speedup against ORI and BFS (per-sweep
// medians), with its interval (every mesh's rounds resampled) and verdict, the paper's RDR values
// (its text, "Serial execution") beside ours; _min/_max are the lowest and highest mesh.
#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportSpeedup(const ReportData& d) {
  using namespace report;
  if (!d.cfg.timing) return {Table({}), "", "", true};
  ReportPart p;
  std::vector<std::string> head = {"ordering", "meshes"};
  for (const char* ref : {"ori", "bfs"}) {
    const std::string n = std::string("speedup_vs_") + ref;
    Append(&head, SpreadColumns(n));
    Append(&head, {n + "_verdict", "paper_" + n, "diff_vs_" + std::string(ref)});
  }
  p.table = Table(head);
  for (const std::string& ord : d.orderings) {
    std::vector<std::string> row = {ord, ""};
    int meshes = 0;
    for (const char* ref : {"ori", "bfs"}) {
      std::vector<std::pair<const CompareRow*, const CompareRow*>> pairs;
      meshes = 0;
      for (const ReportMesh& m : d.meshes)
        if (const CompareRow* r = d.Time(m.name, ord, 1)) {
          pairs.emplace_back(d.Time(m.name, ref, 1), r);
          ++meshes;
        }
      const Spread s = MeanRatio(pairs, d.cfg.seed, false, d.cfg.clock);
      const double paper = ord == "rdr" ? (std::string(ref) == "ori" ? paper::kRdrSpeedupVsOri
                                                                     : paper::kRdrSpeedupVsBfs)
                                        : NAN;
      Append(&row, SpreadCells(s));
      Append(&row, {VerdictCell(s), Num(paper, 2), Num(s.median - paper, 3)});
    }
    row[1] = Int(meshes);
    p.table.AddRow(row);
  }
  p.note =
      "The mean over meshes of T_ref(1) / T_ord(1) on per-sweep medians (" +
      std::string(ClockName(d.cfg.clock)) +
      " clock), with its 95% interval "
      "(each mesh's rounds resampled) and its lowest and highest mesh. The paper: RDR 1.39x over "
      "ORI, 1.19x over BFS, on its nine meshes (times to convergence).";
  return p;
}

}  // namespace meshreuse
