// meshreuse smooth: Laplacian smoothing of meshes (reports/smooth.h), optionally reordered first;
// per-sweep quality and time on stdout, a summary, with --out DIR the tables and run.json.
#include <cstdio>
#include <string>
#include <vector>

#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/table.h"
#include "reports/smooth.h"

namespace meshreuse::cli {

int SmoothCommand(const Args& args) {
  po::options_description desc("options");
  SmoothConfig cfg;
  std::string mode = "gauss-seidel", quality = "per-move", out_dir, triangle_order, counters,
              seed = "1";
  desc.add_options()("mesh", po::value(&cfg.meshes)->required()->multitoken(), "mesh file(s)")(
      "ordering", po::value(&cfg.ordering)->default_value("ori"),
      ("reorder the vertices first: " + OrderingNames()).c_str())(
      "seed", po::value(&seed)->default_value("1"), "seed of seeded orderings")(
      "kernel", po::value(&cfg.kernel)->default_value(kPaperKernel), KernelOptionHelp())(
      "threads,t", po::value(&cfg.smooth.threads)->default_value(1),
      "OpenMP threads (static schedule)")(
      "tol", po::value(&cfg.smooth.tol)->default_value(5e-6, "5e-6"),
      "stop after a sweep that improves the global quality by less than this")(
      "max-iters", po::value(&cfg.smooth.max_iters)->default_value(100),
      "at most this many sweeps")("mode", po::value(&mode)->default_value("gauss-seidel"),
                                  "gauss-seidel or jacobi")(
      "quality", po::value(&quality)->default_value("per-move"),
      "per-move: the global quality updated after every move (the paper's Algorithm 1); "
      "per-sweep: once per sweep by one pass over the triangles (the lean sweep)")(
      "output,o", po::value(&cfg.output),
      (std::string("write the smoothed mesh: ") + kMeshOutputFormats).c_str())(
      "visit-order", po::value(&cfg.visit_order),
      "visit the interior vertices in this file's order (one 0-based id per line, every interior "
      "vertex once), storage unchanged: the serial sweep `meshreuse-mpi smooth --pi-out` "
      "writes")("out", po::value(&out_dir),
                "write summary.csv, summary.md, sweeps.csv and run.json here")(
      "counters", po::value(&counters)->implicit_value("default"),
      "hardware counters (PAPI) around the sweeps, per thread and summed: a comma list of PAPI "
      "events, or none for PAPI_L1_DCM,PAPI_L2_DCM,PAPI_L3_TCM,PAPI_TOT_CYC,PAPI_TOT_INS; events "
      "this machine cannot count are dropped with PAPI's reason")(
      "flush-caches",
      "before the first sweep, stream 64 MiB through the caches (cold start, as the simulator's "
      "empty caches; scripts/validate_callgrind.sh)")("quiet,q", "no progress on stderr");
  AddFormatOptions(desc);
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", -1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "smooth MESH... [--ordering NAME] [--threads P] [--tol T] [-o OUT]",
          "Laplacian smoothing as in the paper (Mesquite's smoother): each sweep moves "
          "every interior vertex, in storage order, to the average of its neighbours. "
          "Prints the global quality and time of each sweep, then a summary. --kernel runs "
          "another mesh kernel instead (its own measure per sweep). With "
          "--ordering the mesh is reordered first and -o writes it in the new order.",
          desc, pos, vm))
    return 0;
  cfg.seed = ParseCount(seed, "--seed", 0, UINT64_MAX >> 1);
  cfg.smooth.mode = ParseUpdateMode(mode);
  cfg.smooth.quality = ParseQualityMode(quality);
  cfg.triangle_order = ParseTriangleOrder(triangle_order);
  if (vm.count("flush-caches")) cfg.smooth.flush_bytes = uint64_t{64} << 20;
  if (!counters.empty() && counters != "none")
    cfg.counter_events = counters == "default" ? DefaultCounterEvents() : SplitList(counters);
  const OutputFormat fmt = FormatOption(vm);
  CheckSmoothConfig(cfg);
  std::vector<std::pair<std::string, std::string>> outputs;
  if (!cfg.output.empty())
    for (const std::string& f : MeshOutputFiles(cfg.output)) {
      CheckOutputPath(f, "-o", InputFiles(cfg.meshes));
      outputs.emplace_back("-o", f);
    }
  if (!out_dir.empty())
    for (const char* f : {"summary.csv", "summary.md", "sweeps.csv", "run.json"})
      outputs.emplace_back("--out", out_dir + "/" + f);
  CheckDistinctOutputs(outputs);
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  const CounterNote note = ProbeCounters(cfg.counter_events, cfg.smooth.threads);
  if (!note.note.empty())
    std::fprintf(stderr, "meshreuse: note: counters: %s%s\n", note.note.c_str(),
                 note.available ? "" : "; no counter is recorded");
  const bool text = fmt == OutputFormat::kText;
  SmoothHooks hooks;
  if (text) {
    hooks.start = [&](const SmoothRun& r) {
      std::printf("== %s: %s vertices, %s triangles, ordering %s%s, %d thread%s, %s\n",
                  r.mesh.c_str(), Grouped(r.vertices).c_str(), Grouped(r.triangles).c_str(),
                  r.ordering.c_str(),
                  ParseOrderingSpec(cfg.ordering).info->seeded
                      ? (" (seed " + std::to_string(cfg.seed) + ")").c_str()
                      : "",
                  r.threads, r.threads == 1 ? "" : "s", UpdateModeName(r.mode));
      if (r.ordering != "ori")
        std::printf("reordering (ordering + apply): %.3f ms\n", 1e3 * r.reorder_seconds);
      std::printf("%6s  %10s  %12s  %10s\n", "sweep", "quality", "improvement", "time_ms");
      std::fflush(stdout);
    };
    hooks.sweep = [](const SweepRecord& s) {
      std::printf("%6d  %10.6f  %+12.3e  %10.3f\n", s.sweep, s.quality, s.improvement,
                  1e3 * s.seconds);
      std::fflush(stdout);
    };
    hooks.done = [](const SmoothRun& r) {
      std::printf("sweeps %zu (%s), quality %.6f -> %.6f, median %.3f ms/sweep, total %.3f s\n",
                  r.result.sweeps.size(), r.result.converged ? "converged" : "max-iters reached",
                  r.result.quality_before, r.result.quality_after, 1e3 * MedianSweepSeconds(r),
                  r.result.seconds);
      for (size_t e = 0; e < r.events.size(); ++e) {
        std::printf("counter %-16s %16s (all sweeps, all threads", r.events[e].c_str(),
                    Grouped(r.sums[e]).c_str());
        for (size_t t = 0; r.per_thread.size() > 1 && t < r.per_thread.size(); ++t)
          std::printf("; thread %zu %s", t, Grouped(r.per_thread[t][e]).c_str());
        std::printf(")\n");
      }
      std::printf("\n");
    };
  }
  const Progress progress(vm.count("quiet") > 0);
  const std::vector<SmoothRun> runs = RunSmooth(cfg, MakeLog(progress), hooks);
  Emit(SmoothOutput(runs, cfg, note), fmt, out_dir, progress);
  return 0;
}

}  // namespace meshreuse::cli
