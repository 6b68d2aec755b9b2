// histogram.csv, profile.csv and capacities.csv: the first sweep's histograms and the profile in
// the analysis' own schemas (the same as `analyze --histogram-csv` and `--profile-csv`, one
// plotting script each), and the cache levels' capacities in elements and lines; meshes.csv,
// smoothing.csv and order_positions.csv: the pictures of reports/pictures.h.
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportHistogramData(const ReportData& d) { return {d.histogram, "", "", false}; }

ReportPart ReportProfileData(const ReportData& d) {
  return {d.profile, "", "", d.profile.Rows() == 0};
}

ReportPart ReportMeshDrawing(const ReportData& d) { return {d.drawing, "", "", false}; }
ReportPart ReportSmoothingWindow(const ReportData& d) {
  return {d.smoothing, "", "", d.smoothing.Rows() == 0};
}
ReportPart ReportOrderPositions(const ReportData& d) {
  return {d.positions, "", "", d.positions.Rows() == 0};
}

ReportPart ReportCapacitiesData(const ReportData& d) {
  using namespace report;
  ReportPart p;
  p.table = Table({"level", "bytes", "ways", "elements", "lines"});
  for (const CacheLevel& l : d.cfg.cache.levels)
    p.table.AddRow({l.name, Int(l.bytes), Int(l.ways), Int(l.bytes / d.cfg.element_bytes),
                    Int(l.bytes / d.cfg.line_bytes)});
  return p;
}

ReportPart ReportCompareJson(const ReportData& d) {
  if (!d.cfg.timing) return {Table({}), "", "", true};
  ReportPart p;
  p.text = Json{{"rows", CompareJson(d.timing)}}.dump(2) + "\n";
  return p;
}

}  // namespace meshreuse
