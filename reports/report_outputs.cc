// The report's registry: report_list.h expanded to declare the builders and build the two tables.
#include "reports/report_outputs.h"

namespace meshreuse {

#define MESHREUSE_REPORT_TABLE(fn, ...) ReportPart fn(const ReportData&);
#define MESHREUSE_REPORT_DATA(fn, ...) ReportPart fn(const ReportData&);
#define MESHREUSE_REPORT_FIGURE(...)
#include "reports/report_list.h"
#undef MESHREUSE_REPORT_TABLE
#undef MESHREUSE_REPORT_DATA
#undef MESHREUSE_REPORT_FIGURE

const std::vector<ReportOutput>& ReportOutputs() {
  static const std::vector<ReportOutput> kOutputs = {
#define MESHREUSE_REPORT_TABLE(fn, name, paper, title, caption) \
  {true, name, fn, paper, title, caption},
#define MESHREUSE_REPORT_DATA(fn, file) {false, file, fn, "", "", ""},
#define MESHREUSE_REPORT_FIGURE(...)
#include "reports/report_list.h"
#undef MESHREUSE_REPORT_TABLE
#undef MESHREUSE_REPORT_DATA
#undef MESHREUSE_REPORT_FIGURE
  };
  return kOutputs;
}

const std::vector<ReportFigure>& ReportFigures() {
  static const std::vector<ReportFigure> kFigures = {
#define MESHREUSE_REPORT_TABLE(...)
#define MESHREUSE_REPORT_DATA(...)
#define MESHREUSE_REPORT_FIGURE(name, paper, script, inputs, when, title) \
  {name, paper, script, inputs, when, title},
#include "reports/report_list.h"
#undef MESHREUSE_REPORT_TABLE
#undef MESHREUSE_REPORT_DATA
#undef MESHREUSE_REPORT_FIGURE
  };
  return kFigures;
}

}  // namespace meshreuse
