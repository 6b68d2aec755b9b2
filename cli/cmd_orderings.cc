// meshreuse orderings: the registry's table (core/orderings/list.h), or a check of specs.
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/orderings/registry.h"

namespace meshreuse::cli {

int OrderingsCommand(const Args& args) {
  po::options_description desc("options");
  std::string check;
  desc.add_options()("check", po::value(&check),
                     "check a comma-separated list of ordering specs (exit 2 naming a bad one)")(
      "json", "the list as JSON");
  po::positional_options_description pos;
  po::variables_map vm;
  if (!ParseOptions(args, "orderings [--check LIST] [--json]",
                    "Lists the vertex orderings, what they do, whether --seed changes them, and "
                    "their source; file:PATH (a user's permutation file) last. Any spec may be "
                    "labelled, LABEL=SPEC, so tables name it LABEL.",
                    desc, pos, vm))
    return 0;
  if (vm.count("check")) {
    const std::vector<std::string> specs = SplitList(check);
    if (specs.empty()) throw UsageError("no ordering given");
    for (const std::string& s : specs) CheckOrderingSpec(s);
    return 0;
  }
  Table t({"name", "seeded", "description", "reference"});
  auto add = [&](const OrderingInfo& o) {
    t.AddRow({std::string(o.name) + (o.argument == kArgument           ? ":PATH"
                                     : o.argument == kOptionalArgument ? "[:ARG]"
                                                                       : ""),
              o.seeded ? "yes" : "no", o.description, o.reference});
  };
  // Registered orderings in the registry's order (users' own included), then file:PATH.
  for (const OrderingInfo& o : Orderings())
    if (o.argument != kArgument) add(o);
  for (const OrderingInfo& o : Orderings())
    if (o.argument == kArgument) add(o);
  Print(t, vm.count("json") ? OutputFormat::kJson : OutputFormat::kText);
  return 0;
}

}  // namespace meshreuse::cli
