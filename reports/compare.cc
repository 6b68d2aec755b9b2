// RunCompare and its tables; see compare.h.
#include "reports/compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

#include "analysis/papi_counters.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "reports/run_info.h"
#include "reports/speedup.h"
#include "reports/timing.h"

namespace meshreuse {

std::vector<double> CompareRow::Values(double CompareRound::*field) const {
  std::vector<double> v;
  for (const CompareRound& r : rounds) v.push_back(r.*field);
  return v;
}

namespace {

using Clock = std::chrono::steady_clock;
double MedianSweep(const SmoothResult& res, double SweepRecord::*field) {
  std::vector<double> v;
  for (const SweepRecord& s : res.sweeps) v.push_back(s.*field);
  return Median(v);
}

// One mesh's rows, measured: warm-up, then rounds until enough.
class MeshTiming {
 public:
  MeshTiming(const CompareConfig& cfg, const std::string& path, const Mesh& base,
             std::vector<CompareRow>* rows, const std::function<void(const std::string&)>& say)
      : cfg_(cfg), path_(path), base_(base), rows_(rows), say_(say), first_(rows->size()) {}

  void Prepare() {
    for (const std::string& spec : cfg_.orderings) {
      // The working copy goes first: the ordering's and the span's scratch memory then never
      // adds to two meshes, and the first apply of each ordering allocates, as a fresh reorder
      // would.
      work_ = Mesh();
      Permutation p = ComputeOrdering(spec, base_, cfg_.seed);
      const EdgeSpan span = MeasureEdgeSpan(base_, p);
      const auto t0 = Clock::now();
      ApplyPermutationInto(base_, p, cfg_.triangle_order, &work_);
      const double apply_first = Since(t0);
      perms_.push_back(p.new_to_old());
      for (int t : cfg_.threads) {
        CompareRow r;
        r.mesh = path_, r.ordering = ParseOrderingSpec(spec).label, r.threads = t;
        r.vertices = base_.NumVertices(), r.triangles = base_.NumTriangles();
        r.apply_first_seconds = apply_first;
        r.span = span;
        rows_->push_back(std::move(r));
      }
    }
  }

  // One pass over every (ordering, threads): the ordering computed (timed), applied (timed) and
  // smoothed. `timed` false: the warm-up, warmup_sweeps sweeps a run, nothing recorded.
  void Round(bool timed, int round) {
    size_t k = first_;
    for (size_t oi = 0; oi < cfg_.orderings.size(); ++oi) {
      auto t0 = Clock::now();
      const Permutation again = ComputeOrdering(cfg_.orderings[oi], base_, cfg_.seed);
      const double order = Since(t0);
      (void)again;  // the same permutation: perms_ is applied, so every run starts alike
      for (int t : cfg_.threads) {
        CompareRow& r = (*rows_)[k++];
        t0 = Clock::now();
        ApplyPermutationInto(base_, Permutation::FromNewToOld(perms_[oi]), cfg_.triangle_order,
                             &work_);
        const double apply = Since(t0);
        SmoothOptions o = cfg_.smooth;
        o.threads = t;
        if (!timed) o.max_iters = std::min(o.max_iters, cfg_.warmup_sweeps);
        o.adjacency_after = false;              // the next run applies the ordering anew
        o.end_qualities = timed && round == 0;  // the final quality: the first round's
        std::unique_ptr<PapiCounters> papi;
        if (timed && !cfg_.counter_events.empty()) {
          papi = std::make_unique<PapiCounters>(cfg_.counter_events, t);
          if (papi->available()) o.region = papi.get();
        }
        const SmoothResult res = RunKernel(kernel_, work_, o);
        if (!timed) continue;
        if (papi && papi->available()) {
          if (!papi->error().empty()) throw std::runtime_error("counters failed: " + papi->error());
          r.counter_events = papi->events();
          r.counters.push_back(papi->Sum());
        }
        CompareRound c;
        c.sweeps = static_cast<int>(res.sweeps.size());
        c.total_wall = res.seconds, c.total_cpu = res.cpu_seconds;
        c.sweep_wall = MedianSweep(res, &SweepRecord::seconds);
        c.sweep_cpu = MedianSweep(res, &SweepRecord::cpu_seconds);
        c.order = order, c.apply = apply;
        r.rounds.push_back(c);
        if (round == 0) r.final_quality = res.quality_after;
        say_("  round " + std::to_string(round + 1) + " " + r.ordering + " x" + std::to_string(t) +
             ": " + std::to_string(c.sweeps) + " sweeps, " + Fixed(res.seconds, 3) + " s wall, " +
             Fixed(res.cpu_seconds, 3) + " s CPU");
      }
    }
  }

  // Spreads, speedups and gains of this mesh's rows from their rounds.
  void Summarize() {
    for (size_t i = first_; i < rows_->size(); ++i) {
      CompareRow& r = (*rows_)[i];
      const uint64_t s = cfg_.seed + i;
      r.order = SpreadOf(r.Values(&CompareRound::order), s);
      r.apply = SpreadOf(r.Values(&CompareRound::apply), s + 1);
      r.total = SpreadOf(r.Values(&CompareRound::total_wall), s + 2);
      r.sweep = SpreadOf(r.Values(&CompareRound::sweep_wall), s + 3);
      r.sweep_cpu = SpreadOf(r.Values(&CompareRound::sweep_cpu), s + 4);
      std::vector<double> ratio;
      for (const CompareRound& c : r.rounds)
        if (c.total_wall > 0) ratio.push_back(c.total_cpu / (c.total_wall * r.threads));
      r.cpu_per_wall = Median(ratio);
      r.cv = CoefficientOfVariation(r.Values(&CompareRound::sweep_wall));
      r.counter_medians.clear();
      for (size_t e = 0; e < r.counter_events.size(); ++e) {
        std::vector<double> v;
        for (const auto& round : r.counters) v.push_back(static_cast<double>(round[e]));
        r.counter_medians.push_back(Median(v));
      }
    }
    const std::vector<CompareRow> mine(rows_->begin() + first_, rows_->end());
    const TimingIndex index(mine);
    for (size_t i = first_; i < rows_->size(); ++i) {
      CompareRow& r = (*rows_)[i];
      r.speedup_vs_ori1 = Speedup(index.Find(path_, "ori", 1), &r, cfg_.seed, cfg_.clock);
      r.gain_vs_bfs = Gain(index.Find(path_, "bfs", r.threads), &r, cfg_.seed, cfg_.clock);
    }
  }

  // --repeat auto: every speedup against ori on one thread known within +-2%. Fills `end`
  // with the widest interval left.
  bool Settled(RepeatAutoEnd* end) const {
    end->widest = NAN;
    for (size_t i = first_; i < rows_->size(); ++i) {
      const CompareRow& r = (*rows_)[i];
      const Spread& s = r.speedup_vs_ori1;
      if (!std::isfinite(s.median)) continue;
      const double w = s.RelativeHalfWidth();
      if (!(end->widest >= w)) {
        end->widest = w;
        end->widest_row = r.ordering + " x" + std::to_string(r.threads);
      }
    }
    end->settled = !(end->widest > 0.02);
    return end->settled;
  }

 private:
  const CompareConfig& cfg_;
  const std::string& path_;
  const Mesh& base_;
  std::vector<CompareRow>* rows_;
  const std::function<void(const std::string&)>& say_;
  const KernelInfo& kernel_ = ParseKernel(cfg_.kernel);
  size_t first_;
  Mesh work_;
  std::vector<std::vector<int32_t>> perms_;
};

}  // namespace

CompareResult RunCompare(const CompareConfig& cfg,
                         const std::function<void(const std::string&)>& progress,
                         const std::function<void(const std::string&)>& warn) {
  const std::function<void(const std::string&)> say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  if (cfg.repeat < 3 && !cfg.repeat_auto)
    throw UsageError("--repeat must be at least 3 (a median and its interval need rounds)");
  cfg.CheckWarmup();
  for (int t : cfg.threads) {
    SmoothOptions o = cfg.smooth;
    o.threads = t;
    CheckKernelOptions(ParseKernel(cfg.kernel), o);
  }
  CompareResult out;
  out.noise.cores = Cores();
  out.noise.load_before = LoadAverage();
  for (size_t mi = 0; mi < cfg.meshes.size(); ++mi) {
    const std::string& path = cfg.meshes[mi];
    say("mesh " + std::to_string(mi + 1) + "/" + std::to_string(cfg.meshes.size()) + ": reading " +
        path);
    std::vector<std::string> warnings;
    const Mesh base = ReadMesh(path, &warnings);
    if (warn)
      for (const std::string& w : warnings) warn(w);
    MeshTiming m(cfg, path, base, &out.rows, say);
    m.Prepare();
    say("  warm-up: every ordering computed, applied and smoothed " +
        std::to_string(std::min(cfg.warmup_sweeps, cfg.smooth.max_iters)) + " sweep(s), untimed");
    m.Round(false, 0);
    const int rounds = cfg.repeat_auto ? cfg.repeat_cap : cfg.repeat;
    RepeatAutoEnd end;
    end.mesh = path;
    for (int round = 0; round < rounds; ++round) {
      m.Round(true, round);
      end.rounds = round + 1;
      if (cfg.repeat_auto && round + 1 >= 3) {
        m.Summarize();
        if (m.Settled(&end)) {
          say("  every speedup within +-2% after " + std::to_string(round + 1) + " rounds");
          break;
        }
      }
    }
    m.Summarize();
    if (cfg.repeat_auto) out.repeat_auto.push_back(end);
  }
  out.noise.load_after = LoadAverage();
  for (const CompareRow& r : out.rows) {
    if (std::isfinite(r.cpu_per_wall) && !(out.noise.cpu_per_wall <= r.cpu_per_wall))
      out.noise.cpu_per_wall = r.cpu_per_wall;
    if (std::isfinite(r.cv) && !(out.noise.cv >= r.cv)) out.noise.cv = r.cv;
  }
  return out;
}

namespace {
std::string SweepRange(const CompareRow& r) {
  if (r.rounds.empty()) return "";
  int lo = r.rounds[0].sweeps, hi = lo;
  for (const CompareRound& c : r.rounds) lo = std::min(lo, c.sweeps), hi = std::max(hi, c.sweeps);
  return lo == hi ? std::to_string(lo) : std::to_string(lo) + "-" + std::to_string(hi);
}
std::string VerdictOf(const Spread& ratio) {
  return std::isfinite(ratio.median) ? VerdictName(SpeedupVerdict(ratio)) : "";
}
std::string GainVerdictOf(const Spread& gain) {
  return std::isfinite(gain.median) ? VerdictName(GainVerdict(gain)) : "";
}
}  // namespace

Table CompareTable(const std::vector<CompareRow>& rows) {
  std::vector<std::string> head = {"mesh",   "ordering",      "threads",     "rounds",
                                   "sweeps", "final_quality", "span_median", "span_p90"};
  for (const char* n : {"order_ms", "apply_ms", "sweep_ms", "sweep_cpu_ms", "total_s"})
    Append(&head, SpreadColumns(n));
  Append(&head, {"apply_first_ms", "cpu_per_wall", "cv"});
  Append(&head, SpreadColumns("speedup_vs_ori1"));
  head.push_back("vs_ori1");
  Append(&head, SpreadColumns("gain_vs_bfs_pct"));
  head.push_back("vs_bfs");
  std::vector<std::string> events;  // counters recorded in any row, in first-seen order
  for (const CompareRow& r : rows)
    for (const std::string& e : r.counter_events)
      if (std::find(events.begin(), events.end(), e) == events.end()) events.push_back(e);
  for (const std::string& e : events) head.push_back(e);
  Table t(head);
  for (const CompareRow& r : rows) {
    std::vector<std::string> row = {r.mesh,
                                    r.ordering,
                                    std::to_string(r.threads),
                                    std::to_string(r.rounds.size()),
                                    SweepRange(r),
                                    ExactNumber(r.final_quality),
                                    std::to_string(r.span.median),
                                    std::to_string(r.span.p90)};
    Append(&row, SpreadCells(r.order, 1e3));
    Append(&row, SpreadCells(r.apply, 1e3));
    Append(&row, SpreadCells(r.sweep, 1e3));
    Append(&row, SpreadCells(r.sweep_cpu, 1e3));
    Append(&row, SpreadCells(r.total));
    Append(&row, {ExactNumber(1e3 * r.apply_first_seconds), ExactNumber(r.cpu_per_wall),
                  ExactNumber(r.cv)});
    Append(&row, SpreadCells(r.speedup_vs_ori1));
    row.push_back(VerdictOf(r.speedup_vs_ori1));
    Append(&row, SpreadCells(r.gain_vs_bfs, 100));
    row.push_back(GainVerdictOf(r.gain_vs_bfs));
    for (const std::string& e : events) {
      const auto it = std::find(r.counter_events.begin(), r.counter_events.end(), e);
      row.push_back(it == r.counter_events.end()
                        ? ""
                        : ExactNumber(r.counter_medians[it - r.counter_events.begin()]));
    }
    t.AddRow(row);
  }
  return t;
}

namespace {
std::string WithInterval(const Spread& s, double k, int decimals) {
  if (!std::isfinite(s.median)) return "";
  std::string t = Fixed(k * s.median, decimals);
  if (std::isfinite(s.lo))
    t += " [" + Fixed(k * s.lo, decimals) + ", " + Fixed(k * s.hi, decimals) + "]";
  return t;
}
}  // namespace

Table CompareTextTable(const std::vector<CompareRow>& rows, TimeClock clock) {
  const bool cpu = clock == TimeClock::kCpu;
  Table t({"mesh", "ordering", "threads", "rounds", "sweeps",
           cpu ? "cpu ms/sweep [95%]" : "ms/sweep [95%]", cpu ? "wall ms/sweep" : "cpu ms/sweep",
           "total s", "speedup vs ori1 [95%]", "verdict", "gain vs bfs % [95%]", "verdict"});
  for (const CompareRow& r : rows) {
    const Spread& chosen = cpu ? r.sweep_cpu : r.sweep;
    const Spread& other = cpu ? r.sweep : r.sweep_cpu;
    t.AddRow({r.mesh, r.ordering, std::to_string(r.threads), std::to_string(r.rounds.size()),
              SweepRange(r), WithInterval(chosen, 1e3, 3), Fixed(1e3 * other.median, 3),
              Fixed(r.total.median, 3), WithInterval(r.speedup_vs_ori1, 1, 3),
              VerdictOf(r.speedup_vs_ori1), WithInterval(r.gain_vs_bfs, 100, 1),
              GainVerdictOf(r.gain_vs_bfs)});
  }
  return t;
}

std::string RepeatAutoEnd::Sentence(int cap) const {
  char b[300];
  std::snprintf(b, sizeof b,
                "%s: --repeat auto stopped at its cap of %d rounds with the speedups not yet "
                "within +-2%%: the widest, %s's, is +-%.1f%% (a larger cap, auto:N, or a quieter "
                "machine narrows it)",
                mesh.c_str(), cap, widest_row.c_str(), 100 * widest);
  return b;
}

Json RepeatAutoEnd::ToJson() const {
  return {{"mesh", mesh},
          {"rounds", rounds},
          {"settled", settled},
          {"widest_relative_half_width", std::isfinite(widest) ? Json(widest) : Json(nullptr)},
          {"widest", widest_row}};
}

void ParseRepeat(const std::string& text, int* repeat, bool* automatic, int* cap) {
  *automatic = text.rfind("auto", 0) == 0;
  if (*automatic) {
    *repeat = 3;
    if (text == "auto") return;
    const std::string c = text.size() > 5 && text[4] == ':' ? text.substr(5) : "";
    if (c.empty() || c.size() > 4 || c.find_first_not_of("0123456789") != std::string::npos ||
        std::stoi(c) < 3)
      throw UsageError("--repeat auto:CAP takes a cap of at least 3 rounds, found '" + text + "'");
    *cap = std::stoi(c);
    return;
  }
  if (text.empty() || text.size() > 4 || text.find_first_not_of("0123456789") != std::string::npos)
    throw UsageError("--repeat takes a number of rounds (at least 3), auto or auto:CAP, found '" +
                     text + "'");
  *repeat = std::stoi(text);
  if (*repeat < 3)
    throw UsageError(
        "--repeat must be at least 3: a median and its interval need rounds (auto: "
        "as many as the intervals need)");
}

Table CompareSummaryTable(const std::vector<CompareRow>& rows, uint64_t seed, TimeClock clock) {
  const TimingIndex index(rows);
  std::vector<std::pair<std::string, int>> cells;
  std::vector<std::string> meshes;
  for (const CompareRow& r : rows) {
    if (std::find(cells.begin(), cells.end(), std::make_pair(r.ordering, r.threads)) == cells.end())
      cells.emplace_back(r.ordering, r.threads);
    if (std::find(meshes.begin(), meshes.end(), r.mesh) == meshes.end()) meshes.push_back(r.mesh);
  }
  std::vector<std::string> head = {"ordering", "threads", "meshes"};
  for (const char* n : {"speedup_vs_ori1", "T_ori/T", "T_bfs/T"}) {
    Append(&head, SpreadColumns(n));
    head.push_back(std::string(n) + "_verdict");
  }
  for (const char* n : {"gain_vs_ori_pct", "gain_vs_bfs_pct"}) {
    Append(&head, SpreadColumns(n));
    head.push_back(std::string(n) + "_verdict");
  }
  Table out(head);
  // Means over the meshes where both sides exist.
  auto mean = [&](const std::string& ord, int p, const std::string& ref, int ref_p, bool gain) {
    std::vector<std::pair<const CompareRow*, const CompareRow*>> pairs;
    for (const std::string& m : meshes)
      pairs.emplace_back(index.Find(m, ref, ref_p), index.Find(m, ord, p));
    return MeanRatio(pairs, seed, gain, clock);
  };
  for (const auto& [ord, p] : cells) {
    std::vector<std::string> row = {ord, std::to_string(p), std::to_string(meshes.size())};
    for (const Spread& s : {mean(ord, p, "ori", 1, false), mean(ord, p, "ori", p, false),
                            mean(ord, p, "bfs", p, false)}) {
      Append(&row, SpreadCells(s));
      row.push_back(VerdictOf(s));
    }
    for (const char* ref : {"ori", "bfs"}) {
      const Spread g = mean(ord, p, ref, p, true);
      Append(&row, SpreadCells(g, 100));
      row.push_back(GainVerdictOf(g));
    }
    out.AddRow(row);
  }
  return out;
}

Table CompareSummaryTextTable(const Table& summary) {
  Table t(
      {"ordering", "threads", "meshes", "speedup_vs_ori1", "verdict", "gain_vs_bfs_%", "verdict"});
  for (const auto& r : summary.JsonValue()) {
    auto cell = [&](const char* k, int decimals) {
      const auto& v = r[k];
      if (v.is_null()) return std::string();
      return v.is_string() ? v.get<std::string>() : Fixed(v.get<double>(), decimals);
    };
    t.AddRow({cell("ordering", 0), cell("threads", 0), cell("meshes", 0),
              cell("speedup_vs_ori1", 3), cell("speedup_vs_ori1_verdict", 0),
              cell("gain_vs_bfs_pct", 1), cell("gain_vs_bfs_pct_verdict", 0)});
  }
  return t;
}

Json CompareJson(const std::vector<CompareRow>& rows) {
  Json a = Json::array();
  auto num = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  for (const CompareRow& r : rows) {
    Json j;
    j["mesh"] = r.mesh;
    j["ordering"] = r.ordering;
    j["threads"] = r.threads;
    j["vertices"] = r.vertices;
    j["triangles"] = r.triangles;
    j["rounds"] = r.rounds.size();
    j["order_seconds"] = SpreadJson(r.order);
    j["apply_seconds"] = SpreadJson(r.apply);
    j["apply_first_seconds"] = num(r.apply_first_seconds);
    j["edge_span"] = {{"median", r.span.median},
                      {"p90", r.span.p90},
                      {"p99", r.span.p99},
                      {"max", r.span.max},
                      {"mean", num(r.span.mean)}};
    j["seconds_per_sweep"] = SpreadJson(r.sweep);
    j["cpu_seconds_per_sweep"] = SpreadJson(r.sweep_cpu);
    j["total_seconds"] = SpreadJson(r.total);
    j["cpu_per_wall"] = num(r.cpu_per_wall);
    j["cv"] = num(r.cv);
    Json rounds = Json::array();
    for (const CompareRound& c : r.rounds)
      rounds.push_back({{"sweeps", c.sweeps},
                        {"total_wall", c.total_wall},
                        {"total_cpu", c.total_cpu},
                        {"sweep_wall", c.sweep_wall},
                        {"sweep_cpu", c.sweep_cpu},
                        {"order", c.order},
                        {"apply", c.apply}});
    j["rounds_measured"] = rounds;
    j["final_quality"] = num(r.final_quality);
    j["speedup_vs_ori1"] = SpreadJson(r.speedup_vs_ori1);
    j["speedup_vs_ori1_verdict"] = VerdictOf(r.speedup_vs_ori1);
    j["gain_vs_bfs"] = SpreadJson(r.gain_vs_bfs);
    j["gain_vs_bfs_verdict"] = GainVerdictOf(r.gain_vs_bfs);
    if (r.counter_events.empty()) {
      j["counters"] = nullptr;
    } else {
      Json cj;
      for (size_t e = 0; e < r.counter_events.size(); ++e) {
        std::vector<long long> per;
        for (const auto& round : r.counters) per.push_back(round[e]);
        cj[r.counter_events[e]] = {{"median", num(r.counter_medians[e])}, {"per_round", per}};
      }
      j["counters"] = cj;
    }
    a.push_back(std::move(j));
  }
  return a;
}

const char* ClockName(TimeClock c) { return c == TimeClock::kCpu ? "cpu" : "wall"; }

TimeClock ParseClock(const std::string& s) {
  if (s == "wall") return TimeClock::kWall;
  if (s == "cpu") return TimeClock::kCpu;
  throw UsageError("--clock: '" + s + "' is not a clock (wall or cpu)");
}

void TimingOptions::CheckWarmup() const {
  if (warmup_sweeps < 1 || warmup_sweeps > 1000)
    throw UsageError("--warm-up-sweeps must be 1..1000");
}

void TimingOptions::AddJson(Json* j) const {
  Json& o = *j;
  o["threads"] = threads;
  o["repeat"] = repeat_auto ? Json("auto") : Json(repeat);
  o["repeat_cap"] = repeat_cap;
  o["warmup_sweeps"] = warmup_sweeps;
  o["clock"] = ClockName(clock);
  o["mode"] = UpdateModeName(smooth.mode);
  o["quality"] = QualityModeName(smooth.quality);
  o["tol"] = smooth.tol;
  o["max_iters"] = smooth.max_iters;
  o["triangle_order"] = TriangleOrderName(triangle_order);
}

Json CompareConfigJson(const CompareConfig& cfg) {
  Json j;
  j["meshes"] = cfg.meshes;
  j["orderings"] = cfg.orderings;
  j["kernel"] = cfg.kernel;
  j["ordering_seeds"] = OrderingSeedsJson(ParseOrderingSpecs(cfg.orderings), cfg.seed);
  j["seed"] = cfg.seed;
  cfg.AddJson(&j);
  j["counters"] = cfg.counter_events;
  return j;
}

RunOutput CompareOutput(const CompareResult& result, const CompareConfig& cfg) {
  RunOutput o;
  o.tool = "meshreuse compare";
  const std::vector<CompareRow>& rows = result.rows;
  const RunOutput::TablePtr t = RunOutput::Share(CompareTable(rows)),
                            summary =
                                RunOutput::Share(CompareSummaryTable(rows, cfg.seed, cfg.clock));
  Json ends = Json::array();
  for (const RepeatAutoEnd& e : result.repeat_auto) ends.push_back(e.ToJson());
  o.json = Json({{"seed", cfg.seed},
                 {"noise", result.noise.ToJson()},
                 {"repeat_auto", ends},
                 {"rows", CompareJson(rows)},
                 {"summary", summary->JsonValue()}});
  o.csv = t;
  o.text.emplace_back(RunOutput::Share(CompareTextTable(rows, cfg.clock)));
  o.text.emplace_back(
      std::string(IsPaperSweep(ParseKernel(cfg.kernel)) ? "" : "(kernel " + cfg.kernel + ") ") +
      "(seed " + std::to_string(cfg.seed) +
      "; medians over the rounds after a warm-up, [95% interval of the median]; speedup = "
      "T_ori(1)/T, gain = (T_bfs-T)/T_bfs on per-sweep medians (" +
      ClockName(cfg.clock) +
      " clock); an interval holding 1 is not distinguishable; every spread: --csv, --json, --out)");
  for (const RepeatAutoEnd& e : result.repeat_auto)
    if (!e.settled) o.text.emplace_back("note: " + e.Sentence(cfg.repeat_cap));
  o.text.emplace_back("");
  o.text.emplace_back("mean over " + std::to_string(cfg.meshes.size()) + " mesh(es):");
  o.text.emplace_back(RunOutput::Share(CompareSummaryTextTable(*summary)));
  o.tables = {{"compare", t, {"csv", "md"}}, {"summary", summary, {"csv", "md"}}};
  o.files.emplace_back("compare.json", Json({{"rows", CompareJson(rows)}}).dump(1) + "\n");
  o.configuration = CompareConfigJson(cfg);
  o.extra = {
      {"noise", result.noise.ToJson()}, {"repeat_auto", ends}, {"results", CompareJson(rows)}};
  return o;
}

}  // namespace meshreuse
