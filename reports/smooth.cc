// The smooth runner; see smooth.h.
#include "reports/smooth.h"

#include <omp.h>

#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/schedule.h"
#include "core/visit_order.h"
#include "reports/compare.h"
#include "reports/inputs.h"
#include "reports/run_info.h"

namespace meshreuse {

void CheckSmoothConfig(const SmoothConfig& cfg) {
  if (cfg.meshes.empty()) throw UsageError("no mesh given");
  CheckOrderingSpec(cfg.ordering);
  if (cfg.smooth.threads < 1 || cfg.smooth.threads > kMaxThreads)
    throw UsageError("--threads must be 1.." + std::to_string(kMaxThreads));
  if (cfg.smooth.max_iters < 1) throw UsageError("--max-iters must be at least 1");
  if (std::isnan(cfg.smooth.tol))
    throw UsageError("--tol must be a number (negative: never stop early)");
  if (!cfg.output.empty() && cfg.meshes.size() != 1)
    throw UsageError("-o takes a single input mesh");
  if (!cfg.counter_events.empty() && cfg.meshes.size() != 1)
    throw UsageError("--counters takes a single input mesh");
  if (!cfg.visit_order.empty() && cfg.meshes.size() != 1)
    throw UsageError("--visit-order takes a single input mesh");
  if (!cfg.visit_order.empty() && ParseOrderingSpec(cfg.ordering).name != "ori")
    throw UsageError("--visit-order names vertices by the mesh's own ids: it takes --ordering ori");
  const KernelInfo& k = ParseKernel(cfg.kernel);
  CheckKernelOptions(k, cfg.smooth);
  if (!IsPaperSweep(k) && !cfg.visit_order.empty())
    throw UsageError("--visit-order takes --kernel laplacian");
  if (!k.moves && !cfg.output.empty())
    throw UsageError("--kernel " + cfg.kernel + " moves no vertex: no -o with it");
}

std::vector<SmoothRun> RunSmooth(const SmoothConfig& cfg, const Log& log,
                                 const SmoothHooks& hooks) {
  CheckSmoothConfig(cfg);
  SmoothOptions opt = cfg.smooth;
  std::unique_ptr<PapiCounters> papi;
  if (!cfg.counter_events.empty()) {
    papi = std::make_unique<PapiCounters>(cfg.counter_events, opt.threads);
    if (papi->available()) opt.region = papi.get();
  }
  const std::string label = ParseOrderingSpec(cfg.ordering).label;
  std::vector<SmoothRun> runs;
  for (const std::string& path : cfg.meshes) {
    SmoothRun run;
    run.mesh = path, run.ordering = label;
    run.threads = opt.threads, run.mode = opt.mode, run.kernel = cfg.kernel;
    Mesh m = LoadMesh(path, log);
    if (ParseOrderingSpec(cfg.ordering).name != "ori" ||
        cfg.triangle_order == TriangleOrder::kSorted) {
      log.Say("laying out in " + cfg.ordering + " order, triangles " +
              TriangleOrderName(cfg.triangle_order));
      const auto t0 = std::chrono::steady_clock::now();
      ApplyPermutationInPlace(&m, ComputeOrdering(cfg.ordering, m, cfg.seed), cfg.triangle_order);
      run.reorder_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (!cfg.visit_order.empty()) m.interior = ReadVisitOrder(cfg.visit_order, m);
    run.vertices = m.NumVertices(), run.triangles = m.NumTriangles();
    if (hooks.start) hooks.start(run);
    const KernelInfo& kernel = ParseKernel(cfg.kernel);
    if (IsPaperSweep(kernel)) {
      log.Say("smoothing " + path);
      NullSink untraced;
      run.result = Smooth(m, opt, untraced,
                          hooks.sweep ? hooks.sweep : std::function<void(const SweepRecord&)>());
    } else {
      log.Say("running " + cfg.kernel + " on " + path);
      SmoothOptions each = opt;
      each.on_sweep = &hooks.sweep;  // each sweep's line as it ends, as the Laplacian's
      run.result = RunKernel(kernel, m, each);
    }
    if (papi && papi->available()) {
      if (!papi->error().empty()) throw std::runtime_error("counters failed: " + papi->error());
      run.events = papi->events();
      run.sums = papi->Sum();
      run.per_thread = papi->per_thread();
    }
    if (!cfg.output.empty())
      for (const std::string& f : SaveMesh(m, cfg.output, log)) {
        log.Say("wrote " + f);
        run.written.push_back(f);
      }
    if (hooks.done) hooks.done(run);
    runs.push_back(std::move(run));
  }
  return runs;
}

double MedianSweepSeconds(const SmoothRun& r) {
  std::vector<double> t;
  for (const SweepRecord& s : r.result.sweeps) t.push_back(s.seconds);
  return Median(t);
}

Table SmoothSummaryTable(const std::vector<SmoothRun>& runs) {
  Table t({"mesh", "ordering", "vertices", "triangles", "threads", "mode", "sweeps", "converged",
           "quality_before", "quality_after", "reorder_ms", "median_ms_per_sweep", "total_s"});
  for (const SmoothRun& r : runs)
    t.AddRow({r.mesh, r.ordering, std::to_string(r.vertices), std::to_string(r.triangles),
              std::to_string(r.threads), UpdateModeName(r.mode),
              std::to_string(r.result.sweeps.size()), r.result.converged ? "yes" : "no",
              Fixed(r.result.quality_before, 6), Fixed(r.result.quality_after, 6),
              Fixed(1e3 * r.reorder_seconds, 3), Fixed(1e3 * MedianSweepSeconds(r), 3),
              Fixed(r.result.seconds, 3)});
  return t;
}

Table SmoothSweepTable(const std::vector<SmoothRun>& runs) {
  Table t({"mesh", "sweep", "quality", "improvement", "ms"});
  for (const SmoothRun& r : runs)
    for (const SweepRecord& s : r.result.sweeps)
      t.AddRow({r.mesh, std::to_string(s.sweep), ExactNumber(s.quality), ExactNumber(s.improvement),
                ExactNumber(1e3 * s.seconds)});
  return t;
}

Json SmoothResultsJson(const std::vector<SmoothRun>& runs) {
  Json a = Json::array();
  for (const SmoothRun& r : runs) {
    Json j;
    j["mesh"] = r.mesh;
    j["ordering"] = r.ordering;
    j["kernel"] = r.kernel;
    j["vertices"] = r.vertices;
    j["triangles"] = r.triangles;
    j["sweeps"] = r.result.sweeps.size();
    j["converged"] = r.result.converged;
    j["quality_before"] = r.result.quality_before;
    j["quality_after"] = r.result.quality_after;
    j["reorder_seconds"] = r.reorder_seconds;
    j["median_seconds_per_sweep"] = MedianSweepSeconds(r);
    j["total_seconds"] = r.result.seconds;
    if (r.events.empty()) {
      j["counters"] = nullptr;
    } else {
      Json c;
      for (size_t e = 0; e < r.events.size(); ++e) {
        std::vector<long long> th;
        for (const auto& t : r.per_thread) th.push_back(t[e]);
        c[r.events[e]] = {{"sum", r.sums[e]}, {"per_thread", th}};
      }
      j["counters"] = c;
    }
    a.push_back(std::move(j));
  }
  return a;
}

Json SmoothConfigJson(const SmoothConfig& cfg, const CounterNote& counters) {
  Json j;
  j["meshes"] = cfg.meshes;
  j["ordering"] = cfg.ordering;
  j["kernel"] = cfg.kernel;
  j["seed"] = cfg.seed;
  j["ordering_seeds"] = OrderingSeedsJson({cfg.ordering}, cfg.seed);
  j["triangle_order"] = TriangleOrderName(cfg.triangle_order);
  j["counters"] = cfg.counter_events.empty() ? Json(nullptr)
                                             : Json{{"events", cfg.counter_events},
                                                    {"version", PapiCounters::Version()},
                                                    {"recorded", counters.available},
                                                    {"note", counters.note}};
  j["threads"] = cfg.smooth.threads;
  j["mode"] = UpdateModeName(cfg.smooth.mode);
  j["quality"] = QualityModeName(cfg.smooth.quality);
  j["tol"] = cfg.smooth.tol;
  j["max_iters"] = cfg.smooth.max_iters;
  j["omp_max_threads"] = omp_get_max_threads();
  return j;
}

RunOutput SmoothOutput(const std::vector<SmoothRun>& runs, const SmoothConfig& cfg,
                       const CounterNote& counters) {
  RunOutput o;
  o.tool = "meshreuse smooth";
  const RunOutput::TablePtr summary = RunOutput::Share(SmoothSummaryTable(runs)),
                            sweeps = RunOutput::Share(SmoothSweepTable(runs));
  if (runs.size() > 1) o.text.emplace_back(summary);
  o.json = Json({{"results", SmoothResultsJson(runs)}, {"sweeps", sweeps->JsonValue()}});
  o.csv = sweeps;
  o.tables = {{"summary", summary, {"csv", "md"}}, {"sweeps", sweeps, {"csv"}}};
  o.configuration = SmoothConfigJson(cfg, counters);
  o.extra = {{"results", SmoothResultsJson(runs)}};
  return o;
}

}  // namespace meshreuse
