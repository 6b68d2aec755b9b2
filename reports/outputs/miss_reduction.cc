// miss_reduction: per ordering and level, the mean over the meshes of 1 - misses(ordering) /
// misses(reference) against ORI and BFS, from the last traced sweep; the paper's numbers for RDR
// (its text, "Cache Performance") beside ours.
#include <map>

#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportMissReduction(const ReportData& d) {
  using namespace report;
  // [ordering][level] -> per mesh misses, in mesh order
  std::map<std::string, std::map<std::string, std::vector<double>>> per_mesh;
  for (const OrderingValidation& v : d.validation)
    for (size_t i = 0; i < v.levels.size(); ++i) {
      LevelStats s;
      uint64_t line_accesses = 0;
      per_mesh[v.ordering][v.levels[i].level.name].push_back(
          LastSweepMisses(v, i, &s, &line_accesses));
    }
  ReportPart p;
  p.table = Table({"ordering", "level", "source", "fewer_vs_ori_pct", "paper_fewer_vs_ori_pct",
                   "diff_vs_ori_points", "fewer_vs_bfs_pct", "paper_fewer_vs_bfs_pct",
                   "diff_vs_bfs_points"});
  const std::vector<CacheLevel>& levels = d.cfg.cache.levels;
  for (const std::string& ord : d.orderings)
    for (size_t i = 0; i < levels.size(); ++i) {
      const std::string& ln = levels[i].name;
      auto fewer = [&](const std::string& ref) {
        if (!per_mesh.count(ref) || ref == ord) return static_cast<double>(NAN);
        const auto& a = per_mesh[ord][ln];
        const auto& b = per_mesh[ref][ln];
        std::vector<double> r;
        for (size_t k = 0; k < a.size() && k < b.size(); ++k)
          r.push_back(b[k] > 0 ? 100.0 * (1 - a[k] / b[k]) : NAN);
        return Mean(r);
      };
      const bool paper_row = ord == "rdr" && levels.size() == 3;
      const double fo = fewer("ori"), fb = fewer("bfs");
      const double po = paper_row ? paper::kRdrFewerMissesVsOri[i] : NAN;
      const double pb = paper_row ? paper::kRdrFewerMissesVsBfs[i] : NAN;
      if (!std::isfinite(fo) && !std::isfinite(fb)) continue;
      const auto src = d.sources.find(ln);
      p.table.AddRow({ord, ln, src == d.sources.end() ? "" : src->second, Pct(fo), Num(po, 1),
                      Num(fo - po, 1), Pct(fb), Num(pb, 1), Num(fb - pb, 1)});
    }
  p.note =
      "Per level, the mean over meshes of 1 - misses(ordering) / misses(reference), from the "
      "last traced sweep (warm caches). The paper's numbers are for RDR on one core.";
  return p;
}

}  // namespace meshreuse
