// misses: the last traced sweep's accesses, misses, cold misses and local and global miss rates
// per mesh, ordering and level (the data of the paper's Figure 9), as a table and as
// data/misses.csv for the miss-rate and scale figures.
#include "reports/report_outputs.h"

namespace meshreuse {

namespace {
Table MissesTable(const ReportData& d) {
  using namespace report;
  Table t({"mesh", "ordering", "level", "source", "accesses", "misses", "cold", "local_miss_rate",
           "global_miss_rate"});
  for (const OrderingValidation& v : d.validation)
    for (size_t i = 0; i < v.levels.size(); ++i) {
      const LevelValidation& l = v.levels[i];
      LevelStats s;
      uint64_t line_accesses = 0;
      const double m = LastSweepMisses(v, i, &s, &line_accesses);
      t.AddRow({v.mesh, v.ordering, l.level.name, l.measured ? "measured" : "simulated",
                Int(s.accesses), ExactNumber(m), l.measured ? "" : Int(s.cold),
                ExactNumber(Ratio(m, static_cast<double>(s.accesses))),
                ExactNumber(Ratio(m, static_cast<double>(line_accesses)))});
    }
  return t;
}
}  // namespace

ReportPart ReportMisses(const ReportData& d) { return {MissesTable(d), "", "", false}; }
ReportPart ReportMissesData(const ReportData& d) { return {MissesTable(d), "", "", false}; }

}  // namespace meshreuse
