// The report's outputs as data: report_list.h expanded into one table of tables and data files
// (each with its builder) and one of figures (each with its plotting script and inputs). RunReport
// loops over them; nothing else lists what a report holds.
#pragma once

#include <string>
#include <vector>

#include "core/table.h"
#include "reports/report_data.h"

namespace meshreuse {

// What a builder returns: a table (or, for a JSON file, its text), and the README's paragraph
// above it. skip: nothing to write in this run (no timing, the figure's mesh absent).
struct ReportPart {
  Table table{{}};
  std::string text;
  std::string note;
  bool skip = false;
};
using ReportBuilder = ReportPart (*)(const ReportData&);

struct ReportOutput {
  bool is_table;  // tables/NAME.{csv,md,tex} + a README section; else data/NAME
  const char* name;
  ReportBuilder build;
  const char* paper;    // the paper's table or figure it stands beside ("" for data files)
  const char* title;    // README section title ("" for none)
  const char* caption;  // LaTeX caption
};

struct ReportFigure {
  const char* name;
  const char* paper;
  const char* script;  // in scripts/
  const char* inputs;  // space-separated paths in the report folder
  const char* when;    // "" or "scale"
  const char* title;
};

const std::vector<ReportOutput>& ReportOutputs();
const std::vector<ReportFigure>& ReportFigures();

}  // namespace meshreuse
