// MeasureKernels; see kernel_runs.h.
#include "reports/kernel_runs.h"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <optional>

#include "analysis/cache_sim.h"
#include "analysis/line_quantiles.h"
#include "analysis/reuse_analysis.h"
#include "analysis/sweep_footprint.h"
#include "core/kernels/kernel.h"
#include "core/orderings/registry.h"
#include "reports/speedup.h"
#include "tracer/access_stream.h"

namespace meshreuse {

namespace {

double MedianOf(const SmoothResult& r, double SweepRecord::*field) {
  std::vector<double> v;
  for (const SweepRecord& s : r.sweeps) v.push_back(s.*field);
  return Median(v);
}

// The memory of a mesh's arrays.
uint64_t MeshBytes(const Mesh& m) {
  return 8 * uint64_t{m.xy.size()} + 4 * uint64_t{m.tri.size()} + uint64_t{m.boundary.size()} +
         8 * uint64_t{m.v2v.off.size() + m.v2t.off.size()} +
         4 * uint64_t{m.v2v.idx.size() + m.v2t.idx.size() + m.interior.size()};
}

// The last sweep's floor: the footprint's over every sweep less that of the sweeps before it (a
// sum over sweeps). lines: per thread, per sweep.
std::vector<uint64_t> LastSweepFloor(std::vector<std::vector<uint64_t>> lines,
                                     const KernelRunsConfig& cfg) {
  const std::vector<uint64_t> all_floor = MissFloor(lines, cfg.cache, cfg.line_bytes);
  for (auto& t : lines)
    if (!t.empty()) t.pop_back();
  const std::vector<uint64_t> before = MissFloor(lines, cfg.cache, cfg.line_bytes);
  std::vector<uint64_t> floor;
  for (size_t i = 0; i < all_floor.size(); ++i)
    floor.push_back(all_floor[i] - (i < before.size() ? before[i] : 0));
  return floor;
}

// The simulated part of a Laplacian run read from Table 3's validation of the same stream
// (KernelRunsConfig::laplacian); false where it does not have all of it (one thread's stream of
// traced_sweeps sweeps, both quantiles).
bool FromValidation(const KernelRunsConfig& cfg, const OrderingValidation& v, KernelRun* r) {
  if (v.threads != 1 || v.iterations != cfg.traced_sweeps || v.sweeps.empty() ||
      v.sweeps.size() != static_cast<size_t>(cfg.traced_sweeps) || v.sweeps.back().size() != 1 ||
      !v.line_q50 || !v.line_q90)
    return false;
  const std::vector<LevelStats>& last = v.sweeps.back()[0];
  r->accesses = last.empty() ? 0 : last[0].accesses;
  r->misses.clear();
  for (const LevelStats& s : last) r->misses.push_back(s.misses);
  r->floor = LastSweepFloor(v.sweep_lines, cfg);
  r->q50 = *v.line_q50, r->q90 = *v.line_q90;
  return true;
}

// The simulated part of one run: misses and floor of the last traced sweep, line quantiles. Each
// stream starts from a copy of the ordering's layout `laid` (a kernel changes its mesh), or where
// none is held (null), from the ordering applied to `base` afresh.
void Simulate(const KernelRunsConfig& cfg, const KernelInfo& k, const Mesh* laid, const Mesh& base,
              const Permutation& perm, KernelRun* r) {
  Mesh work;
  auto lay_out = [&] {
    if (laid)
      laid->CopyInto(&work);
    else
      ApplyPermutationInto(base, perm, cfg.triangle_order, &work);
  };
  lay_out();
  CacheSimulation sim(cfg.cache, cfg.line_bytes);
  SweepFootprint footprint(cfg.line_bytes);
  LineQuantiles quantiles(cfg.line_bytes, cfg.quantile_depth);
  FanOut all({&sim, &footprint, &quantiles});
  // None of the three reads the per-sweep counts: no counting run before; nor the qualities.
  SmoothOptions o = ExactSweeps(cfg.traced_sweeps);
  o.end_qualities = false;
  StreamMesh(work, o, r->mesh, r->ordering, all, &k, false);
  const std::vector<LevelStats> last = sim.SweepStats(0, sim.sweeps() - 1);
  r->accesses = last.empty() ? 0 : last[0].accesses;
  for (const LevelStats& s : last) r->misses.push_back(s.misses);
  r->floor = LastSweepFloor(footprint.lines(), cfg);
  const std::optional<uint64_t> q50 = quantiles.Quantile(0, 0.5), q90 = quantiles.Quantile(0, 0.9);
  if (q50 && q90) {
    r->q50 = *q50, r->q90 = *q90;
    return;
  }
  // A quantile at depth or beyond (or none): the same stream again, into the whole analysis.
  lay_out();
  ReuseOptions ro;
  ro.granularity = Granularity::kLine;
  ro.line_bytes = cfg.line_bytes;
  ro.profile = false;
  ReuseAnalysis reuse(ro);
  StreamMesh(work, ExactSweeps(cfg.traced_sweeps), r->mesh, r->ordering, reuse, &k, false);
  if (const StreamAnalysis* s = reuse.line(0)) {
    r->q50 = s->hist.Quantile(0.5);
    r->q90 = s->hist.Quantile(0.9);
  }
}

}  // namespace

void MeasureKernels(const KernelRunsConfig& cfg, const std::string& mesh, const Mesh& base,
                    std::vector<KernelRun>* out, const std::function<void(const std::string&)>& say,
                    PhaseTimes* phases) {
  // Each part's seconds into `phases`, inside the caller's phase.
  auto part = [phases](const char* name, auto&& f) {
    std::optional<PhaseTimes::Scope> t;
    if (phases) t.emplace(phases, name, "inside the one above");
    f();
  };
  const size_t first = out->size();
  std::vector<Permutation> perms;
  for (const std::string& o : cfg.orderings) perms.push_back(ComputeOrdering(o, base, cfg.seed));
  // Every ordering's layout, made once for the simulations and the timed rounds while they fit
  // cfg.held_bytes (else each simulation and round applies its ordering itself, one layout held
  // at a time): a copy is sequential where an apply gathers.
  const size_t no = cfg.orderings.size();
  const bool hold_layouts = MeshBytes(base) * no <= cfg.held_bytes;
  std::vector<Mesh> layouts(hold_layouts ? no : 1);  // else one, laid out by each round in turn
  if (hold_layouts)
    for (size_t o = 0; o < no; ++o)
      ApplyPermutationInto(base, perms[o], cfg.triangle_order, &layouts[o]);
  // The simulations, side by side on the host's cores (each job its own copy of the layout, stream
  // and simulators; results in job order, so nothing depends on the schedule).
  for (const std::string& kn : cfg.kernels)
    for (size_t o = 0; o < cfg.orderings.size(); ++o) {
      KernelRun r;
      r.mesh = mesh, r.kernel = kn, r.ordering = cfg.labels[o];
      r.time.mesh = mesh, r.time.ordering = cfg.labels[o];
      r.time.vertices = base.NumVertices(), r.time.triangles = base.NumTriangles();
      r.time.final_quality = NAN;  // known once timed
      out->push_back(std::move(r));
    }
  say("kernels: " + mesh + ", " + std::to_string(cfg.kernels.size()) + " kernels x " +
      std::to_string(cfg.orderings.size()) + " orderings x " + std::to_string(cfg.traced_sweeps) +
      " simulated sweeps");
  std::exception_ptr failed;
  part("other kernels: simulated", [&] {
    const int jobs = static_cast<int>(out->size() - first);
#pragma omp parallel for schedule(dynamic, 1) \
    num_threads(std::max(1, std::min(jobs, omp_get_max_threads())))
    for (int j = 0; j < jobs; ++j) {
      try {
        KernelRun& r = (*out)[first + j];
        const size_t o = static_cast<size_t>(j) % cfg.orderings.size();
        const KernelInfo& k = ParseKernel(r.kernel);
        const OrderingValidation* v = o < cfg.laplacian.size() ? cfg.laplacian[o] : nullptr;
        if (!(v && IsPaperSweep(k) && FromValidation(cfg, *v, &r)))
          Simulate(cfg, k, hold_layouts ? &layouts[o] : nullptr, base, perms[o], &r);
      } catch (...) {
#pragma omp critical(meshreuse_kernel_runs_failed)
        if (!failed) failed = std::current_exception();
      }
    }
  });
  if (failed) std::rethrow_exception(failed);
  if (!cfg.timing) return;
  part("other kernels: timed", [&] {
    // Round 0 warms up (untimed, warmup_sweeps sweeps a run of each kernel in the first
    // ordering: what a warm-up leaves is the process's state, the layout's and the working
    // mesh's pages and each kernel's code, the same whichever ordering; timings.md measured
    // it); then every ordering x kernel once per round. Each kernel's run starts from a copy of
    // its ordering's layout: a copy is sequential where applying the permutation gathers (on
    // lake, 375k vertices, an apply took 0.12-0.15 s, half of a smart-laplacian run's untimed
    // time). A kernel's set-up (PrepareKernel: edge-swap's jitter and triangle neighbours, the
    // stiffness pattern) is made from the layout. Both are the same every round, so they are made
    // once and kept for the rounds after, as long as what is kept fits cfg.held_bytes (the
    // layouts, made before the simulations, first; then set-ups as they come); what does not fit
    // is made again each round (one layout held at a time). On lake the six layouts hold about 245
    // MB and edge-swap's set-ups 90 MB; its set-ups, one a run, took 1.33 s and the applies 0.53 s
    // of the 10.4-s timed part.
    uint64_t held = hold_layouts ? MeshBytes(base) * no : 0;
    Mesh work;
    // Per kernel x ordering: its set-up (none yet, or none to share: nullptr) and whether it is
    // kept (fits the budget) or made again at every run.
    std::vector<std::unique_ptr<KernelSetup>> setups(cfg.kernels.size() * no);
    std::vector<bool> kept(setups.size(), false);
    for (int round = 0; round <= cfg.rounds; ++round) {
      say("kernels: " + mesh +
          (round == 0 ? ", warm-up round" : ", round " + std::to_string(round)) + " of " +
          std::to_string(cfg.rounds));
      for (size_t o = 0; o < (round == 0 ? 1 : no); ++o) {
        const size_t l = hold_layouts ? o : 0;
        Mesh& laid = layouts[l];
        if (!hold_layouts)  // (held ones were made above)
          ApplyPermutationInto(base, perms[o], cfg.triangle_order, &laid);
        for (size_t kk = 0; kk < cfg.kernels.size(); ++kk) {
          const size_t at = kk * cfg.orderings.size() + o;  // rows: kernel, then ordering
          const size_t i = first + at;
          const KernelInfo& k = ParseKernel(cfg.kernels[kk]);
          if (!setups[at]) {
            setups[at] = PrepareKernel(k, laid);
            const uint64_t bytes = setups[at] ? setups[at]->Bytes() : 0;
            kept[at] = held + bytes <= cfg.held_bytes;
            if (kept[at]) held += bytes;
          }
          laid.CopyInto(&work);
          SmoothOptions o =
              ExactSweeps(round == 0 ? std::min(cfg.sweeps, cfg.warmup_sweeps) : cfg.sweeps);
          o.adjacency_after = false;  // the next run copies the layout anew
          o.end_qualities = false;    // the final quality is the last sweep's
          o.setup = setups[at].get();
          const SmoothResult res = RunKernel(k, work, o);
          if (!kept[at]) setups[at].reset();
          if (round == 0) continue;
          CompareRound c;
          c.sweeps = static_cast<int>(res.sweeps.size());
          c.total_wall = res.seconds, c.total_cpu = res.cpu_seconds;
          c.sweep_wall = MedianOf(res, &SweepRecord::seconds);
          c.sweep_cpu = MedianOf(res, &SweepRecord::cpu_seconds);
          CompareRow& t = (*out)[i].time;
          if (round == 1) t.final_quality = res.sweeps.empty() ? NAN : res.sweeps.back().quality;
          t.rounds.push_back(c);
        }
      }
    }
  });
  for (size_t i = first; i < out->size(); ++i) {
    CompareRow& t = (*out)[i].time;
    const uint64_t s = cfg.seed + i;
    t.sweep = SpreadOf(t.Values(&CompareRound::sweep_wall), s);
    t.sweep_cpu = SpreadOf(t.Values(&CompareRound::sweep_cpu), s + 1);
    t.total = SpreadOf(t.Values(&CompareRound::total_wall), s + 2);
  }
  // Against ORI and BFS of the same kernel.
  for (size_t i = first; i < out->size(); ++i) {
    KernelRun& r = (*out)[i];
    const CompareRow *ori = nullptr, *bfs = nullptr;
    for (size_t j = first; j < out->size(); ++j) {
      const KernelRun& x = (*out)[j];
      if (x.kernel != r.kernel) continue;
      if (x.ordering == "ori") ori = &x.time;
      if (x.ordering == "bfs") bfs = &x.time;
    }
    r.time.speedup_vs_ori1 = Speedup(ori, &r.time, cfg.seed + i, cfg.clock);
    r.time.gain_vs_bfs = Gain(bfs, &r.time, cfg.seed + i, cfg.clock);
  }
}

}  // namespace meshreuse
