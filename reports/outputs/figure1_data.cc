// figure1.csv and figure1_summary.csv: the paper's Figure 1 (one mesh, random / ORI / BFS): every
// access of the first sweep binned in time x quarter-octave distance (cold accesses apart), and
// each panel's caption numbers (average distance, modelled L1 miss rate, time) beside the paper's.
#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportFigure1Data(const ReportData& d) {
  using namespace report;
  if (d.fig1.empty()) return {Table({}), "", "", true};
  ReportPart p;
  p.table = Table({"ordering", "time_bin", "distance_lo", "distance_hi", "count"});
  for (const Figure1Data& f : d.fig1) {
    const int db = f.bins.empty() ? 0 : static_cast<int>(f.bins[0].size());
    for (size_t t = 0; t < f.bins.size(); ++t)
      for (int b = 0; b < db; ++b)
        if (f.bins[t][b]) {
          const bool cold = b == db - 1;
          p.table.AddRow({f.ordering, Int(t), cold ? "cold" : Int(DistanceBinLo(b)),
                          cold ? "cold" : Int(DistanceBinLo(b + 1) - 1), Int(f.bins[t][b])});
        }
  }
  return p;
}

ReportPart ReportFigure1Summary(const ReportData& d) {
  using namespace report;
  if (d.fig1.empty()) return {Table({}), "", "", true};
  ReportPart p;
  p.table = Table({"ordering", "accesses", "cold", "mean_distance", "model_l1_miss_rate_pct",
                   "seconds", "paper_mean_distance", "paper_l1_miss_rate_pct", "paper_seconds"});
  for (const Figure1Data& f : d.fig1) {
    const CompareRow* r = d.Time(d.cfg.figure1_mesh, f.ordering, 1);
    const auto pf = paper::Figure1(f.ordering);
    p.table.AddRow({f.ordering, Int(f.accesses), Int(f.cold), ExactNumber(f.mean),
                    Num(100 * f.model_l1_rate, 3), r ? ExactNumber(r->total.median) : "",
                    pf ? ExactNumber(pf->mean_distance) : "",
                    pf ? ExactNumber(pf->l1_miss_percent) : "",
                    pf ? ExactNumber(pf->seconds) : ""});
  }
  return p;
}

}  // namespace meshreuse
