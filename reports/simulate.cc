// The simulate runner; see simulate.h.
#include "reports/simulate.h"

#include <limits>

#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/schedule.h"
#include "reports/inputs.h"
#include "reports/run_info.h"
#include "reports/stream_source.h"
#include "tracer/access_stream.h"

namespace meshreuse {

void CheckSimulateConfig(const SimulateConfig& cfg) {
  if (cfg.by_array && !cfg.machine.empty())
    throw UsageError("--by-array counts the private caches' misses: not with --machine");
  if (cfg.ranks > 0 && (!cfg.machine.empty() || !cfg.format.empty() || cfg.threads != 1))
    throw UsageError(
        "--ranks simulates each rank's part of a mesh (one stream per rank, private caches): "
        "no --machine, --format or --threads with it");
  cfg.Check();
  for (const CacheLevel& c : cfg.cache.levels)
    if (c.ways == 0)
      throw UsageError("cache level " + c.name + " needs its associativity for simulation, e.g. " +
                       c.name + "=32K/8");
  if (cfg.machine.empty() && (cfg.machine_threads.size() > 1 || cfg.placements.size() > 1))
    throw UsageError(
        "--threads and --placement take one value without --machine (lists: a machine run per "
        "thread count and placement)");
  if (!cfg.machine.empty()) {
    Machine m = ParseMachine(cfg.machine);
    SetPrefetch(&m, cfg.prefetch);
    if (cfg.placements.empty()) throw UsageError("--placement: no placement given");
    for (int p : cfg.machine_threads.empty() ? std::vector<int>{cfg.threads} : cfg.machine_threads)
      for (Placement pl : cfg.placements) PlaceThreads(m, p, pl);
    return;
  }
  CacheSimulation check(cfg.cache, cfg.line_bytes);  // the geometry
}

int ParseInterleave(const std::string& s) {
  if (s == "serial") return kSerialShares;
  if (s == "access") return kAccessGrain;
  if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos ||
      std::stoi(s) < 1)
    throw UsageError("--interleave: '" + s + "' (serial, access, or visits per turn: 1, 64, ...)");
  return std::stoi(s);
}

std::string InterleaveName(int interleave) {
  return interleave == kSerialShares  ? "serial"
         : interleave == kAccessGrain ? "access"
                                      : std::to_string(interleave);
}

namespace {

// A simulator per stream (per rank's part), made by `make`.
template <class Sim, class Make>
class SimulateStreams : public StreamConsumer {
 public:
  SimulateStreams(std::string where, Make make) : where_(std::move(where)), make_(make) {}
  std::string Verb() const override { return "simulating"; }
  std::string Where() const override { return where_; }
  AccessConsumer& Start(const StreamJob&) override {
    runs.push_back(make_());
    return *runs.back();
  }
  std::vector<std::unique_ptr<Sim>> runs;

 private:
  std::string where_;
  Make make_;
};

template <class Sim, class Make>
std::vector<std::unique_ptr<Sim>> Simulate(const StreamSource& src, std::string where, Make make,
                                           const Log& log) {
  SimulateStreams<Sim, Make> c(std::move(where), make);
  ForEachStream(src, c, log);
  return std::move(c.runs);
}

}  // namespace

namespace {

// A machine's simulators for one stream, a placement each, and their runs at the stream's end.
class MachineStreams : public StreamConsumer {
 public:
  MachineStreams(const Machine& m, const std::vector<Placement>& placements, int threads,
                 MachineSimulations* out)
      : m_(m), placements_(placements), threads_(threads), out_(*out) {}
  std::string Verb() const override { return "simulating"; }
  std::string Where() const override {
    std::string w = " on " + m_.name + ", " + std::to_string(threads_) + " thread(s)";
    for (size_t i = 0; i < placements_.size() && (i == 0 || threads_ > 1); ++i)
      w += std::string(i ? "," : " ") + PlacementName(placements_[i]);
    return w;
  }
  AccessConsumer& Start(const StreamJob& job) override {
    first_ = out_.sims.size();
    std::vector<AccessConsumer*> to;
    for (size_t i = 0; i < placements_.size() && (i == 0 || threads_ > 1); ++i) {
      out_.sims.push_back(std::make_unique<MulticoreSimulation>(m_, placements_[i]));
      to.push_back(out_.sims.back().get());
    }
    label_ = job.ordering ? job.ordering->label : "";
    all_ = std::make_unique<FanOut>(to);
    return *all_;
  }
  void Finish(const StreamJob& job) override {
    for (size_t i = first_; i < out_.sims.size(); ++i)
      out_.runs.push_back(CollectMachineRun(*out_.sims[i], job.input, label_, false));
  }

 private:
  const Machine& m_;
  const std::vector<Placement>& placements_;
  int threads_;
  MachineSimulations& out_;
  size_t first_ = 0;
  std::string label_;
  std::unique_ptr<FanOut> all_;
};

}  // namespace

MachineSimulations RunMachineSimulate(const SimulateConfig& cfg, const Log& log) {
  CheckSimulateConfig(cfg);
  Machine machine = ParseMachine(cfg.machine);
  SetPrefetch(&machine, cfg.prefetch);
  MachineSimulations out;
  for (int p : cfg.machine_threads.empty() ? std::vector<int>{cfg.threads} : cfg.machine_threads) {
    StreamSource src = cfg;
    src.threads = p;
    MachineStreams c(machine, cfg.placements, p, &out);
    ForEachStream(src, c, log);
  }
  return out;
}

Table MachineTable(const std::vector<std::unique_ptr<MulticoreSimulation>>& runs, bool warm) {
  Table t(MulticoreSimulation::Columns());
  for (const auto& s : runs) s->AppendRows(&t, warm);
  return t;
}

std::vector<std::unique_ptr<CacheSimulation>> RunSimulate(const SimulateConfig& cfg,
                                                          const Log& log) {
  CheckSimulateConfig(cfg);
  return Simulate<CacheSimulation>(
      cfg, "",
      [&cfg] {
        auto sim = std::make_unique<CacheSimulation>(cfg.cache, cfg.line_bytes);
        if (cfg.by_array) sim->CountByArray();
        return sim;
      },
      log);
}

Table SimulateTable(const std::vector<std::unique_ptr<CacheSimulation>>& runs, bool per_sweep) {
  Table t(CacheSimulation::Columns());
  for (const auto& s : runs) s->AppendRows(&t, per_sweep);
  return t;
}

Table SimulateArrayTable(const std::vector<std::unique_ptr<CacheSimulation>>& runs) {
  Table t(CacheSimulation::ArrayColumns());
  for (const auto& s : runs) s->AppendArrayRows(&t);
  return t;
}

Json SimulateConfigJson(const SimulateConfig& cfg) {
  Json j = cfg.ToJson();
  if (cfg.machine.empty()) {
    j["cache"] = cfg.cache.text;
    j["line_bytes"] = cfg.line_bytes;
    j["by_array"] = cfg.by_array;
  } else {
    j["machine"] = cfg.machine;
    j["machine_threads"] =
        cfg.machine_threads.empty() ? std::vector<int>{cfg.threads} : cfg.machine_threads;
    std::vector<std::string> placements;
    for (Placement p : cfg.placements) placements.push_back(PlacementName(p));
    j["placement"] = placements;
    j["interleave"] = InterleaveName(cfg.interleave);
    j["prefetch"] = cfg.prefetch;
  }
  return j;
}

RunOutput SimulateOutput(const std::vector<std::unique_ptr<CacheSimulation>>& runs,
                         const SimulateConfig& cfg, bool per_sweep) {
  RunOutput o;
  o.tool = "meshreuse simulate";
  const RunOutput::TablePtr t = RunOutput::Share(SimulateTable(runs, per_sweep));
  const RunOutput::TablePtr arrays =
      cfg.by_array ? RunOutput::Share(SimulateArrayTable(runs)) : nullptr;
  o.csv = cfg.by_array ? arrays : t;
  o.json = o.csv;
  o.text.emplace_back(o.csv);
  o.text.emplace_back("(simulated: set-associative, write-allocate, " +
                      std::to_string(cfg.line_bytes) +
                      " B lines; each thread stream has private caches" +
                      (cfg.by_array ? "; per array: its lookups at each level and the misses "
                                      "among them, miss_share of the level's misses"
                                    : "") +
                      ")");
  o.tables.push_back({"simulate", t, {"csv", "json"}});
  if (cfg.by_array) o.tables.push_back({"simulate-arrays", arrays, {"csv", "json"}});
  o.configuration = SimulateConfigJson(cfg);
  return o;
}

RunOutput MachineOutput(const MachineSimulations& m, const SimulateConfig& cfg) {
  RunOutput o;
  o.tool = "meshreuse simulate";
  o.csv = RunOutput::Share(MachineTable(m.sims, cfg.warm));
  o.json = o.csv;
  const RunOutput::TablePtr summary = RunOutput::Share(MachineSummaryTable(m.runs));
  if (cfg.per_thread) {
    o.text.emplace_back(o.csv);
  } else {
    o.text.emplace_back(summary);
    o.text.emplace_back("");
    for (const std::string& s : MachineSentences(m.runs)) o.text.emplace_back(s);
  }
  if (!m.sims.empty()) {
    const Machine& mc = m.sims[0]->machine();
    o.text.emplace_back(
        "(simulated on " + mc.name + ": " + std::to_string(mc.sockets) + " socket(s) x " +
        std::to_string(mc.cores_per_socket) + " cores, interleave " +
        InterleaveName(cfg.interleave) + "; NUMA " +
        (mc.numa == Numa::kFirstTouch ? "first-touch: pages on socket 0" : "interleaved") +
        (cfg.per_thread
             ? "; per thread: accesses per level, memory local/remote, and on 'total' the cost "
               "model's cycles)"
             : "; per run, its last sweep: C(p) the cost model's cycles of the slowest thread at "
               "the low and high ends of the machine's latency ranges, Speedup(p) = C_ori(1) / "
               "C_ord(p), self = C_ord(1) / C_ord(p), Gain(p) = 1 - C_ord(p) / C_ref(p); misses "
               "summed over the threads; --per-thread for each thread's rows)"));
  }
  o.tables.push_back({"simulate", o.csv, {"csv", "json"}});
  o.tables.push_back({"summary", summary, {"csv"}});
  o.configuration = SimulateConfigJson(cfg);
  return o;
}

}  // namespace meshreuse
