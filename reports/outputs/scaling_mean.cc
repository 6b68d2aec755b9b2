// scaling_mean: the mean over the meshes of Speedup(p) and Gain(p) per ordering and thread count,
// with intervals (every mesh's rounds resampled) and verdicts, the paper's gain ranges for RDR
// (1-32 cores) beside ours.
#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportScalingMean(const ReportData& d) {
  using namespace report;
  if (!d.cfg.timing) return {Table({}), "", "", true};
  ReportPart p;
  std::vector<std::string> head = {"ordering", "threads"};
  Append(&head, SpreadColumns("mean_speedup"));
  head.push_back("mean_speedup_verdict");
  for (const char* ref : {"ori", "bfs"}) {
    const std::string n = std::string("mean_gain_vs_") + ref + "_pct";
    Append(&head, SpreadColumns(n));
    Append(&head, {n + "_verdict", std::string("paper_gain_vs_") + ref + "_pct_low",
                   std::string("paper_gain_vs_") + ref + "_pct_high"});
  }
  p.table = Table(head);
  for (const std::string& ord : d.orderings)
    for (int th : d.cfg.threads) {
      auto pairs = [&](const std::string& ref, int ref_p) {
        std::vector<std::pair<const CompareRow*, const CompareRow*>> v;
        for (const ReportMesh& m : d.meshes)
          if (const CompareRow* r = d.Time(m.name, ord, th))
            v.emplace_back(d.Time(m.name, ref, ref_p), r);
        return v;
      };
      std::vector<std::string> row = {ord, Int(th)};
      const Spread s = MeanRatio(pairs("ori", 1), d.cfg.seed, false, d.cfg.clock);
      Append(&row, SpreadCells(s));
      row.push_back(VerdictCell(s));
      const bool rdr = ord == "rdr";
      for (const char* ref : {"ori", "bfs"}) {
        const Spread g = MeanRatio(pairs(ref, th), d.cfg.seed, true, d.cfg.clock);
        const auto& range = std::string(ref) == "ori" ? paper::kRdrGainVsOri : paper::kRdrGainVsBfs;
        Append(&row, SpreadCells(g, 100));
        Append(&row,
               {VerdictCell(g, true), rdr ? Num(range[0], 0) : "", rdr ? Num(range[1], 0) : ""});
      }
      p.table.AddRow(row);
    }
  p.note =
      "Speedup(p) = T_ori(1) / T_ord(p); Gain(p) = (T_ref(p) - T_ord(p)) / T_ref(p), on per-sweep "
      "medians (" +
      std::string(ClockName(d.cfg.clock)) +
      " clock), means over the meshes with 95% intervals. The paper gives its gains as ranges over "
      "1-32 cores (RDR: 20-30% over ORI, 10-30% over BFS). Per mesh: "
      "[tables/scaling.md](tables/scaling.md).";
  return p;
}

}  // namespace meshreuse
