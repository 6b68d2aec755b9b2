// The simulate runner; see simulate.h.
#include "reports/simulate.h"

#include <limits>

#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/schedule.h"
#include "reports/inputs.h"
#include "reports/rank_locality.h"
#include "reports/run_info.h"
#include "tracer/access_stream.h"

namespace meshreuse {

void CheckSimulateConfig(const SimulateConfig& cfg) {
  if (cfg.inputs.empty()) throw UsageError("no input given");
  if (!cfg.format.empty()) ParseTraceFormat(cfg.format);
  for (const std::string& o : cfg.orderings) CheckOrderingSpec(o);
  if (cfg.iterations < 1 || cfg.iterations > kMaxStreamSweeps)
    throw UsageError("--iterations must be 1..65536");
  if (cfg.threads < 1 || cfg.threads > kMaxThreads)
    throw UsageError("--threads must be 1.." + std::to_string(kMaxThreads));
  CheckStreamSweeps(cfg.iterations, cfg.threads);
  if (cfg.by_array && !cfg.machine.empty())
    throw UsageError("--by-array counts the private caches' misses: not with --machine");
  if (cfg.ranks > 0 && (!cfg.machine.empty() || !cfg.format.empty() || cfg.threads != 1))
    throw UsageError(
        "--ranks simulates each rank's part of a mesh (one stream per rank, private caches): "
        "no --machine, --format or --threads with it");
  CheckRankParts(cfg.ranks, cfg.partition, cfg.inputs);
  for (const CacheLevel& c : cfg.cache.levels)
    if (c.ways == 0)
      throw UsageError("cache level " + c.name + " needs its associativity for simulation, e.g. " +
                       c.name + "=32K/8");
  if (!cfg.machine.empty()) {
    Machine m = ParseMachine(cfg.machine);
    SetPrefetch(&m, cfg.prefetch);
    PlaceThreads(m, cfg.threads, cfg.placement);
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

std::vector<std::unique_ptr<MulticoreSimulation>> RunMachineSimulate(const SimulateConfig& cfg,
                                                                     const Log& log) {
  CheckSimulateConfig(cfg);
  Machine machine = ParseMachine(cfg.machine);
  SetPrefetch(&machine, cfg.prefetch);
  std::vector<std::unique_ptr<MulticoreSimulation>> runs;
  SmoothOptions sweeps;
  sweeps.max_iters = cfg.iterations;
  sweeps.tol = -std::numeric_limits<double>::infinity();
  sweeps.threads = cfg.threads;
  sweeps.mode = cfg.mode;
  sweeps.interleave = cfg.interleave;
  for (const std::string& in : cfg.inputs) {
    const InputKind kind = cfg.format.empty() ? ClassifyInput(in) : InputKind::kText;
    if (kind == InputKind::kMesh) {
      for (const std::string& ord : cfg.orderings) {
        Mesh m = LayOut(in, ord, cfg.seed, cfg.triangle_order, log);
        auto sim = std::make_unique<MulticoreSimulation>(machine, cfg.placement);
        log.Say("simulating " + std::to_string(cfg.iterations) + " sweep(s) of " + in + " in " +
                ord + " order on " + machine.name + ", " + std::to_string(cfg.threads) +
                " thread(s) " + PlacementName(cfg.placement));
        StreamMesh(m, sweeps, in, ParseOrderingSpec(ord).label, *sim);
        runs.push_back(std::move(sim));
      }
      continue;
    }
    auto sim = std::make_unique<MulticoreSimulation>(machine, cfg.placement);
    if (kind == InputKind::kTrace) {
      log.Say("simulating trace " + in + " on " + machine.name);
      StreamTraceFile(in, *sim);
    } else {
      const TraceFormat& f = ParseTraceFormat(cfg.format.empty() ? "text" : cfg.format);
      log.Say("simulating " + in + " as " + f.name + " on " + machine.name);
      StreamForeignTrace(in, f, cfg.instructions, *sim);
    }
    runs.push_back(std::move(sim));
  }
  return runs;
}

Table MachineTable(const std::vector<std::unique_ptr<MulticoreSimulation>>& runs, bool warm) {
  Table t(MulticoreSimulation::Columns());
  for (const auto& s : runs) s->AppendRows(&t, warm);
  return t;
}

std::vector<std::unique_ptr<CacheSimulation>> RunSimulate(const SimulateConfig& cfg,
                                                          const Log& log) {
  CheckSimulateConfig(cfg);
  std::vector<std::unique_ptr<CacheSimulation>> runs;
  auto make = [&cfg] {
    auto sim = std::make_unique<CacheSimulation>(cfg.cache, cfg.line_bytes);
    if (cfg.by_array) sim->CountByArray();
    return sim;
  };
  SmoothOptions sweeps;
  sweeps.max_iters = cfg.iterations;
  sweeps.tol = -std::numeric_limits<double>::infinity();
  sweeps.threads = cfg.threads;
  sweeps.mode = cfg.mode;
  for (const std::string& in : cfg.inputs) {
    const InputKind kind = cfg.format.empty() ? ClassifyInput(in) : InputKind::kText;
    if (kind == InputKind::kMesh && cfg.ranks > 0) {
      for (const std::string& ord : cfg.orderings) {
        RankLocalityConfig rc;
        rc.mesh = in, rc.ranks = cfg.ranks, rc.partition = cfg.partition, rc.ordering = ord;
        rc.placement = cfg.cut_placement;
        rc.seed = cfg.seed, rc.sweeps = sweeps;
        StreamRankParts(rc, log, [&](int32_t) -> AccessConsumer& {
          runs.push_back(make());
          return *runs.back();
        });
      }
      continue;
    }
    if (kind == InputKind::kMesh) {
      for (const std::string& ord : cfg.orderings) {
        Mesh m = LayOut(in, ord, cfg.seed, cfg.triangle_order, log);
        auto sim = make();
        log.Say("simulating " + std::to_string(cfg.iterations) + " sweep(s) of " + in + " in " +
                ord + " order");
        StreamMesh(m, sweeps, in, ParseOrderingSpec(ord).label, *sim);
        runs.push_back(std::move(sim));
      }
      continue;
    }
    auto sim = make();
    if (kind == InputKind::kTrace) {
      log.Say("simulating trace " + in);
      StreamTraceFile(in, *sim);
    } else {
      const TraceFormat& f = ParseTraceFormat(cfg.format.empty() ? "text" : cfg.format);
      log.Say("simulating " + in + " as " + f.name);
      StreamForeignTrace(in, f, cfg.instructions, *sim);
    }
    runs.push_back(std::move(sim));
  }
  return runs;
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
  Json j;
  j["inputs"] = cfg.inputs;
  j["format"] = cfg.format;
  j["orderings"] = cfg.orderings;
  j["seed"] = cfg.seed;
  j["ordering_seeds"] = OrderingSeedsJson(cfg.orderings, cfg.seed);
  j["iterations"] = cfg.iterations;
  j["threads"] = cfg.threads;
  j["mode"] = UpdateModeName(cfg.mode);
  if (cfg.machine.empty()) {
    j["cache"] = cfg.cache.text;
    j["line_bytes"] = cfg.line_bytes;
    j["by_array"] = cfg.by_array;
  } else {
    j["machine"] = cfg.machine;
    j["placement"] = PlacementName(cfg.placement);
    j["interleave"] = InterleaveName(cfg.interleave);
    j["prefetch"] = cfg.prefetch;
  }
  return j;
}

}  // namespace meshreuse
