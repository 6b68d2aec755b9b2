// meshreuse orderings | reorder | compare.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/papi_counters.h"
#include "cli/common.h"
#include "cli/options.h"
#include "core/mesh_io.h"
#include "core/orderings/rdr.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "core/quality.h"
#include "reports/compare.h"
#include "reports/run_info.h"
#include "reports/table.h"

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
                    "Lists the vertex orderings, what they do and their source; file:PATH (a "
                    "user's permutation file) last.",
                    desc, pos, vm))
    return 0;
  if (vm.count("check")) {
    CheckOrderings(SplitList(check));
    return 0;
  }
  Table t({"name", "description", "reference"});
  auto add = [&](const OrderingInfo& o) {
    t.AddRow({std::string(o.name) + (o.argument == kArgument           ? ":PATH"
                                     : o.argument == kOptionalArgument ? "[:ARG]"
                                                                       : ""),
              o.description, o.reference});
  };
  // Registered orderings in the registry's order (users' own included), then file:PATH.
  for (const OrderingInfo& o : Orderings())
    if (o.argument != kArgument) add(o);
  for (const OrderingInfo& o : Orderings())
    if (o.argument == kArgument) add(o);
  std::printf("%s", vm.count("json") ? t.Json().c_str() : t.Aligned().c_str());
  return 0;
}

int ReorderCommand(const Args& args) {
  po::options_description desc("options");
  std::string mesh, ordering, out, triangle_order;
  uint64_t seed = 1;
  desc.add_options()("mesh", po::value(&mesh)->required(), "input mesh")(
      "ordering", po::value(&ordering)->required(), ("one of: " + OrderingNames()).c_str())(
      "seed", po::value(&seed)->default_value(1), "seed of randomised orderings")(
      "output,o", po::value(&out)->required(),
      "prefix: writes PREFIX.node, PREFIX.ele and PREFIX.perm (the permutation, file: format)")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(args, "reorder MESH --ordering NAME -o PREFIX",
                    "Reorders a mesh's vertices (and its triangles to follow them) and writes the "
                    "reordered mesh and the permutation. PREFIX.perm lists, one per line, the old "
                    "id of each new vertex; `--ordering file:PREFIX.perm` reads it back.",
                    desc, pos, vm))
    return 0;
  CheckOrderings({ordering});
  const Progress progress(vm.count("quiet") > 0);
  const Mesh m = LoadMesh(mesh, progress);
  auto t0 = std::chrono::steady_clock::now();
  const Permutation p = ComputeOrdering(ordering, m, seed);
  const double order_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  const Mesh r = ApplyPermutation(m, p, TriangleOrderOption(triangle_order));
  const double apply_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const std::string& f : WriteMesh(r, out)) std::printf("wrote %s\n", f.c_str());
  WritePermutation(p.new_to_old(), out + ".perm",
                   "meshreuse reorder " + mesh + " --ordering " + ordering +
                       (ordering == "random" ? " --seed " + std::to_string(seed) : ""));
  std::printf("wrote %s.perm\n", out.c_str());
  std::printf("ordering %s: %.3f ms to compute, %.3f ms to apply\n", ordering.c_str(),
              1e3 * order_s, 1e3 * apply_s);
  if (ordering == "rdr" || ordering == "rdr-frontier") {  // the chains behind the order
    RdrChains c;
    (ordering == "rdr" ? RdrOrder : RdrFrontierOrder)(m, VertexQualities(m), &c);
    std::vector<int64_t> n;
    for (int64_t k : c.placed)
      if (k > 0) n.push_back(k);
    std::sort(n.begin(), n.end());
    const auto small = std::lower_bound(n.begin(), n.end(), 10) - n.begin();
    if (!n.empty())
      std::printf("chains placing vertices: %zu, longest %lld, median %lld, fewer than ten: %lld\n",
                  n.size(), static_cast<long long>(n.back()),
                  static_cast<long long>(n[n.size() / 2]), static_cast<long long>(small));
  }
  return 0;
}

int CompareCommand(const Args& args) {
  po::options_description desc("options");
  std::string orderings = "ori,bfs,rdr,random", threads = "1", out_dir, mode_name = "gauss-seidel",
              quality_name = "per-move", triangle_order, counters;
  CompareConfig cfg;
  desc.add_options()("mesh", po::value(&cfg.meshes)->required()->multitoken(), "mesh file(s)")(
      "orderings", po::value(&orderings)->default_value(orderings), "comma-separated orderings")(
      "threads,t", po::value(&threads)->default_value("1"), "comma-separated thread counts")(
      "repeat", po::value(&cfg.repeat)->default_value(5), "smoothing runs per (ordering, threads)")(
      "seed", po::value(&cfg.seed)->default_value(1), "seed of randomised orderings")(
      "tol", po::value(&cfg.smooth.tol)->default_value(5e-6, "5e-6"), "stop rule, as for smooth")(
      "max-iters", po::value(&cfg.smooth.max_iters)->default_value(100),
      "at most this many sweeps")("quality", po::value(&quality_name)->default_value("per-move"),
                                  "per-move (the paper's Algorithm 1) or per-sweep (lean)")(
      "mode", po::value(&mode_name)->default_value("gauss-seidel"), "gauss-seidel or jacobi")(
      "out", po::value(&out_dir),
      "write compare.{csv,md,json}, summary.{csv,md} and run.json here")(
      "json", "print the rows and the summary as JSON instead of text")(
      "csv", "print the rows as CSV instead of text")(
      "counters", po::value(&counters)->implicit_value("default"),
      "hardware counters (PAPI) around every run's sweeps, as for smooth; median over rounds")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", -1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "compare MESH... [--orderings ori,bfs,rdr,random] [--threads 1,2] [--repeat 5]",
          "For each mesh x ordering x thread count: reorder once, then smooth to "
          "convergence --repeat times from the same start (rounds interleave the "
          "orderings, so machine noise hits all alike). Reports median time per sweep and "
          "in total, sweeps, final quality, reordering time, and the paper's Speedup "
          "T_ori(1)/T_ord(p) and Gain (T_bfs(p)-T_ord(p))/T_bfs(p) on median totals.",
          desc, pos, vm))
    return 0;
  cfg.orderings = SplitList(orderings);
  CheckOrderings(cfg.orderings);
  cfg.threads = ParseThreadList(threads);
  CheckOneFormat(vm);
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  if (cfg.repeat < 1) throw po::error("--repeat must be at least 1");
  if (std::isnan(cfg.smooth.tol)) throw po::error("--tol must be a number");
  try {
    cfg.smooth.mode = ParseUpdateMode(mode_name);
    cfg.smooth.quality = ParseQualityMode(quality_name);
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
  cfg.triangle_order = TriangleOrderOption(triangle_order);
  if (!counters.empty()) {
    cfg.counter_events = counters == "default" ? DefaultCounterEvents() : SplitList(counters);
    const CounterNote note = ProbeCounters(cfg.counter_events);
    if (!note.note.empty())
      std::fprintf(stderr, "meshreuse: note: counters: %s%s\n", note.note.c_str(),
                   note.available ? "" : "; no counter is recorded");
  }
  const Progress progress(vm.count("quiet") > 0);
  const std::vector<CompareRow> rows = RunCompare(
      cfg, [&](const std::string& s) { progress.Say(s); },
      [](const std::string& w) { std::fprintf(stderr, "meshreuse: warning: %s\n", w.c_str()); });
  const Table t = CompareTable(rows);
  const Table summary = CompareSummaryTable(rows);
  if (vm.count("json")) {
    std::printf("{\"seed\": %llu, \"rows\": %s, \"summary\": %s}\n",
                static_cast<unsigned long long>(cfg.seed), CompareJson(rows).c_str(),
                summary.Json().c_str());
  } else if (vm.count("csv")) {
    std::printf("%s", t.Csv().c_str());
  } else {
    std::printf("%s", t.Aligned().c_str());
    std::printf(
        "(seed %llu; times are medians of %d runs; speedup = T_ori(1)/T; gain = "
        "(T_bfs-T)/T_bfs;\n span = |new(u) - new(v)| over the mesh edges)\n\n",
        static_cast<unsigned long long>(cfg.seed), cfg.repeat);
    std::printf("mean over %zu mesh(es):\n%s", cfg.meshes.size(), summary.Aligned().c_str());
  }
  if (!out_dir.empty()) {
    WriteText(out_dir + "/compare.csv", t.Csv());
    WriteText(out_dir + "/compare.md", t.Markdown());
    WriteText(out_dir + "/summary.csv", summary.Csv());
    WriteText(out_dir + "/summary.md", summary.Markdown());
    WriteText(out_dir + "/compare.json", "{\n  \"rows\": " + CompareJson(rows) + "\n}\n");
    std::string th;
    for (int x : cfg.threads) th += (th.empty() ? "" : ", ") + std::to_string(x);
    std::string ord;
    for (const std::string& o : cfg.orderings) ord += (ord.empty() ? "" : ", ") + JsonString(o);
    WriteText(out_dir + "/run.json",
              "{\n" + RunJsonHeader("meshreuse compare") + "  \"config\": {\"orderings\": [" + ord +
                  "], \"threads\": [" + th + "], \"repeat\": " + std::to_string(cfg.repeat) +
                  ", \"seed\": " + std::to_string(cfg.seed) + ", \"triangle_order\": " +
                  JsonString(triangle_order) + ", \"counters\": " + JsonString(counters) +
                  ", \"mode\": " + JsonString(UpdateModeName(cfg.smooth.mode)) +
                  ", \"quality\": " + JsonString(QualityModeName(cfg.smooth.quality)) +
                  ", \"tol\": " + JsonNumber(cfg.smooth.tol) +
                  ", \"max_iters\": " + std::to_string(cfg.smooth.max_iters) + "},\n" +
                  "  \"results\": " + CompareJson(rows) + "\n}\n");
    progress.Say("wrote " + out_dir + "/{compare,summary}.{csv,md}, compare.json, run.json");
  }
  return 0;
}

}  // namespace meshreuse::cli
