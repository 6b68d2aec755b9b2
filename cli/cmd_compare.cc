// meshreuse compare: the smoother timed under several orderings and thread counts, rounds
// interleaved (reports/compare.h).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/papi_counters.h"
#include "cli/common.h"
#include "cli/configs.h"
#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "reports/compare.h"

namespace meshreuse::cli {

namespace {

// Parses `args` into cfg, vm and out_dir: false when --help was printed.
bool ParseCompare(const Args& args, CompareConfig& cfg, po::variables_map& vm,
                  std::string& out_dir) {
  po::options_description desc("options");
  std::string orderings = "ori,bfs,rdr,random", threads = "1", mode = "gauss-seidel",
              quality = "per-move", triangle_order, counters, seed = "1", repeat = "5",
              clock = "wall";
  desc.add_options()("mesh", po::value(&cfg.meshes)->required()->multitoken(), "mesh file(s)")(
      "orderings", po::value(&orderings)->default_value(orderings),
      "comma-separated orderings (LABEL=SPEC names a row)")(
      "kernel", po::value(&cfg.kernel)->default_value(kPaperKernel),
      (std::string(KernelOptionHelp()) +
       "; a fixed-work kernel (assembly, spmv) runs 10 sweeps unless --max-iters says")
          .c_str())("threads,t", po::value(&threads)->default_value("1"),
                    "comma-separated thread counts")(
      "repeat", po::value(&repeat)->default_value("5"),
      "timed rounds (at least 3), or auto[:CAP]: rounds until every speedup is known within "
      "+-2% (at most CAP, default 15)")("seed", po::value(&seed)->default_value("1"),
                                        "seed of seeded orderings")(
      "clock", po::value(&clock)->default_value(clock),
      "speedups and gains on wall time (for scaling, on a quiet machine) or cpu: the thread "
      "CPU time of the sweeps, summed over threads (on a shared machine)")(
      "tol", po::value(&cfg.smooth.tol)->default_value(5e-6, "5e-6"), "stop rule, as for smooth")(
      "max-iters", po::value(&cfg.smooth.max_iters)->default_value(100),
      "at most this many sweeps")(
      "warm-up-sweeps", po::value(&cfg.warmup_sweeps)->default_value(cfg.warmup_sweeps),
      "sweeps of each run's untimed warm-up (as many as --max-iters: a whole run)")(
      "quality", po::value(&quality)->default_value("per-move"),
      "per-move (the paper's Algorithm 1) or per-sweep (lean)")(
      "mode", po::value(&mode)->default_value("gauss-seidel"), "gauss-seidel or jacobi")(
      "out", po::value(&out_dir),
      "write compare.{csv,md,json}, summary.{csv,md} and run.json here")(
      "counters", po::value(&counters)->implicit_value("default"),
      "hardware counters (PAPI) around every run's sweeps, as for smooth; median over rounds")(
      "quiet,q", "no progress on stderr");
  AddFormatOptions(desc);
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", -1);
  if (!ParseOptions(
          args, "compare MESH... [--orderings ori,bfs,rdr,random] [--threads 1,2] [--repeat 5]",
          "For each mesh x ordering x thread count: an untimed warm-up (--warm-up-sweeps "
          "sweeps), then --repeat "
          "rounds that each compute the ordering, apply it and smooth to convergence from the "
          "same start (rounds interleave the orderings, so machine noise hits all alike). "
          "Every time is reported as min, median, max and a 95% interval of the median "
          "(seeded bootstrap over the rounds), in wall and thread CPU time; the paper's Speedup "
          "T_ori(1)/T_ord(p) and Gain (T_bfs(p)-T_ord(p))/T_bfs(p) come from per-sweep medians, "
          "each with its interval, and a comparison whose interval holds 1 is 'not "
          "distinguishable'. A busy machine (load above the cores, CPU/wall below 0.9, rounds "
          "varying by more than 5%) is said on stderr and in run.json.",
          desc, pos, vm))
    return false;
  cfg.orderings = SplitList(orderings);
  if (cfg.orderings.empty()) throw UsageError("no ordering given");
  for (const std::string& o : cfg.orderings) CheckOrderingSpec(o);
  cfg.threads = ParseThreadList(threads);
  ParseRepeat(repeat, &cfg.repeat, &cfg.repeat_auto, &cfg.repeat_cap);
  cfg.seed = ParseCount(seed, "--seed", 0, UINT64_MAX >> 1);
  cfg.clock = ParseClock(clock);
  if (std::isnan(cfg.smooth.tol)) throw UsageError("--tol must be a number");
  if (cfg.smooth.max_iters < 1) throw UsageError("--max-iters must be at least 1");
  cfg.smooth.mode = ParseUpdateMode(mode);
  cfg.smooth.quality = ParseQualityMode(quality);
  if (ParseKernel(cfg.kernel).fixed && vm["max-iters"].defaulted()) cfg.smooth.max_iters = 10;
  cfg.triangle_order = ParseTriangleOrder(triangle_order);
  if (!counters.empty() && counters != "none") {
    cfg.counter_events = counters == "default" ? DefaultCounterEvents() : SplitList(counters);
    const CounterNote note = ProbeCounters(cfg.counter_events);
    if (!note.note.empty())
      std::fprintf(stderr, "meshreuse: note: counters: %s%s\n", note.note.c_str(),
                   note.available ? "" : "; no counter is recorded");
  }
  return true;
}

}  // namespace

CompareConfig CompareConfigFromArgs(const Args& args) {
  CompareConfig cfg;
  po::variables_map vm;
  std::string out_dir;
  if (!ParseCompare(args, cfg, vm, out_dir)) throw UsageError("--help is the command's");
  RefuseCommandOptions(vm, {"out", "json", "csv", "markdown", "quiet"});
  return cfg;
}

int CompareCommand(const Args& args) {
  CompareConfig cfg;
  po::variables_map vm;
  std::string out_dir;
  if (!ParseCompare(args, cfg, vm, out_dir)) return 0;
  const OutputFormat fmt = FormatOption(vm);
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  const Progress progress(vm.count("quiet") > 0);
  const Log log = MakeLog(progress);
  const CompareResult result = RunCompare(cfg, log.progress, log.warn);
  for (const std::string& why : result.noise.Reasons())  // said once, before the tables
    std::fprintf(stderr, "meshreuse: warning: timings taken on a busy machine: %s\n", why.c_str());
  if (!result.noise.Reasons().empty() && cfg.clock == TimeClock::kWall)
    std::fprintf(stderr,
                 "meshreuse: note: --clock cpu ranks the orderings by the CPU time their sweeps "
                 "cost, which other work on the machine disturbs less than wall time\n");
  Emit(CompareOutput(result, cfg), fmt, out_dir, progress);
  return 0;
}

}  // namespace meshreuse::cli
