// meshreuse validate: the miss model against the simulator and hardware counters, with the
// paper's Table 3 (reports/validation.h).
#include <cstdio>
#include <filesystem>
#include <string>

#include "analysis/papi_counters.h"
#include "cli/common.h"
#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "reports/inputs.h"
#include "reports/validation.h"

namespace meshreuse::cli {

int ValidateCommand(const Args& args) {
  po::options_description desc("options");
  std::string mesh, cache = "westmere-ex", counters = "PAPI_L1_DCM,PAPI_L2_DCM,PAPI_L3_TCM",
                    out_dir;
  ValidationConfig cfg;
  SourceOptionText source;
  source.orderings = "ori,bfs,rdr";
  desc.add_options()("mesh", po::value(&mesh)->required(), "input mesh");
  SourceHelp help;
  help.orderings = "comma-separated orderings";
  help.iterations = "sweeps";
  help.threads = "streams (static schedule)";
  AddSourceOptions(desc, &cfg, &source, help);
  desc.add_options()("cache", po::value(&cache)->default_value("westmere-ex"),
                     "westmere-ex (alias westmere: L1=32K/8,L2=256K/8,L3=24M/24) or "
                     "NAME=SIZE/WAYS[@CYCLES],...,mem@CYCLES")(
      "element-bytes", po::value(&cfg.element_bytes)->default_value(66),
      "element size of the element model (the paper's 66-byte nodes)")(
      "line-bytes", po::value(&cfg.line_bytes)->default_value(64), "cache line size")(
      "counters", po::value(&counters)->default_value(counters),
      "PAPI events for the levels, in level order ('none': simulate only)")(
      "exclude-cold", "Table 3: take cold misses as compulsory and invert the rest")(
      "out", po::value(&out_dir),
      "write validate.{csv,md,json}, cost.csv, table3.{csv,md}, sweeps.csv and run.json here")(
      "quiet,q", "no progress on stderr");
  AddFormatOptions(desc, /*markdown=*/true);
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "validate MESH [--orderings ori,bfs,rdr] [--iterations K] [--threads P]",
          "Validates the miss model: per ordering and cache level, the fully associative model "
          "(element and line), the set-associative simulation and hardware counters (PAPI, "
          "where the machine has them; otherwise every number is labelled simulated), their "
          "ratios, miss rates and the equation-2 cost; then the paper's Table 3 (misses and the "
          "inverse model's capacities) beside the paper's values.",
          desc, pos, vm))
    return 0;
  const OutputFormat fmt = FormatOption(vm);
  SourceOf(source, vm, &cfg);
  cfg.cache = ParseCacheSpec(cache);
  cfg.counter_events = counters == "none" ? std::vector<std::string>{} : SplitList(counters);
  cfg.exclude_cold = vm.count("exclude-cold") > 0;
  cfg.inputs = {mesh};
  cfg.mesh_name = std::filesystem::path(mesh).filename().string();
  CheckValidationConfig(cfg);
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  const CounterNote note = ProbeCounters(cfg.counter_events);
  if (!note.note.empty())  // said once, before the work
    std::fprintf(stderr, "meshreuse: note: counters: %s%s\n", note.note.c_str(),
                 note.available ? "" : "; every miss below is simulated");
  const Progress progress(vm.count("quiet") > 0);
  const Log log = MakeLog(progress);
  const std::vector<OrderingValidation> r = RunValidation(LoadMesh(mesh, log), cfg, log.progress);
  Emit(ValidationOutput(r, cfg), fmt, out_dir, progress);
  return 0;
}

}  // namespace meshreuse::cli
