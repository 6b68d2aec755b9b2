// meshreuse report: the paper's experiment as one run (reports/report.h), behind
// scripts/reproduce.sh. Options are checked and the output folder made before any work.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <thread>

#include "analysis/machine.h"
#include "cli/common.h"
#include "core/error.h"
#include "core/orderings/registry.h"
#include "reports/compare.h"
#include "reports/report.h"
#include "tracer/access_stream.h"

namespace meshreuse::cli {

namespace {

// Draws the report's figures: Debian's python3 (where matplotlib is) on scripts/plot_report.py
// DIR, its lines on stderr (none when quiet). Returns "" once drawn, else why not.
std::string DrawFigures(const std::string& out_dir, bool quiet) {
  const std::string python = "/usr/bin/python3",
                    script = std::string(MESHREUSE_SOURCE_DIR) + "/scripts/plot_report.py";
  if (::access(python.c_str(), X_OK) != 0) return "there is no " + python;
  if (::access(script.c_str(), R_OK) != 0) return "there is no " + script;
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) return "fork failed";
  if (pid == 0) {
    const int out = quiet ? ::open("/dev/null", O_WRONLY) : ::dup(2);
    if (out >= 0) ::dup2(out, 1);
    const char* argv[] = {python.c_str(), script.c_str(), out_dir.c_str(), nullptr};
    ::execv(argv[0], const_cast<char* const*>(argv));
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  return WIFEXITED(status) ? "plot_report.py exited " + std::to_string(WEXITSTATUS(status))
                           : "plot_report.py was killed";
}

}  // namespace

int ReportCommand(const Args& args) {
  po::options_description desc("options");
  std::string orderings = "ori,bfs,rdr", threads, out_dir, triangle_order, cache = "westmere-ex",
              counters = "PAPI_L1_DCM,PAPI_L2_DCM,PAPI_L3_TCM", fig1_orderings = "random,ori,bfs",
              seed = "1", repeat = "3", clock = "wall", machine = "westmere-ex",
              machine_threads = "1,2,4,8,16,24,32", prefetch = "L1,L2",
              kernels = "laplacian,smart-laplacian,untangle,edge-swap,assembly,spmv",
              kernel_orderings = "ori,bfs,rdr,grid-wave,rcm,hilbert";
  ReportConfig cfg;
  desc.add_options()("mesh", po::value(&cfg.meshes)->required()->multitoken(), "mesh file(s)")(
      "orderings", po::value(&orderings)->default_value(orderings),
      "comma-separated orderings (registered names, file:PATH, LABEL=SPEC)")(
      "threads,t", po::value(&threads), "comma-separated thread counts (default: 1..cores)")(
      "repeat", po::value(&repeat)->default_value("3"),
      "timed rounds per (ordering, threads), at least 3, or auto[:CAP] (as for compare)")(
      "seed", po::value(&seed)->default_value("1"), "seed of seeded orderings")(
      "clock", po::value(&clock)->default_value(clock),
      "speedups and gains on wall or cpu time (as for compare)")(
      "tol", po::value(&cfg.smooth.tol)->default_value(5e-6, "5e-6"), "stop rule, as for smooth")(
      "max-iters", po::value(&cfg.smooth.max_iters)->default_value(100),
      "at most this many sweeps")(
      "warm-up-sweeps", po::value(&cfg.warmup_sweeps)->default_value(cfg.warmup_sweeps),
      "sweeps of each timed run's untimed warm-up, the kernels part's too (as for compare)")(
      "cache", po::value(&cache)->default_value(cache), "cache levels, as for validate")(
      "counters", po::value(&counters)->default_value(counters),
      "PAPI events for the levels (none: simulate only)")(
      "validate-sweeps", po::value(&cfg.validate_sweeps)->default_value(2),
      "traced sweeps for Table 3 and the miss rates")(
      "profile-sweeps", po::value(&cfg.profile_sweeps)->default_value(8),
      "sweeps of the profile figure")("figure1-mesh",
                                      po::value(&cfg.figure1_mesh)->default_value(cfg.figure1_mesh),
                                      "mesh (short name) of the first figure; none: no figure")(
      "figure1-orderings", po::value(&fig1_orderings)->default_value(fig1_orderings),
      "its orderings")("figure1-bins", po::value(&cfg.figure1_time_bins)->default_value(400),
                       "its time bins (columns)")(
      "profile-mesh", po::value(&cfg.profile_mesh)->default_value(cfg.profile_mesh),
      "mesh (short name) of the profile figure; none: no figure")(
      "machine", po::value(&machine)->default_value(machine),
      "the many-core part: westmere-ex (alias westmere; the paper's 4 x 8 cores) or a machine file "
      "(README, "
      "\"Many cores\"); none: no many-core part")(
      "machine-threads", po::value(&machine_threads)->default_value(machine_threads),
      "thread counts simulated on the machine (compact and scatter placement)")(
      "machine-sweeps", po::value(&cfg.machine_sweeps)->default_value(cfg.machine_sweeps),
      "traced sweeps per simulation (the last, warm, is counted)")(
      "prefetch", po::value(&prefetch)->default_value(prefetch),
      "levels with a next-line prefetcher in the one-thread prefetch table; none: no table")(
      "kernels", po::value(&kernels)->default_value(kernels),
      "the other-kernels part (the paper's conjecture): these kernels of `meshreuse kernels` in "
      "--kernel-orderings on every mesh, simulated and timed (local-opt, ten Laplacian sweeps' "
      "cost a sweep, only when named); none: no such part")(
      "kernel-orderings", po::value(&kernel_orderings)->default_value(kernel_orderings),
      "the orderings of the kernels part")(
      "kernel-sweeps", po::value(&cfg.kernel_sweeps)->default_value(cfg.kernel_sweeps),
      "timed sweeps per run in the kernels part")(
      "no-timing", "skip the timed runs (tables 1-3, misses and figure data only)")(
      "label", po::value(&cfg.label), "a name for the run (README title, run.json)")(
      "measured", po::value(&cfg.measured),
      "a compare.csv from `meshreuse compare --out DIR` run on another machine (a 16-core "
      "node, say): its speedups drawn beside the many-core prediction (the machine named from "
      "the run.json beside it)")(
      "prior-phases", po::value(&cfg.prior_phases),
      "a file of phases that ran before the report, one \"NAME WALL_SECONDS CPU_SECONDS\" per "
      "line (scripts/reproduce.sh: its setup, build and meshing): put first in the README's and "
      "run.json's breakdown of where the time went")(
      "no-figures",
      "do not draw the figures (otherwise drawn at the end by scripts/plot_report.py under "
      "Debian's /usr/bin/python3 with matplotlib)")("out", po::value(&out_dir)->required(),
                                                    "the result folder (created; must be empty)")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", -1);
  po::variables_map vm;
  if (!ParseOptions(args, "report MESH... --out DIR [--orderings ori,bfs,rdr] [--threads 1,2]",
                    "Runs the paper's experiment on the meshes and writes every table (CSV, "
                    "Markdown, LaTeX; the paper's values beside ours), the data of every figure "
                    "(drawn at the end by scripts/plot_report.py where Debian's matplotlib is), "
                    "run.json, manifest.json and a README.md "
                    "to DIR. scripts/reproduce.sh runs it on the nine meshes.",
                    desc, pos, vm))
    return 0;
  cfg.orderings = SplitList(orderings);
  cfg.figure1_orderings = SplitList(fig1_orderings);
  if (cfg.figure1_mesh == "none") cfg.figure1_mesh.clear();
  if (cfg.profile_mesh == "none") cfg.profile_mesh.clear();
  cfg.threads = threads.empty() ? std::vector<int>{} : ParseThreadList(threads);
  if (cfg.threads.empty())
    for (int p = 1; p <= std::max(1, static_cast<int>(std::thread::hardware_concurrency())); ++p)
      cfg.threads.push_back(p);
  ParseRepeat(repeat, &cfg.repeat, &cfg.repeat_auto, &cfg.repeat_cap);
  cfg.seed = ParseCount(seed, "--seed", 0, UINT64_MAX >> 1);
  cfg.clock = ParseClock(clock);
  if (std::isnan(cfg.smooth.tol)) throw UsageError("--tol must be a number");
  cfg.cache = ParseCacheSpec(cache);
  cfg.counter_events = counters == "none" ? std::vector<std::string>{} : SplitList(counters);
  cfg.timing = vm.count("no-timing") == 0;
  cfg.kernels = kernels == "none" ? std::vector<std::string>{} : SplitList(kernels);
  cfg.kernel_orderings = SplitList(kernel_orderings);
  cfg.machine = machine == "none" ? "" : CanonicalMachine(machine);
  cfg.machine_threads = ParseThreadList(machine_threads);
  cfg.prefetch_levels = prefetch == "none" ? "" : prefetch;
  cfg.triangle_order = ParseTriangleOrder(triangle_order);
  cfg.command_line = FullCommandLine();
  for (const std::string& m : cfg.meshes)
    if (ClassifyInput(m) != InputKind::kMesh)
      throw UsageError("'" + m + "' is not a mesh (.node, .ele or .msh)");
  CheckReportConfig(cfg);
  const bool existed = std::filesystem::exists(out_dir);
  PrepareOutDir(out_dir, /*must_be_empty=*/true);
  const Progress progress(vm.count("quiet") > 0);
  // The figures are drawn inside the run, once its tables and data are written, so their time is
  // in the breakdown; a failure to draw them is a note, not an error.
  std::string why_no_figures;
  std::function<void()> figures;
  if (vm.count("no-figures") == 0)
    figures = [&] {
      progress.Say("drawing the figures (scripts/plot_report.py)");
      why_no_figures = DrawFigures(out_dir, vm.count("quiet") > 0);
    };
  try {
    std::printf("%s\n", RunReport(cfg, out_dir, MakeLog(progress), figures).c_str());
  } catch (...) {
    // A failed run leaves the folder as it found it (absent, or empty), so a retry can use it.
    std::error_code ec;
    if (!existed) {
      std::filesystem::remove_all(out_dir, ec);
    } else {
      for (const auto& e : std::filesystem::directory_iterator(out_dir, ec))
        std::filesystem::remove_all(e.path(), ec);
    }
    throw;
  }
  if (!why_no_figures.empty())
    std::fprintf(stderr,
                 "meshreuse: note: the figures were not drawn (%s): draw them with "
                 "/usr/bin/python3 scripts/plot_report.py %s once Debian's python3-matplotlib "
                 "is installed (scripts/setup.sh --with-plots)\n",
                 why_no_figures.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace meshreuse::cli
