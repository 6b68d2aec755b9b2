// The model's validation; see validation.h.
#include "reports/validation.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include "analysis/papi_counters.h"
#include "analysis/reuse_analysis.h"
#include "analysis/sweep_footprint.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/orderings/registry.h"
#include "core/schedule.h"
#include "reports/inputs.h"
#include "reports/paper.h"
#include "reports/run_info.h"
#include "reports/stream_source.h"

namespace meshreuse {

namespace {

std::string RatioCell(double a, double b) { return b > 0 ? ExactNumber(a / b) : ""; }

}  // namespace

void CheckValidationConfig(const ValidationConfig& cfg) {
  cfg.Check();
  if (cfg.element_bytes == 0) throw UsageError("--element-bytes must be positive");
  for (const CacheLevel& c : cfg.cache.levels)
    if (c.ways == 0)
      throw UsageError("cache level " + c.name + " needs its associativity for simulation, e.g. " +
                       c.name + "=32K/8");
  CacheSimulation check(cfg.cache, cfg.line_bytes);  // the geometry and the line size
}

namespace {

// Counters: an untraced run of the sweeps on `laid`, where PAPI counts; per level the misses
// counted, -1 where none. `note` says which.
std::vector<double> CountMisses(const Mesh& laid, const ValidationConfig& cfg, const Log& log,
                                std::string* note) {
  const std::vector<CacheLevel>& levels = cfg.cache.levels;
  std::vector<double> counted(levels.size(), -1);
  if (cfg.counter_events.empty()) {
    *note = "simulated (no counters asked for)";
    return counted;
  }
  std::vector<std::string> wanted;
  for (size_t i = 0; i < levels.size() && i < cfg.counter_events.size(); ++i)
    wanted.push_back(cfg.counter_events[i]);
  PapiCounters papi(wanted, cfg.threads);
  if (!papi.available()) {
    *note = "simulated";
    return counted;
  }
  log.Say("validate: " + std::to_string(cfg.iterations) + " untraced sweep(s) with counters");
  Mesh m = laid.Clone();
  SmoothOptions o = cfg.Sweeps();
  o.region = &papi;
  RunKernel(cfg.Kernel(), m, o);
  if (!papi.error().empty()) throw std::runtime_error("counters failed: " + papi.error());
  const std::vector<long long> sum = papi.Sum();
  for (size_t i = 0; i < wanted.size(); ++i)
    for (size_t e = 0; e < papi.events().size(); ++e)
      if (papi.events()[e] == wanted[i]) counted[i] = static_cast<double>(sum[e]);
  *note = "measured (" + PapiCounters::Version() + ")";
  return counted;
}

// Per level: the models' misses on the merged histograms, the simulator's, the counters', the
// floor, Table 3's capacities; then equation 2 on the line model's and the simulator's misses.
void AddLevels(const ReuseHistogram& eh, const ReuseHistogram& lh, const CacheSimulation& sim,
               const std::vector<double>& counted, const ValidationConfig& cfg,
               OrderingValidation* v) {
  const std::vector<CacheLevel>& levels = cfg.cache.levels;
  const std::vector<uint64_t> floor = MissFloor(v->sweep_lines, cfg.cache, cfg.line_bytes);
  const std::vector<LevelMisses> me = ModelMisses(eh, levels, cfg.element_bytes);
  const std::vector<LevelMisses> ml = ModelMisses(lh, levels, cfg.line_bytes);
  std::vector<uint64_t> model_misses, sim_misses;
  for (size_t i = 0; i < levels.size(); ++i) {
    LevelValidation l;
    l.level = levels[i];
    l.element_capacity = me[i].capacity, l.line_capacity = ml[i].capacity;
    l.model_element = me[i].misses, l.model_line = ml[i].misses;
    l.floor = floor[i];
    for (int t = 0; t < cfg.threads; ++t) l.simulated += sim.Stats(t)[i];
    l.measured = counted[i] >= 0;
    l.counter = l.measured ? counted[i] : 0;
    l.table3_misses = l.measured ? static_cast<uint64_t>(l.counter) : l.simulated.misses;
    l.capacity_elements = CapacityForMisses(eh, l.table3_misses, cfg.exclude_cold);
    l.capacity_lines = CapacityForMisses(lh, l.table3_misses, cfg.exclude_cold);
    model_misses.push_back(l.model_line);
    sim_misses.push_back(l.simulated.misses);
    v->levels.push_back(l);
  }
  v->cost_model = AdditionalCycles(model_misses, cfg.cache);
  v->cost_simulated = AdditionalCycles(sim_misses, cfg.cache);
}

// Each ordering's traced sweeps streamed at once into the reuse analysis, the simulator and the
// footprint; at the stream's end its validation (and the counters' run on the same layout).
class ValidateStreams : public StreamConsumer {
 public:
  ValidateStreams(const ValidationConfig& cfg, const Log& log) : cfg_(cfg), log_(log) {}
  std::string Verb() const override { return "validate: tracing"; }
  AccessConsumer& Start(const StreamJob& job) override {
    ReuseOptions ao;
    ao.line_bytes = cfg_.line_bytes;
    ao.profile = false;
    analysis_ = std::make_unique<ReuseAnalysis>(ao);
    sim_ = std::make_unique<CacheSimulation>(cfg_.cache, cfg_.line_bytes);
    footprint_ = std::make_unique<SweepFootprint>(cfg_.line_bytes);
    both_ = std::make_unique<FanOut>(
        std::vector<AccessConsumer*>{analysis_.get(), sim_.get(), footprint_.get()});
    laid_ = std::make_unique<Mesh>(job.mesh->Clone());  // for the counters' untraced run
    return *both_;
  }
  void Finish(const StreamJob& job) override {
    OrderingValidation v;
    v.mesh = cfg_.mesh_name, v.ordering = job.ordering->label;
    v.vertices = laid_->NumVertices();
    v.iterations = cfg_.iterations, v.threads = cfg_.threads;
    ReuseHistogram eh, lh;
    for (int t = 0; t < cfg_.threads; ++t) {
      if (const StreamAnalysis* s = analysis_->element(t)) eh.Merge(s->hist);
      if (const StreamAnalysis* s = analysis_->line(t)) lh.Merge(s->hist);
    }
    v.element_accesses = eh.accesses(), v.line_accesses = lh.accesses();
    v.element_cold = eh.cold(), v.line_cold = lh.cold();
    if (lh.finite() > 0) v.line_q50 = lh.Quantile(0.5), v.line_q90 = lh.Quantile(0.9);
    v.sweep_lines = footprint_->lines();
    for (size_t s = 0; s < sim_->sweeps(); ++s) {
      std::vector<std::vector<LevelStats>> per;
      for (int t = 0; t < cfg_.threads; ++t) per.push_back(sim_->SweepStats(t, s));
      v.sweeps.push_back(std::move(per));
    }
    const std::vector<double> counted = CountMisses(*laid_, cfg_, log_, &v.counters);
    AddLevels(eh, lh, *sim_, counted, cfg_, &v);
    out.push_back(std::move(v));
  }
  std::vector<OrderingValidation> out;

 private:
  const ValidationConfig& cfg_;
  const Log& log_;
  std::unique_ptr<ReuseAnalysis> analysis_;
  std::unique_ptr<CacheSimulation> sim_;
  std::unique_ptr<SweepFootprint> footprint_;
  std::unique_ptr<FanOut> both_;
  std::unique_ptr<Mesh> laid_;
};

}  // namespace

std::vector<OrderingValidation> RunValidation(
    const Mesh& base, const ValidationConfig& cfg,
    const std::function<void(const std::string&)>& progress) {
  if (cfg.cache.levels.empty()) throw std::invalid_argument("no cache levels");
  Log log;
  log.progress = progress;
  ValidationConfig src = cfg;
  if (src.inputs.empty()) src.inputs = {cfg.mesh_name};
  src.loaded = &base;
  ValidateStreams c(src, log);
  ForEachStream(src, c, log);
  return std::move(c.out);
}

Table ValidationTable(const std::vector<OrderingValidation>& r) {
  Table t({"mesh", "ordering", "level", "size", "ways", "accesses", "model_element_misses",
           "model_line_misses", "simulated_misses", "simulated_cold", "simulated_excess",
           "counter_misses", "model_line/simulated", "simulated/counter", "local_miss_rate",
           "global_miss_rate", "counters", "floor_misses", "over_floor"});
  for (const OrderingValidation& v : r)
    for (const LevelValidation& l : v.levels) {
      const LevelStats& s = l.simulated;
      t.AddRow({v.mesh, v.ordering, l.level.name, std::to_string(l.level.bytes),
                std::to_string(l.level.ways), std::to_string(s.accesses),
                std::to_string(l.model_element), std::to_string(l.model_line),
                std::to_string(s.misses), std::to_string(s.cold), std::to_string(s.misses - s.cold),
                l.measured ? Fixed(l.counter, 0) : "",
                RatioCell(static_cast<double>(l.model_line), static_cast<double>(s.misses)),
                l.measured ? RatioCell(static_cast<double>(s.misses), l.counter) : "",
                ExactNumber(s.MissRate()),
                v.line_accesses ? ExactNumber(static_cast<double>(s.misses) / v.line_accesses) : "",
                l.measured ? "measured" : "simulated", std::to_string(l.floor),
                std::to_string(s.misses - std::min(s.misses, l.floor))});
    }
  return t;
}

Table ValidationSweepTable(const std::vector<OrderingValidation>& r) {
  Table t({"mesh", "ordering", "sweep", "level", "accesses", "simulated_misses", "simulated_cold"});
  for (const OrderingValidation& v : r)
    for (size_t s = 0; s < v.sweeps.size(); ++s)
      for (size_t i = 0; i < v.levels.size(); ++i) {
        LevelStats sum;
        for (const auto& th : v.sweeps[s]) sum += th[i];
        t.AddRow({v.mesh, v.ordering, std::to_string(s + 1), v.levels[i].level.name,
                  std::to_string(sum.accesses), std::to_string(sum.misses),
                  std::to_string(sum.cold)});
      }
  return t;
}

Table Table3(const std::vector<OrderingValidation>& r) {
  std::vector<std::string> head = {"mesh", "ordering", "source"};
  const size_t n = r.empty() ? 0 : r[0].levels.size();
  auto names = [&](const std::string& prefix, const std::string& suffix) {
    for (size_t i = 0; i < n; ++i) head.push_back(prefix + r[0].levels[i].level.name + suffix);
  };
  names("", "_misses_k_per_sweep");
  if (n == 3) names("paper_", "_misses_k");
  names("", "_capacity_k_elements");
  if (n == 3) names("paper_", "_capacity_k_elements");
  names("", "_capacity_lines");
  Table t(head);
  for (const OrderingValidation& v : r) {
    const std::string name = MeshShortName(v.mesh);
    const auto pt = paper::Table3(name, v.ordering);
    const bool has_paper = n == 3 && pt && paper::Sized(name, v.vertices);
    std::vector<std::string> row = {v.mesh, v.ordering,
                                    v.levels.empty() || !v.levels[0].measured
                                        ? std::string("simulated")
                                        : std::string("measured")};
    for (const LevelValidation& l : v.levels)
      row.push_back(Fixed(static_cast<double>(l.table3_misses) / 1e3 / v.iterations, 2));
    if (n == 3)
      for (int i = 0; i < 3; ++i) row.push_back(has_paper ? Fixed((*pt)[i], 2) : "");
    for (const LevelValidation& l : v.levels)
      row.push_back(CapacityCell(l.capacity_elements, 1e-3));
    if (n == 3)
      for (int i = 3; i < 6; ++i) row.push_back(has_paper ? Fixed((*pt)[i], 2) : "");
    for (const LevelValidation& l : v.levels) row.push_back(CapacityCell(l.capacity_lines));
    t.AddRow(row);
  }
  return t;
}

Table ValidationCostTable(const std::vector<OrderingValidation>& r) {
  Table t({"mesh", "ordering", "accesses", "element_accesses", "cost_model_at_low_latency",
           "cost_model_at_high_latency", "cost_simulated_at_low_latency",
           "cost_simulated_at_high_latency", "counters"});
  auto cell = [](const std::optional<CostRange>& c, bool high) {
    return c ? Fixed(high ? c->high : c->low, 0) : std::string();
  };
  for (const OrderingValidation& o : r)
    t.AddRow({o.mesh, o.ordering, std::to_string(o.line_accesses),
              std::to_string(o.element_accesses), cell(o.cost_model, false),
              cell(o.cost_model, true), cell(o.cost_simulated, false), cell(o.cost_simulated, true),
              o.counters});
  return t;
}

Json ValidationConfigJson(const ValidationConfig& cfg) {
  Json j = cfg.ToJson();
  j["cache"] = cfg.cache.text;
  j["element_bytes"] = cfg.element_bytes;
  j["line_bytes"] = cfg.line_bytes;
  j["exclude_cold"] = cfg.exclude_cold;
  j["counter_events"] = cfg.counter_events;
  return j;
}

std::vector<std::string> Table3Notes(const std::vector<OrderingValidation>& r, bool exclude_cold) {
  std::vector<std::string> notes;
  notes.push_back(
      "Table 3: misses are per sweep (over the sweeps run); capacities from the inverse model "
      "(n misses -> the distance of the n-th largest access, cold accesses counting as the "
      "largest" +
      std::string(exclude_cold ? "; --exclude-cold: cold accesses taken as compulsory, the rest "
                                 "inverted"
                               : "") +
      ") over the element stream (66-byte nodes, as the paper) and over the line stream.");
  for (const OrderingValidation& v : r)
    for (const LevelValidation& l : v.levels)
      if (l.capacity_elements == kInfiniteCapacity || l.capacity_lines == kInfiniteCapacity)
        notes.push_back(
            "inf (" + v.mesh + " " + v.ordering + " " + l.level.name + "): its " +
            std::to_string(l.table3_misses) +
            " misses are no more than the cold (first-touch) "
            "accesses (" +
            std::to_string(v.element_cold) + " elements, " + std::to_string(v.line_cold) +
            " lines), which miss at any capacity, so no finite capacity explains them; "
            "--exclude-cold counts the cold accesses as compulsory and inverts the rest.");
  return notes;
}

RunOutput ValidationOutput(const std::vector<OrderingValidation>& r, const ValidationConfig& cfg) {
  RunOutput o;
  o.tool = "meshreuse validate";
  const Table v = ValidationTable(r), t3 = Table3(r), sw = ValidationSweepTable(r),
              cost = ValidationCostTable(r);
  const std::vector<std::string> notes = Table3Notes(r, cfg.exclude_cold);
  o.json =
      Json({{"validation", v.JsonValue()}, {"table3", t3.JsonValue()}, {"cost", cost.JsonValue()}});
  const RunOutput::TablePtr vp = RunOutput::Share(v), cp = RunOutput::Share(cost),
                            tp = RunOutput::Share(t3);
  for (const RunOutput::TablePtr& t : {vp, cp, tp}) {
    o.text.emplace_back(t);
    o.text.emplace_back("");
  }
  for (const std::string& n : notes) o.text.emplace_back(n);
  o.csv = vp;
  o.tables = {
      {"validate", vp, {"csv", "md", "json"}}, {"cost", cp, {"csv"}}, {"table3", tp, {"csv"}}};
  std::string md = t3.Markdown();
  for (const std::string& n : notes) md += "\n" + n + "\n";
  o.files.emplace_back("table3.md", md);
  o.tables.push_back({"sweeps", RunOutput::Share(sw), {"csv"}});
  o.configuration = ValidationConfigJson(cfg);
  o.extra = {{"counters", r.empty() ? "" : r[0].counters}};
  return o;
}

}  // namespace meshreuse
