// meshreuse smooth: Laplacian smoothing of one or more meshes, optionally reordered first
// (--ordering; the reordering time is reported apart from the smoothing time). Per-sweep quality
// and time on stdout, a summary table at the end, and with --out DIR the tables as CSV/Markdown
// plus run.json.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/papi_counters.h"
#include "cli/common.h"
#include "cli/options.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/smoother.h"
#include "reports/compare.h"
#include "reports/run_info.h"
#include "reports/table.h"

namespace meshreuse::cli {

int SmoothCommand(const Args& args) {
  po::options_description desc("options");
  std::vector<std::string> meshes;
  std::string mode_name = "gauss-seidel", quality_name = "per-move", out_mesh, out_dir,
              ordering = "ori", triangle_order, counters;
  uint64_t seed = 1;
  SmoothOptions opt;
  desc.add_options()("mesh", po::value(&meshes)->required()->multitoken(), "mesh file(s)")(
      "ordering", po::value(&ordering)->default_value("ori"),
      ("reorder the vertices first: " + OrderingNames()).c_str())(
      "seed", po::value(&seed)->default_value(1), "seed of randomised orderings")(
      "threads,t", po::value(&opt.threads)->default_value(1), "OpenMP threads (static schedule)")(
      "tol", po::value(&opt.tol)->default_value(5e-6, "5e-6"),
      "stop after a sweep that improves the global quality by less than this")(
      "max-iters", po::value(&opt.max_iters)->default_value(100), "at most this many sweeps")(
      "mode", po::value(&mode_name)->default_value("gauss-seidel"), "gauss-seidel or jacobi")(
      "quality", po::value(&quality_name)->default_value("per-move"),
      "per-move: the global quality updated after every move (the paper's Algorithm 1); "
      "per-sweep: once per sweep by one pass over the triangles (the lean sweep)")(
      "output,o", po::value(&out_mesh),
      "write the smoothed mesh (PATH.vtk or a .node/.ele prefix)")(
      "out", po::value(&out_dir), "write summary.csv, summary.md, sweeps.csv and run.json here")(
      "counters", po::value(&counters)->implicit_value("default"),
      "hardware counters (PAPI) around the sweeps, per thread and summed: a comma list of PAPI "
      "events, or none for PAPI_L1_DCM,PAPI_L2_DCM,PAPI_L3_TCM,PAPI_TOT_CYC,PAPI_TOT_INS; events "
      "this machine cannot count are dropped with PAPI's reason")(
      "json", "print the results and every sweep as JSON instead of text")(
      "csv", "print every sweep as CSV instead of text")(
      "flush-caches",
      "before the first sweep, stream 64 MiB through the caches (cold start, as "
      "the simulator's empty caches; scripts/validate_callgrind.sh)")("quiet,q",
                                                                      "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", -1);
  po::variables_map vm;
  if (!ParseOptions(args, "smooth MESH... [--ordering NAME] [--threads P] [--tol T] [-o OUT]",
                    "Laplacian smoothing as in the paper (Mesquite's smoother): each sweep moves "
                    "every interior vertex, in storage order, to the average of its neighbours. "
                    "Prints the global quality and time of each sweep, then a summary. With "
                    "--ordering the mesh is reordered first and -o writes it in the new order.",
                    desc, pos, vm))
    return 0;
  try {
    opt.mode = ParseUpdateMode(mode_name);
    opt.quality = ParseQualityMode(quality_name);
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
  if (opt.threads < 1 || opt.threads > 1024)
    throw po::error("--threads must be between 1 and 1024");
  if (opt.max_iters < 1) throw po::error("--max-iters must be at least 1");
  if (std::isnan(opt.tol)) throw po::error("--tol must be a number (negative: never stop early)");
  if (!out_mesh.empty() && meshes.size() != 1) throw po::error("-o takes a single input mesh");
  CheckOrderings({ordering});
  CheckOneFormat(vm);
  const bool json = vm.count("json") > 0, csv = vm.count("csv") > 0, text = !json && !csv;
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  if (!out_mesh.empty()) CheckWritable(out_mesh);
  const TriangleOrder tri_order = TriangleOrderOption(triangle_order);
  if (vm.count("flush-caches")) opt.flush_bytes = uint64_t{64} << 20;
  const Progress progress(vm.count("quiet") > 0);
  std::unique_ptr<PapiCounters> papi;
  std::string counters_json = "null";
  if (!counters.empty()) {
    papi = std::make_unique<PapiCounters>(
        counters == "default" ? DefaultCounterEvents() : SplitList(counters), opt.threads);
    if (!papi->reason().empty())
      std::fprintf(stderr, "meshreuse: note: counters: %s%s\n", papi->reason().c_str(),
                   papi->available() ? "" : "; no counter is recorded");
    if (papi->available()) opt.region = papi.get();
  }

  Table summary({"mesh", "ordering", "vertices", "triangles", "threads", "mode", "sweeps",
                 "converged", "quality_before", "quality_after", "reorder_ms",
                 "median_ms_per_sweep", "total_s"});
  Table sweeps({"mesh", "sweep", "quality", "improvement", "ms"});
  std::string results_json;
  if (meshes.size() > 1 && papi && papi->available())
    throw po::error("--counters takes a single input mesh");
  for (const std::string& path : meshes) {
    Mesh m = LoadMesh(path, progress);
    double reorder_s = 0;
    if (ordering != "ori" || tri_order == TriangleOrder::kSorted) {
      progress.Say("laying out in " + ordering + " order, triangles " +
                   TriangleOrderName(tri_order));
      const auto t0 = std::chrono::steady_clock::now();
      ApplyPermutationInPlace(&m, ComputeOrdering(ordering, m, seed), tri_order);
      reorder_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (text)
      std::printf("== %s: %s vertices, %s triangles, ordering %s%s, %d thread%s, %s\n",
                  path.c_str(), Grouped(m.NumVertices()).c_str(), Grouped(m.NumTriangles()).c_str(),
                  ordering.c_str(),
                  ordering == "random" ? (" (seed " + std::to_string(seed) + ")").c_str() : "",
                  opt.threads, opt.threads == 1 ? "" : "s", UpdateModeName(opt.mode));
    if (text && ordering != "ori")
      std::printf("reordering (ordering + apply): %.3f ms\n", 1e3 * reorder_s);
    if (text) std::printf("%6s  %10s  %12s  %10s\n", "sweep", "quality", "improvement", "time_ms");
    std::fflush(stdout);
    progress.Say("smoothing " + path);
    NullSink untraced;
    const SmoothResult r = Smooth(m, opt, untraced, [&](const SweepRecord& s) {
      if (!text) return;
      std::printf("%6d  %10.6f  %+12.3e  %10.3f\n", s.sweep, s.quality, s.improvement,
                  1e3 * s.seconds);
      std::fflush(stdout);
    });
    std::vector<double> times;
    for (const SweepRecord& s : r.sweeps) {
      times.push_back(s.seconds);
      sweeps.AddRow({path, std::to_string(s.sweep), JsonNumber(s.quality),
                     JsonNumber(s.improvement), JsonNumber(1e3 * s.seconds)});
    }
    const double med = Median(times);
    if (text)
      std::printf("sweeps %zu (%s), quality %.6f -> %.6f, median %.3f ms/sweep, total %.3f s\n",
                  r.sweeps.size(), r.converged ? "converged" : "max-iters reached",
                  r.quality_before, r.quality_after, 1e3 * med, r.seconds);
    if (papi && papi->available()) {
      if (!papi->error().empty()) throw std::runtime_error("counters failed: " + papi->error());
      const std::vector<long long> sum = papi->Sum();
      std::string per_thread;
      counters_json = "{";
      for (size_t e = 0; e < papi->events().size(); ++e) {
        if (text)
          std::printf("counter %-16s %16s (all sweeps, all threads", papi->events()[e].c_str(),
                      Grouped(sum[e]).c_str());
        std::string th = "[";
        for (size_t t = 0; t < papi->per_thread().size(); ++t) {
          if (text && opt.threads > 1)
            std::printf("; thread %zu %s", t, Grouped(papi->per_thread()[t][e]).c_str());
          th += (t ? ", " : "") + std::to_string(papi->per_thread()[t][e]);
        }
        if (text) std::printf(")\n");
        counters_json += std::string(e ? ", " : "") + JsonString(papi->events()[e]) +
                         ": {\"sum\": " + std::to_string(sum[e]) + ", \"per_thread\": " + th + "]}";
      }
      counters_json += "}";
    }
    if (text) std::printf("\n");
    summary.AddRow(
        {path, ordering, std::to_string(m.NumVertices()), std::to_string(m.NumTriangles()),
         std::to_string(opt.threads), UpdateModeName(opt.mode), std::to_string(r.sweeps.size()),
         r.converged ? "yes" : "no", Fixed(r.quality_before, 6), Fixed(r.quality_after, 6),
         Fixed(1e3 * reorder_s, 3), Fixed(1e3 * med, 3), Fixed(r.seconds, 3)});
    results_json +=
        std::string(results_json.empty() ? "" : ",\n") + "    {\"mesh\": " + JsonString(path) +
        ", \"ordering\": " + JsonString(ordering) +
        ", \"vertices\": " + std::to_string(m.NumVertices()) +
        ", \"triangles\": " + std::to_string(m.NumTriangles()) +
        ", \"sweeps\": " + std::to_string(r.sweeps.size()) +
        ", \"converged\": " + (r.converged ? "true" : "false") +
        ", \"quality_before\": " + JsonNumber(r.quality_before) +
        ", \"quality_after\": " + JsonNumber(r.quality_after) +
        ", \"reorder_seconds\": " + JsonNumber(reorder_s) +
        ", \"median_seconds_per_sweep\": " + JsonNumber(med) +
        ", \"total_seconds\": " + JsonNumber(r.seconds) + ", \"counters\": " + counters_json + "}";
    if (!out_mesh.empty())
      for (const std::string& f : WriteMesh(m, out_mesh)) progress.Say("wrote " + f);
  }
  if (text && meshes.size() > 1) std::printf("%s", summary.Aligned().c_str());
  if (json)
    std::printf("{\"results\": [\n%s\n], \"sweeps\": %s}\n", results_json.c_str(),
                sweeps.Json().c_str());
  if (csv) std::printf("%s", sweeps.Csv().c_str());
  if (!out_dir.empty()) {
    WriteText(out_dir + "/summary.csv", summary.Csv());
    WriteText(out_dir + "/summary.md", summary.Markdown());
    WriteText(out_dir + "/sweeps.csv", sweeps.Csv());
    WriteText(out_dir + "/run.json",
              "{\n" + RunJsonHeader("meshreuse smooth") + "  \"config\": {\"ordering\": " +
                  JsonString(ordering) + ", \"seed\": " + std::to_string(seed) +
                  ", \"triangle_order\": " + JsonString(triangle_order) + ", \"counters\": " +
                  (papi ? std::string("{\"version\": ") + JsonString(PapiCounters::Version()) +
                              ", \"recorded\": " + (papi->available() ? "true" : "false") +
                              ", \"note\": " + JsonString(papi->reason()) + "}"
                        : std::string("null")) +
                  ", \"threads\": " + std::to_string(opt.threads) +
                  ", \"mode\": " + JsonString(UpdateModeName(opt.mode)) + ", \"quality\": " +
                  JsonString(QualityModeName(opt.quality)) + ", \"tol\": " + JsonNumber(opt.tol) +
                  ", \"max_iters\": " + std::to_string(opt.max_iters) +
                  ", \"omp_max_threads\": " + std::to_string(omp_get_max_threads()) +
                  "},\n  \"results\": [\n" + results_json + "\n  ]\n}\n");
    progress.Say("wrote " + out_dir + "/{summary.csv,summary.md,sweeps.csv,run.json}");
  }
  return 0;
}

}  // namespace meshreuse::cli
