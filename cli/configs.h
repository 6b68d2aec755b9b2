// The configurations three commands build from their options, for a caller other than the command
// itself (the Python module, cli/python/): the same parsing, defaults and checks, so a keyword of
// the module means what the option means and is refused with the same message. `in_memory`, when
// set, is called once the stream source is read and before the checks: it points the source at a
// mesh or ids already in memory (StreamSource::loaded, ids). --help, output options and the
// format flags are the command's own business; here they are refused (UsageError).
#pragma once

#include <functional>

#include "cli/commands.h"
#include "reports/analyze.h"
#include "reports/compare.h"
#include "reports/simulate.h"

namespace meshreuse::cli {

using InMemory = std::function<void(StreamSource&)>;
AnalyzeConfig AnalyzeConfigFromArgs(const Args& args, const InMemory& in_memory = {});
SimulateConfig SimulateConfigFromArgs(const Args& args, const InMemory& in_memory = {});
CompareConfig CompareConfigFromArgs(const Args& args);

}  // namespace meshreuse::cli
