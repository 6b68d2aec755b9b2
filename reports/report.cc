// The paper's experiment as one run; see report.h. Measuring (a mesh at a time, then the timing)
// fills a ReportData; then report_files.h writes every output of report_list.h, run.json, the
// manifest and the results README from it.
#include "reports/report.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <mutex>
#include <set>

#include "analysis/machine.h"
#include "analysis/multicore_sim.h"
#include "analysis/papi_counters.h"
#include "analysis/reuse_analysis.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/schedule.h"
#include "core/smoother.h"
#include "reports/inputs.h"
#include "reports/output.h"
#include "reports/paper.h"
#include "reports/phase_times.h"
#include "reports/pictures.h"
#include "reports/report_files.h"
#include "reports/report_outputs.h"
#include "reports/run_info.h"
#include "tracer/access_stream.h"

namespace meshreuse {

namespace {

using Clock = std::chrono::steady_clock;

// An ordering spec for one mesh: "{mesh}" in it (file:perms/{mesh}.perm) becomes the mesh's
// name, so one spec names a permutation file per mesh.
std::string ForMesh(const std::string& spec, const std::string& mesh) {
  std::string s = spec;
  for (size_t at; (at = s.find("{mesh}")) != std::string::npos;) s.replace(at, 6, mesh);
  return s;
}

bool Contains(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

// Progress with the elapsed time and an estimate of what remains, from work units done so far.
// Units: file bytes x the wall seconds a kind of work takes, in timed sweeps of the same mesh
// (one core). The CPU costs, from the full run's phases (the nine paper meshes, the 2-core Xeon
// VM, 2026-12-05: a timed sweep 11 ms on carabiner): a reuse-distance job (one traced sweep into
// the exact stack, the layout, the stream) 36 sweeps, each profile sweep 22; Table 3's simulation
// 100 a traced sweep; a many-core simulation 34 + 0.66 p a sweep and placement at p threads (more
// caches to keep coherent: a job took 1.5 CPU seconds at one thread, with the prefetcher's
// simulation beside the compact one, and 2.4 at 32, on carabiner); a kernel's simulated run
// 43 a traced sweep, a kernel's timed sweep 2.7 (its set-up, copy and layout included: 50 and 3
// before the kernels part took 151 s instead of 171, 2026-12-05's second full run); a timed run
// of the Laplacian to convergence 95 (65 sweeps, its warm-up, ordering and layout, and a second
// thread's sweep worth more than half). The jobs that run side by side count their CPU over the
// host's cores. The same units order the pool's jobs, the costliest first. (Before, the estimate
// counted the kernels' timed sweeps 30 each and the timed runs 65 sweeps: in the first minutes of
// that full run it said 11 to 28 minutes were left of 9.)
class Steps {
 public:
  static constexpr double kFirstSweep = 36, kProfileSweep = 22, kSimulation = 100, kMachine = 34,
                          kMachinePerThread = 0.66, kKernelTraced = 43, kKernelSweep = 2.7,
                          kTimedRun = 95;
  Steps(const Log& log, const ReportConfig& cfg, const std::vector<ReportMesh>& meshes)
      : log_(log), cfg_(cfg), t0_(Clock::now()), cores_(std::max(1, omp_get_max_threads())) {
    const double no = static_cast<double>(cfg.orderings.size());
    for (const ReportMesh& m : meshes) {
      total_ += no * (Reuse(m) + Table3(m));
      if (m.name == cfg.profile_mesh) total_ += no * Profile(m);
      if (m.name == cfg.figure1_mesh)
        for (const std::string& o : cfg.figure1_orderings)
          if (!Contains(cfg.orderings, o)) total_ += Reuse(m);
      if (cfg.timing) total_ += Timed(m);
      total_ += Kernels(m);
      if (!cfg.machine.empty())
        for (int p : cfg.machine_threads) total_ += no * Machine(m, p);
    }
  }
  // The units of each kind of work on mesh m (an ordering's, where it is done per ordering).
  double Reuse(const ReportMesh& m) const { return m.weight * kFirstSweep / cores_; }
  double Profile(const ReportMesh& m) const {
    return m.weight * kProfileSweep * cfg_.profile_sweeps / cores_;
  }
  double Table3(const ReportMesh& m) const {
    return m.weight * kSimulation * cfg_.validate_sweeps / cores_;
  }
  // A many-core job at p threads: both placements, at one thread the compact one and the
  // prefetcher's (where it has levels).
  static size_t MachineSimulations(const ReportConfig& cfg, int p) {
    return p > 1 || !cfg.prefetch_levels.empty() ? 2 : 1;
  }
  double Machine(const ReportMesh& m, int p) const {
    return m.weight * (kMachine + kMachinePerThread * p) * cfg_.machine_sweeps *
           static_cast<double>(MachineSimulations(cfg_, p)) / cores_;
  }
  double Timed(const ReportMesh& m) const {  // every ordering on every thread count
    double p_sum = 0;
    for (int p : cfg_.threads) p_sum += 1.0 / p;
    return m.weight * static_cast<double>(cfg_.orderings.size()) * cfg_.repeat * kTimedRun * p_sum;
  }
  // The kernels part: simulated (but the Laplacian in an ordering Table 3 traced: read from
  // there) and timed.
  double Kernels(const ReportMesh& m) const {
    const double runs = static_cast<double>(cfg_.kernels.size() * cfg_.kernel_orderings.size());
    double simulated = runs;
    if (Contains(cfg_.kernels, kPaperKernel))
      for (const std::string& o : cfg_.kernel_orderings) simulated -= Contains(cfg_.orderings, o);
    return m.weight *
           (simulated * cfg_.validate_sweeps * kKernelTraced / cores_ +
            (cfg_.timing ? runs * (cfg_.repeat + 1) * cfg_.kernel_sweeps * kKernelSweep : 0));
  }
  // Say and Done may be called from the jobs that run side by side.
  void Say(const std::string& what) const {
    const std::lock_guard<std::mutex> hold(lock_);
    const double el = std::chrono::duration<double>(Clock::now() - t0_).count();
    std::string left = "?";
    if (done_ > 0 && done_ < total_) left = Duration(el / done_ * (total_ - done_));
    if (done_ >= total_) left = "0s";
    log_.Say(what + " [" + Duration(el) + " elapsed, ~" + left + " left]");
  }
  void Done(double units) {
    const std::lock_guard<std::mutex> hold(lock_);
    done_ += units;
  }

 private:
  const Log& log_;
  const ReportConfig& cfg_;
  Clock::time_point t0_;
  double cores_;
  double total_ = 0, done_ = 0;
  mutable std::mutex lock_;
};

// The element stream of one traced sweep into an exact stack; every distance in order too when
// Figure 1 needs it.
class FirstSweepConsumer : public AccessConsumer {
 public:
  static constexpr uint32_t kColdMark = std::numeric_limits<uint32_t>::max();
  FirstSweepConsumer(int64_t vertices, std::vector<uint32_t>* series)
      : a_(static_cast<uint64_t>(vertices)), series_(series) {}
  void Begin(const StreamInfo&) override {}
  void Consume(const Access* a, size_t n) override {
    for (size_t i = 0; i < n; ++i) {
      if (a[i].element == Access::kNoElement) continue;
      const uint64_t d = a_.AddExact(a[i].element);
      if (series_) series_->push_back(d == StackDistance::kCold ? kColdMark : uint32_t(d));
    }
  }
  ReuseHistogram& hist() { return a_.hist; }

 private:
  StreamAnalysis a_;
  std::vector<uint32_t>* series_;
};

Figure1Data BinFigure1(const std::string& ordering, const ReuseHistogram& h,
                       const std::vector<uint32_t>& series, int32_t vertices,
                       const ReportConfig& cfg) {
  Figure1Data f;
  f.ordering = ordering;
  f.accesses = series.size();
  f.cold = h.cold();
  f.mean = h.mean();
  const uint64_t c1 = cfg.cache.levels[0].bytes / cfg.element_bytes;
  f.model_l1_rate = report::Ratio(static_cast<double>(h.cold() + h.CountAtLeast(c1)),
                                  static_cast<double>(h.accesses()));
  const int tb = cfg.figure1_time_bins;
  const int db = report::DistanceBin(std::max<uint64_t>(1, static_cast<uint64_t>(vertices))) + 2;
  f.bins.assign(tb, std::vector<uint64_t>(db, 0));
  for (size_t i = 0; i < series.size(); ++i) {
    const size_t t = static_cast<size_t>((static_cast<unsigned __int128>(i) * tb) / series.size());
    const uint32_t d = series[i];
    ++f.bins[t][d == FirstSweepConsumer::kColdMark ? db - 1 : report::DistanceBin(d)];
  }
  return f;
}

// What MeasureReuse adds to the report's data for one ordering, kept apart while the mesh's jobs
// run side by side and added in ordering order after them (ReportData's fields of the same names).
struct ReusePart {
  Table positions = OrderPositionsTable(), profile{ReuseAnalysis::ProfileColumns()},
        histogram{ReuseAnalysis::HistogramColumns()};
  std::vector<Figure1Data> fig1;
  std::vector<FirstSweep> first;
};

// Table 2's histogram (and Figure 1's bins) of one ordering, and the profile on the profile mesh.
void MeasureReuse(const ReportConfig& cfg, const ReportMesh& mr, const Mesh& base,
                  const std::string& spec, const std::string& label, bool in_tables, ReusePart* d,
                  Steps& steps) {
  const bool in_fig1 = mr.name == cfg.figure1_mesh && Contains(cfg.figure1_orderings, spec);
  steps.Say("reuse distances: " + mr.name + " " + label + ", first sweep");
  const Permutation p = ComputeOrdering(ForMesh(spec, mr.name), base, cfg.seed);
  if (in_tables && mr.name == cfg.figure1_mesh)  // the ordering as a picture, on one mesh
    AppendOrderPositions(mr.name, label, base, p, &d->positions);
  Mesh m = ApplyPermutation(base, p, cfg.triangle_order);
  const bool profile = in_tables && mr.name == cfg.profile_mesh;
  Mesh start;  // the laid-out mesh before the sweep, for the profile's run
  if (profile) start = m.Clone();
  std::vector<uint32_t> series;
  FirstSweepConsumer first(mr.vertices, in_fig1 ? &series : nullptr);
  StreamMesh(m, ExactSweeps(1), mr.name, label, first);
  steps.Done(steps.Reuse(mr));
  if (in_fig1) d->fig1.push_back(BinFigure1(label, first.hist(), series, mr.vertices, cfg));
  if (profile) {
    steps.Say("reuse-distance profile: " + mr.name + " " + label + ", " +
              std::to_string(cfg.profile_sweeps) + " sweeps");
    ReuseOptions o;
    o.granularity = Granularity::kElement;
    ReuseAnalysis a(o);
    StreamMesh(start, ExactSweeps(cfg.profile_sweeps), mr.name, label, a);
    a.AppendProfileRows(&d->profile);
    steps.Done(steps.Profile(mr));
  }
  if (in_tables) {
    first.hist().AppendRows(&d->histogram, {mr.name, label, "0", "element"});
    d->first.push_back({mr.name, label, mr.vertices, std::move(first.hist())});
  }
}

// One of a mesh's simulation jobs, run side by side with the others on the host's cores; `cost`
// (its Steps units) orders them (the longest first, so that the last to finish is a short one).
struct Job {
  double cost;
  std::function<void()> run;
};

// Runs `jobs` side by side, a job a thread at a time, the costliest first (ties in the order
// given); every job writes its own results, so nothing depends on the schedule. The first
// exception is rethrown after all have ended. `threads` 1: one after another.
void RunJobs(std::vector<Job> jobs, int threads) {
  std::stable_sort(jobs.begin(), jobs.end(),
                   [](const Job& x, const Job& y) { return x.cost > y.cost; });
  std::exception_ptr failed;
  const int n = static_cast<int>(jobs.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(1, std::min(n, threads)))
  for (int i = 0; i < n; ++i) {
    try {
      jobs[i].run();
    } catch (...) {
#pragma omp critical(meshreuse_report_failed)
      if (!failed) failed = std::current_exception();
    }
  }
  if (failed) std::rethrow_exception(failed);
}

// A job's wall and thread CPU seconds into `phases` under `name`, inside the one above.
class JobTime {
 public:
  JobTime(PhaseTimes* phases, std::string name)
      : phases_(phases), name_(std::move(name)), w0_(Clock::now()), c0_(ThreadCpuSeconds()) {}
  ~JobTime() {
    const double wall = std::chrono::duration<double>(Clock::now() - w0_).count();
    const double cpu = ThreadCpuSeconds() - c0_;
#pragma omp critical(meshreuse_report_phases)
    phases_->Add(name_, wall, cpu, "inside the one above");
  }

 private:
  PhaseTimes* phases_;
  std::string name_;
  Clock::time_point w0_;
  double c0_;
};

// The many-core part's jobs for one mesh: every ordering at every thread count, both placements
// fed from one stream; at one thread also with the prefetcher (a third simulation, yet the
// cheapest job: one core's caches). Each job its own stream and simulators, on its own copy of
// the ordering's layout (`laid`, which must outlive the jobs); results into `runs`, by ordering *
// counts + count.
void MachineJobs(const ReportConfig& cfg, const ReportMesh& mr, const ReportData& d,
                 const std::vector<Mesh>& laid, std::vector<std::vector<MachineRun>>* runs,
                 Steps& steps, PhaseTimes* phases, std::vector<Job>* jobs) {
  const Machine machine = ParseMachine(cfg.machine);
  Machine prefetching = machine;
  SetPrefetch(&prefetching, cfg.prefetch_levels);
  const int counts = static_cast<int>(cfg.machine_threads.size());
  runs->assign(laid.size() * counts, {});
  for (size_t k = 0; k < laid.size(); ++k)
    for (int j = 0; j < counts; ++j) {
      const int threads = cfg.machine_threads[j];
      jobs->push_back({steps.Machine(mr, threads), [&cfg, &mr, &d, &laid, &steps, runs, phases, k,
                                                    j, counts, threads, machine, prefetching] {
                         const JobTime time(phases, "many-core simulation, " +
                                                        std::to_string(threads) + " thread(s)");
                         const std::string& label = d.orderings[k];
                         steps.Say("many-core simulation: " + mr.name + " " + label + ", " +
                                   std::to_string(threads) + " thread(s) on " + machine.name);
                         SmoothOptions o = ExactSweeps(cfg.machine_sweeps);
                         o.threads = threads;
                         o.interleave = 1;
                         o.end_qualities = false;
                         MulticoreSimulation compact(machine, Placement::kCompact),
                             scatter(machine, Placement::kScatter),
                             pre(prefetching, Placement::kCompact);
                         std::vector<AccessConsumer*> to = {&compact};
                         if (threads > 1) to.push_back(&scatter);
                         if (threads == 1 && !cfg.prefetch_levels.empty()) to.push_back(&pre);
                         FanOut all(to);
                         Mesh m = laid[k].Clone();
                         StreamMesh(m, o, mr.name, label, all);
                         std::vector<MachineRun>& r = (*runs)[k * counts + j];
                         r.push_back(CollectMachineRun(compact, mr.name, label, false));
                         if (threads > 1)
                           r.push_back(CollectMachineRun(scatter, mr.name, label, false));
                         if (threads == 1 && !cfg.prefetch_levels.empty())
                           r.push_back(CollectMachineRun(pre, mr.name, label, true));
                         steps.Done(steps.Machine(mr, threads));
                       }});
    }
}

// Everything but the timing, for one mesh: Table 1's counts, the reuse analyses (Table 2, Figure
// 1, the profile), Table 3's simulations and the many-core part, their jobs side by side on the
// host's cores (one pool: a part of few jobs leaves no core idle while another has jobs left),
// each job writing its own results, added to `d` in ordering order after them. Where a counter
// will count, Table 3's jobs run after the pool, one at a time: its untimed run wants the
// machine to itself. Every ordering's layout is in memory for the many-core jobs.
void MeasureMesh(const ReportConfig& cfg, ReportMesh& mr, ReportData* d, Steps& steps,
                 const Log& log, PhaseTimes* phases) {
  const Mesh base = [&] {
    const PhaseTimes::Scope t = phases->Time("reading the meshes");
    return LoadMesh(mr.path, log);
  }();
  mr.vertices = base.NumVertices(), mr.triangles = base.NumTriangles();
  mr.interior = static_cast<int32_t>(base.interior.size());
  AppendMeshDrawing(mr.name, base, &d->drawing);
  if (mr.name == cfg.figure1_mesh) {
    const PhaseTimes::Scope t = phases->Time("smoothing picture");
    steps.Say("smoothing picture: " + mr.name);
    AppendSmoothingWindow(mr.name, base, cfg.smooth, &d->smoothing);
  }
  const PhaseTimes::Scope whole = phases->Time("simulations (reuse distances, misses, many-core)");
  std::vector<Job> jobs;
  // Table 2, Figure 1 and the profile: an ordering a job.
  std::vector<std::string> specs = cfg.orderings;
  if (mr.name == cfg.figure1_mesh)
    for (const std::string& o : cfg.figure1_orderings)
      if (!Contains(specs, o)) specs.push_back(o);
  std::vector<ReusePart> reuse(specs.size());
  for (size_t i = 0; i < specs.size(); ++i) {
    const bool profile = mr.name == cfg.profile_mesh && Contains(cfg.orderings, specs[i]);
    jobs.push_back({steps.Reuse(mr) + (profile ? steps.Profile(mr) : 0), [&, i] {
                      const JobTime time(phases, "reuse distances (Table 2, Figure 1, profiles)");
                      const bool in_tables = Contains(cfg.orderings, specs[i]);
                      MeasureReuse(cfg, mr, base, specs[i], ParseOrderingSpec(specs[i]).label,
                                   in_tables, &reuse[i], steps);
                    }});
  }
  // Table 3: an ordering a job, or after the pool where a counter counts. Where none can, the
  // jobs do not ask PAPI again (its calls are not made thread-safe here) and say what an
  // unavailable PAPI says.
  ValidationConfig vc;
  vc.inputs = {mr.path};
  vc.mesh_name = mr.name;
  vc.seed = cfg.seed;
  vc.iterations = cfg.validate_sweeps;
  vc.triangle_order = cfg.triangle_order;
  vc.cache = cfg.cache;
  vc.element_bytes = cfg.element_bytes, vc.line_bytes = cfg.line_bytes;
  vc.counter_events = cfg.counter_events;
  const bool counting = !cfg.counter_events.empty() && ProbeCounters(cfg.counter_events).available;
  if (!counting) vc.counter_events.clear();
  std::vector<OrderingValidation> validation(cfg.orderings.size());
  std::vector<Job> table3;
  for (size_t k = 0; k < cfg.orderings.size(); ++k)
    table3.push_back({steps.Table3(mr), [&, k] {
                        const JobTime time(phases, "misses (Table 3: the simulator, the model)");
                        ValidationConfig one = vc;
                        one.orderings = {ForMesh(cfg.orderings[k], mr.name)};
                        std::vector<OrderingValidation> vs =
                            RunValidation(base, one, [&](const std::string& s) { steps.Say(s); });
                        vs[0].ordering = d->orderings[k];
                        if (!counting && !cfg.counter_events.empty()) vs[0].counters = "simulated";
                        validation[k] = std::move(vs[0]);
                        steps.Done(steps.Table3(mr));
                      }});
  steps.Say("misses (Table 3): " + mr.name + ", " + std::to_string(cfg.orderings.size()) +
            " orderings x " + std::to_string(cfg.validate_sweeps) + " traced sweeps" +
            (counting ? " (after the other simulations: counters count)" : ""));
  if (!counting) jobs.insert(jobs.end(), table3.begin(), table3.end());
  // The many-core part.
  std::vector<Mesh> laid;
  std::vector<std::vector<MachineRun>> machine;
  if (!cfg.machine.empty()) {
    for (const std::string& o : cfg.orderings)
      laid.push_back(ApplyPermutation(base, ComputeOrdering(ForMesh(o, mr.name), base, cfg.seed),
                                      cfg.triangle_order));
    MachineJobs(cfg, mr, *d, laid, &machine, steps, phases, &jobs);
  }
  // The kinds of job listed in this order, whichever finishes first.
  phases->Add("reuse distances (Table 2, Figure 1, profiles)", 0, 0, "inside the one above");
  phases->Add("misses (Table 3: the simulator, the model)", 0, 0, "inside the one above");
  if (!cfg.machine.empty())
    for (int p : cfg.machine_threads)
      phases->Add("many-core simulation, " + std::to_string(p) + " thread(s)", 0, 0,
                  "inside the one above");
  RunJobs(std::move(jobs), omp_get_max_threads());
  if (counting) RunJobs(std::move(table3), 1);
  for (ReusePart& r : reuse) {
    d->positions.Append(r.positions);
    d->profile.Append(r.profile);
    d->histogram.Append(r.histogram);
    for (Figure1Data& f : r.fig1) d->fig1.push_back(std::move(f));
    for (FirstSweep& f : r.first) d->first.push_back(std::move(f));
  }
  for (OrderingValidation& v : validation) d->validation.push_back(std::move(v));
  for (std::vector<MachineRun>& r : machine)
    for (MachineRun& x : r) d->machine.push_back(std::move(x));
}

// One run's noise into the report's: the loads at the first start and the last end, the lowest
// CPU/wall and the highest CV of any.
void Absorb(const Noise& n, Noise* into) {
  into->cores = n.cores;
  if (!std::isfinite(into->load_before)) into->load_before = n.load_before;
  into->load_after = n.load_after;
  if (std::isfinite(n.cpu_per_wall) && !(into->cpu_per_wall <= n.cpu_per_wall))
    into->cpu_per_wall = n.cpu_per_wall;
  if (std::isfinite(n.cv) && !(into->cv >= n.cv)) into->cv = n.cv;
}

// RunCompare a mesh at a time (each mesh's orderings may name its own permutation file), rows
// labelled as configured; then Figure 1's other orderings on its mesh, one thread.
void MeasureTiming(const ReportConfig& cfg, ReportData* d, Steps& steps) {
  CompareConfig cc;
  static_cast<TimingOptions&>(cc) = cfg;
  cc.seed = cfg.seed;
  for (size_t mi = 0; mi < d->meshes.size(); ++mi) {
    const ReportMesh& m = d->meshes[mi];
    cc.meshes = {m.path};
    cc.orderings.clear();
    std::vector<std::string> labels;
    for (const std::string& o : cfg.orderings) {
      cc.orderings.push_back(ForMesh(o, m.name));
      labels.push_back(ParseOrderingSpec(cc.orderings.back()).label);
    }
    const std::string where = "timing [" + std::to_string(mi + 1) + "/" +
                              std::to_string(d->meshes.size()) + "] " + m.name + ": ";
    CompareResult got = RunCompare(cc, [&](const std::string& s) { steps.Say(where + s); }, {});
    Absorb(got.noise, &d->noise);
    for (const RepeatAutoEnd& e : got.repeat_auto)
      if (!e.settled) d->notes.push_back(e.Sentence(cfg.repeat_cap));
    for (CompareRow& r : got.rows) {
      const size_t k = std::find(labels.begin(), labels.end(), r.ordering) - labels.begin();
      if (k < d->orderings.size()) r.ordering = d->orderings[k];
      d->timing.push_back(std::move(r));
    }
    steps.Done(steps.Timed(m));
  }
  const ReportMesh* fig1 = d->Mesh(cfg.figure1_mesh);
  std::vector<std::string> extra;
  for (const std::string& o : cfg.figure1_orderings)
    if (!Contains(cfg.orderings, o)) extra.push_back(o);
  if (fig1 && !extra.empty()) {
    CompareConfig fc = cc;
    fc.meshes = {fig1->path};
    fc.orderings.clear();
    for (const std::string& o : extra) fc.orderings.push_back(ForMesh(o, fig1->name));
    fc.threads = {1};
    steps.Say("timing Figure 1's other orderings on " + fig1->name);
    CompareResult got = RunCompare(fc, {}, {});
    Absorb(got.noise, &d->noise);
    for (CompareRow& r : got.rows) d->timing.push_back(std::move(r));
  }
}

// "simulated (why)" or "measured (PAPI ...)", from the validation runs.
void CounterSources(const ReportConfig& cfg, ReportData* d) {
  d->counters = "simulated";
  for (const OrderingValidation& v : d->validation)
    for (const LevelValidation& l : v.levels) {
      d->sources[l.level.name] = l.measured ? "measured" : "simulated";
      if (l.measured) d->counters = v.counters;
    }
  if (d->counters == "simulated")
    d->counters += cfg.counter_events.empty() ? std::string(" (no counters asked for)")
                                              : " (" + ProbeCounters(cfg.counter_events).note + ")";
}

}  // namespace

void CheckReportConfig(const ReportConfig& cfg) {
  if (cfg.meshes.empty()) throw UsageError("no mesh given");
  if (cfg.orderings.empty()) throw UsageError("no ordering given");
  for (const std::string& m : cfg.meshes) {
    const std::string name = MeshShortName(m);
    for (const std::string& o : cfg.orderings) {
      const OrderingSpec s = ParseOrderingSpec(ForMesh(o, name));
      if (s.name == "file" && !std::filesystem::is_regular_file(s.argument))
        throw UsageError("ordering " + o + ": no permutation file '" + s.argument + "' for mesh " +
                         name);
    }
    for (const std::string& o : cfg.figure1_orderings) CheckOrderingSpec(ForMesh(o, name));
  }
  std::set<std::string> names, labels;
  for (const std::string& m : cfg.meshes)
    if (!names.insert(MeshShortName(m)).second)
      throw UsageError("two meshes are named '" + MeshShortName(m) +
                       "': the tables name meshes by their file's stem");
  for (const std::string& o : cfg.orderings)
    if (!labels.insert(ParseOrderingSpec(o).label).second)
      throw UsageError("two orderings are labelled '" + ParseOrderingSpec(o).label + "'");
  if (!cfg.measured.empty()) {
    if (cfg.machine.empty())
      throw UsageError(
          "--measured draws speedups beside the many-core prediction: not with "
          "--machine none");
    ReadMeasured(cfg.measured);  // a bad file refused before any work
  }
  if (cfg.threads.empty()) throw UsageError("no thread count given");
  for (int p : cfg.threads)
    if (p < 1 || p > kMaxThreads)
      throw UsageError("thread counts must be 1.." + std::to_string(kMaxThreads));
  if (cfg.repeat < 1 || cfg.repeat > 1000) throw UsageError("repeat must be 1..1000");
  cfg.CheckWarmup();
  if (cfg.validate_sweeps < 1 || cfg.validate_sweeps > 1000)
    throw UsageError("validation sweeps must be 1..1000");
  if (!cfg.machine.empty()) {
    Machine m = ParseMachine(cfg.machine);
    SetPrefetch(&m, cfg.prefetch_levels);
    if (cfg.machine_threads.empty()) throw UsageError("--machine-threads: no thread count");
    for (int p : cfg.machine_threads)
      if (p < 1 || p > m.cores())
        throw UsageError("--machine-threads " + std::to_string(p) + ": the machine " + m.name +
                         " has " + std::to_string(m.cores()) + " cores");
    if (cfg.machine_sweeps < 2 || cfg.machine_sweeps > 16)
      throw UsageError("machine sweeps must be 2..16 (the last one is counted, warm)");
  }
  if (cfg.profile_sweeps < 1 || cfg.profile_sweeps > 1000)
    throw UsageError("profile sweeps must be 1..1000");
  if (cfg.figure1_time_bins < 1 || cfg.figure1_time_bins > 100000)
    throw UsageError("figure 1 time bins must be 1..100000");
  for (const CacheLevel& l : cfg.cache.levels)
    if (l.ways == 0) throw UsageError("cache level " + l.name + " needs its ways (e.g. L1=32K/8)");
  for (const std::string& k : cfg.kernels) {
    SmoothOptions o = ExactSweeps(cfg.kernel_sweeps);
    CheckKernelOptions(ParseKernel(k), o);
  }
  if (!cfg.kernels.empty()) {
    if (cfg.kernel_orderings.empty()) throw UsageError("--kernel-orderings: no ordering given");
    for (const std::string& m : cfg.meshes)
      for (const std::string& o : cfg.kernel_orderings)
        CheckOrderingSpec(ForMesh(o, MeshShortName(m)));
    if (cfg.kernel_sweeps < 1 || cfg.kernel_sweeps > 1000)
      throw UsageError("--kernel-sweeps must be 1..1000");
  }
}

// The figure meshes among the meshes: a configured name that is absent falls back to the first
// mesh, said (never a figure dropped silently); an empty name draws no figure.
ReportConfig WithFigureMeshes(ReportConfig cfg, std::vector<std::string>* notes) {
  std::set<std::string> names;
  for (const std::string& m : cfg.meshes) names.insert(MeshShortName(m));
  const std::string first = MeshShortName(cfg.meshes[0]);
  for (auto [mesh, what] : {std::pair{&cfg.figure1_mesh,
                                      "Figure 1, the smoothing and the ordering "
                                      "pictures are"},
                            std::pair{&cfg.profile_mesh, "the profile is"}})
    if (!mesh->empty() && !names.count(*mesh)) {
      notes->push_back(std::string(what) + " drawn on " + first + ": " + *mesh +
                       " is not among the meshes.");
      *mesh = first;
    }
  return cfg;
}

std::string RunReport(const ReportConfig& in_cfg, const std::string& out_dir, const Log& log,
                      const std::function<void()>& figures) {
  CheckReportConfig(in_cfg);
  PhaseTimes phases;  // the prior ones first: a bad file fails before the long work
  if (!in_cfg.prior_phases.empty()) phases.AddFile(in_cfg.prior_phases);
  std::vector<std::string> notes;
  const ReportConfig cfg = WithFigureMeshes(in_cfg, &notes);
  for (const std::string& n : notes) log.Say(n);
  namespace fs = std::filesystem;
  for (const char* sub : {"/tables", "/data", "/figures"}) fs::create_directories(out_dir + sub);
  ReportData d;
  d.cfg = cfg;
  d.profile = Table(ReuseAnalysis::ProfileColumns());
  d.drawing = MeshDrawingTable();
  d.smoothing = SmoothingWindowTable();
  d.positions = OrderPositionsTable();
  d.notes = notes;
  d.histogram = Table(ReuseAnalysis::HistogramColumns());
  if (!cfg.measured.empty()) d.measured = ReadMeasured(cfg.measured);
  for (const std::string& o : cfg.orderings) d.orderings.push_back(ParseOrderingSpec(o).label);
  for (const std::string& p : cfg.meshes) {  // read when its turn comes; sized by its file
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(p, ec);
    d.meshes.push_back({p, MeshShortName(p), ec ? 1.0 : static_cast<double>(bytes)});
  }
  Steps steps(log, cfg, d.meshes);
  for (ReportMesh& m : d.meshes) MeasureMesh(cfg, m, &d, steps, log, &phases);
  // Figure 1's panels in the configured order (the paper's: random, ORI, BFS).
  auto rank = [&](const Figure1Data& f) {
    for (size_t i = 0; i < cfg.figure1_orderings.size(); ++i)
      if (ParseOrderingSpec(cfg.figure1_orderings[i]).label == f.ordering) return i;
    return cfg.figure1_orderings.size();
  };
  std::stable_sort(d.fig1.begin(), d.fig1.end(),
                   [&](const Figure1Data& a, const Figure1Data& b) { return rank(a) < rank(b); });
  CounterSources(cfg, &d);
  if (cfg.timing) {
    const PhaseTimes::Scope t = phases.Time("timed runs (Table 4, speedups)");
    MeasureTiming(cfg, &d, steps);
    if (const std::string busy = report::BusyNote(d); !busy.empty()) log.Warn(busy);
  }
  if (!cfg.kernels.empty()) {
    const PhaseTimes::Scope t = phases.Time("other kernels (simulated and timed)");
    for (const ReportMesh& m : d.meshes) {
      KernelRunsConfig kc;
      kc.kernels = cfg.kernels;
      for (const std::string& o : cfg.kernel_orderings) {
        kc.orderings.push_back(ForMesh(o, m.name));
        kc.labels.push_back(ParseOrderingSpec(kc.orderings.back()).label);
      }
      kc.sweeps = cfg.kernel_sweeps;
      kc.traced_sweeps = cfg.validate_sweeps;
      kc.rounds = cfg.repeat;
      kc.warmup_sweeps = cfg.warmup_sweeps;
      kc.timing = cfg.timing;
      kc.clock = cfg.clock;
      kc.seed = cfg.seed;
      kc.triangle_order = cfg.triangle_order;
      kc.cache = cfg.cache;
      kc.line_bytes = cfg.line_bytes;
      // Table 3 traced the Laplacian's sweeps of this mesh in the orderings it shares with this
      // part (the same traced sweeps, caches, seed and triangle order, one thread): that
      // kernel's simulated part is read from there, not simulated twice.
      for (const std::string& o : cfg.kernel_orderings) {
        const OrderingValidation* v = nullptr;
        for (size_t k = 0; k < cfg.orderings.size() && k < d.orderings.size(); ++k)
          if (cfg.orderings[k] == o)
            for (const OrderingValidation& x : d.validation)
              if (x.mesh == m.name && x.ordering == d.orderings[k]) v = &x;
        kc.laplacian.push_back(v);
      }
      const Mesh base = LoadMesh(m.path, log);
      MeasureKernels(
          kc, m.name, base, &d.kernels, [&](const std::string& s) { steps.Say(s); }, &phases);
      steps.Done(steps.Kernels(m));
    }
  }

  std::string sections;
  const Json manifest = [&] {
    const PhaseTimes::Scope t = phases.Time("tables and figure data");
    return report::WriteOutputs(d, out_dir, &sections);
  }();
  WriteTextFile(out_dir + "/manifest.json", RunJsonText(manifest));  // what the figures read
  if (figures) {
    const PhaseTimes::Scope t = phases.Time("figures (scripts/plot_report.py)");
    figures();
  }
  WriteTextFile(
      out_dir + "/run.json",
      RunJsonText(RunJson("meshreuse report", cfg.command_line, report::ConfigurationJson(cfg),
                          Json{{"counters", d.counters},
                               {"noise", cfg.timing ? d.noise.ToJson() : Json(nullptr)},
                               {"phases", phases.ToJson()}})));
  WriteTextFile(out_dir + "/README.md",
                report::Readme(d, manifest, sections) +
                    "\n## Where the time went\n\nWall and CPU seconds per phase of this run "
                    "(CPU: every thread of the process, and the figures' python; the many-core "
                    "thread counts run side by side on the host's cores, each shown with its own "
                    "thread's CPU):\n\n" +
                    phases.Markdown());
  steps.Say("tables written to " + out_dir);
  return out_dir + "/README.md";
}

}  // namespace meshreuse
