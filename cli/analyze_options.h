// analyze's options (cli/cmd_analyze.cc, and the Python module through cli/configs.h): their
// declaration, the configuration they give and its defaults and checks, in one place.
#pragma once

#include <string>

#include "cli/common.h"
#include "cli/configs.h"

namespace meshreuse::cli {

// The options only analyze has (the stream source's are common.h's), as given.
struct AnalyzeOptionText {
  SourceOptionText source;
  std::string granularity, quantiles = "50,75,90,100", cache = "westmere-ex", hist_csv, prof_csv,
                           mrc_csv, out_dir, measured, sample_size, sample_exact_below,
                           element_bytes = "66", line_bytes = "64", chunk, rank_stats,
                           scatter_from = "16";
  double sample_rate = 0;
};

// Parses `args` into cfg, t and vm: false when --help was printed. The source is pointed at what
// is in memory before the defaults that depend on it and the checks.
bool ParseAnalyze(const Args& args, Communicator* transport, const InMemory& in_memory,
                  AnalyzeConfig* cfg, AnalyzeOptionText* t, po::variables_map* vm);

}  // namespace meshreuse::cli
