// The report's files from what it measured (report.h): every output of report_list.h written,
// with the manifest of what was; the configuration as run.json holds it; the results README.
// RunReport (report.cc) measures, then calls these.
#pragma once

#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "reports/report_data.h"
#include "reports/run_info.h"

namespace meshreuse::report {

// "L1 32 KiB 8-way, L2 ...".
std::string LevelsText(const std::vector<CacheLevel>& levels);
// run.json's configuration.
Json ConfigurationJson(const ReportConfig& cfg);
// Writes every output of report_list.h this run has into `out`; returns the manifest and appends
// the README's sections to `sections`.
Json WriteOutputs(const ReportData& d, const std::string& out, std::string* sections);
// "Timings taken on a busy machine: ..." naming what it affects, or "" for a quiet one.
std::string BusyNote(const ReportData& d);
// The results README before its breakdown of the time.
std::string Readme(const ReportData& d, const Json& manifest, const std::string& sections);

}  // namespace meshreuse::report
