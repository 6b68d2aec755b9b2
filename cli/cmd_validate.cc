// meshreuse simulate | validate: the set-associative cache simulator on a mesh (streamed), a
// trace file or another tool's trace; and the miss model's validation against it and against
// hardware counters where the machine has them, with the paper's Table 3 (reports/validation.h).
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "analysis/cache_sim.h"
#include "analysis/papi_counters.h"
#include "analysis/trace_analysis.h"
#include "cli/common.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/smoother.h"
#include "reports/run_info.h"
#include "reports/table.h"
#include "reports/validation.h"
#include "tracer/trace_reader.h"

namespace meshreuse::cli {

namespace {

std::vector<CacheLevel> SimulatedLevels(const std::string& spec) {
  try {
    std::vector<CacheLevel> l = ParseCacheSpec(spec);
    for (const CacheLevel& c : l)
      if (c.ways == 0)
        throw std::invalid_argument("cache level " + c.name +
                                    " needs its associativity for simulation, e.g. " + c.name +
                                    "=32K/8");
    return l;
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
}

void Print(const Table& t, bool json, bool csv) {
  if (json) {
    std::printf("%s", t.Json().c_str());
  } else if (csv) {
    std::printf("%s", t.Csv().c_str());
  } else {
    std::printf("%s", t.Aligned().c_str());
  }
}

}  // namespace

int SimulateCommand(const Args& args) {
  po::options_description desc("options");
  std::vector<std::string> inputs;
  std::string orderings = "ori", cache = "westmere-ex", mode = "gauss-seidel", format,
              triangle_order;
  int iterations = 1, threads = 1;
  uint32_t line_bytes = 64;
  uint64_t seed = 1;
  desc.add_options()("input", po::value(&inputs)->required()->multitoken(),
                     "mesh(es) (the smoother streams into the simulator), a trace file from "
                     "`meshreuse trace`, or another tool's trace with --format ('-': stdin)")(
      "orderings", po::value(&orderings)->default_value("ori"),
      "for meshes: comma-separated orderings")("seed", po::value(&seed)->default_value(1),
                                               "seed of randomised orderings")(
      "iterations,k", po::value(&iterations)->default_value(1), "for meshes: sweeps to simulate")(
      "threads,t", po::value(&threads)->default_value(1), "for meshes: streams (static schedule)")(
      "mode", po::value(&mode)->default_value("gauss-seidel"),
      "for meshes: gauss-seidel or jacobi")(
      "format", po::value(&format),
      "other tools' traces: text, u32, u64 (each value a byte address, a 1-byte access)")(
      "cache", po::value(&cache)->default_value("westmere-ex"),
      "westmere-ex (L1=32K/8,L2=256K/8,L3=24M/24) or a list NAME=SIZE/WAYS,...")(
      "line-bytes", po::value(&line_bytes)->default_value(64), "cache line size (a power of two)")(
      "per-sweep", "one row per sweep as well (meshes and trace files)")("json", "print JSON")(
      "csv", "print CSV")("quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("input", -1);
  po::variables_map vm;
  if (!ParseOptions(args, "simulate INPUT... [--orderings ori,bfs,rdr] [--cache L1=32K/8,...]",
                    "Set-associative LRU simulation (valgrind's model: write-allocate, an access "
                    "straddling two lines counts once and misses if either misses, each level sees "
                    "the misses of the one above) of every load and store: hits, misses, cold "
                    "misses and the excess over them, per level and thread stream.",
                    desc, pos, vm))
    return 0;
  CheckOneFormat(vm);
  if (iterations < 1 || iterations > 100000) throw po::error("--iterations must be 1..100000");
  if (threads < 1 || threads > 255) throw po::error("--threads must be 1..255");
  if (line_bytes == 0 || (line_bytes & (line_bytes - 1)))
    throw po::error("--line-bytes must be a power of two");
  const std::vector<CacheLevel> levels = SimulatedLevels(cache);
  const std::vector<std::string> ords = SplitList(orderings);
  CheckOrderings(ords);
  const TriangleOrder tri_order = TriangleOrderOption(triangle_order);
  ExternalFormat fmt = ExternalFormat::kText;
  try {
    if (!format.empty()) fmt = ParseExternalFormat(format);
    CacheHierarchy(levels, line_bytes);  // rejects a size that is no multiple of ways x line
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
  const Progress progress(vm.count("quiet") > 0);
  const bool per_sweep = vm.count("per-sweep") > 0;

  Table t({"input", "ordering", "thread", "sweep", "level", "size", "ways", "sets", "accesses",
           "hits", "misses", "cold", "excess", "miss_rate", "read_misses", "write_misses"});
  auto rows = [&](const std::string& in, const std::string& ord, const CacheSimulation& sim) {
    for (int th = 0; th < sim.threads(); ++th) {
      std::vector<std::pair<std::string, std::vector<LevelStats>>> parts = {{"all", sim.Stats(th)}};
      if (per_sweep)
        for (size_t s = 0; s < sim.sweeps(); ++s)
          parts.emplace_back(std::to_string(s + 1), sim.SweepStats(th, s));
      for (const auto& [sweep, st] : parts)
        for (size_t i = 0; i < levels.size(); ++i) {
          const LevelStats& s = st[i];
          t.AddRow({in, ord, std::to_string(th), sweep, levels[i].name,
                    std::to_string(levels[i].bytes), std::to_string(levels[i].ways),
                    std::to_string(levels[i].bytes / line_bytes / levels[i].ways),
                    std::to_string(s.accesses), std::to_string(s.accesses - s.misses),
                    std::to_string(s.misses), std::to_string(s.cold),
                    std::to_string(s.misses - s.cold), JsonNumber(s.MissRate()),
                    std::to_string(s.read_misses), std::to_string(s.write_misses)});
        }
    }
  };
  for (const std::string& in : inputs) {
    if (format.empty() && in != "-" && IsMesh(in)) {
      for (const std::string& ord : ords) {
        Mesh m = LayOut(in, ord, seed, tri_order, progress);
        SmoothOptions so;
        so.max_iters = iterations;
        so.tol = -std::numeric_limits<double>::infinity();
        so.threads = threads;
        try {
          so.mode = ParseUpdateMode(mode);
        } catch (const std::invalid_argument& e) {
          throw po::error(e.what());
        }
        CacheSimulation sim(levels, line_bytes, threads);
        progress.Say("simulating " + std::to_string(iterations) + " sweep(s) of " + in + " in " +
                     ord + " order");
        CacheSimSink sink{&sim};
        Smooth(m, so, sink);
        rows(in, ord, sim);
      }
    } else if (format.empty() && in != "-") {
      TraceReader r(in);
      const TraceHeader& h = r.header();
      CacheSimulation sim(levels, line_bytes, static_cast<int>(h.threads));
      progress.Say("simulating trace " + in + " (" + Grouped(static_cast<long long>(h.records)) +
                   " accesses)");
      std::vector<TraceRecord> batch;
      uint64_t seen = 0;
      size_t next_sweep = 0;
      while (r.Next(&batch))
        for (const TraceRecord& rec : batch) {
          while (next_sweep < h.iteration_starts.size() && h.iteration_starts[next_sweep] == seen) {
            sim.BeginSweep();
            ++next_sweep;
          }
          ++seen;
          if (rec.thread >= h.threads)
            throw InputError(in, 0,
                             "record " + std::to_string(seen) + " has thread " +
                                 std::to_string(rec.thread) + " beyond the header's " +
                                 std::to_string(h.threads));
          sim.Access(rec.thread, rec.address, rec.size, (rec.array & kStoreBit) != 0);
        }
      rows(in, h.ordering.empty() ? "?" : h.ordering, sim);
    } else {
      CacheSimulation sim(levels, line_bytes, 1);
      progress.Say("simulating " + in + " as " + (format.empty() ? "text" : format));
      ReadExternalTrace(in, fmt,
                        [&sim](uint64_t v, uint32_t size) { sim.Access(0, v, size, false); });
      rows(in, "", sim);
    }
  }
  Print(t, vm.count("json") > 0, vm.count("csv") > 0);
  if (!vm.count("json") && !vm.count("csv"))
    std::printf(
        "(simulated: set-associative LRU, write-allocate, %u B lines; each thread stream "
        "has private caches)\n",
        line_bytes);
  return 0;
}

int ValidateCommand(const Args& args) {
  po::options_description desc("options");
  std::string mesh, orderings = "ori,bfs,rdr", cache = "westmere-ex", mode = "gauss-seidel",
                    triangle_order, counters = "PAPI_L1_DCM,PAPI_L2_DCM,PAPI_L3_TCM", out_dir;
  ValidationConfig cfg;
  desc.add_options()("mesh", po::value(&mesh)->required(), "input mesh")(
      "orderings", po::value(&orderings)->default_value(orderings), "comma-separated orderings")(
      "seed", po::value(&cfg.seed)->default_value(1), "seed of randomised orderings")(
      "iterations,k", po::value(&cfg.iterations)->default_value(2), "sweeps")(
      "threads,t", po::value(&cfg.threads)->default_value(1), "streams (static schedule)")(
      "mode", po::value(&mode)->default_value("gauss-seidel"), "gauss-seidel or jacobi")(
      "cache", po::value(&cache)->default_value("westmere-ex"),
      "westmere-ex (L1=32K/8,L2=256K/8,L3=24M/24) or NAME=SIZE/WAYS,...")(
      "element-bytes", po::value(&cfg.element_bytes)->default_value(66),
      "element size of the element model (the paper's 66-byte nodes)")(
      "line-bytes", po::value(&cfg.line_bytes)->default_value(64), "cache line size")(
      "counters", po::value(&counters)->default_value(counters),
      "PAPI events for the levels, in level order ('none': simulate only)")(
      "exclude-cold", "Table 3: take cold misses as compulsory and invert the rest")(
      "markdown", "print Markdown tables")("json", "print JSON")("csv", "print CSV")(
      "out", po::value(&out_dir),
      "write validate.{csv,md,json}, table3.{csv,md}, sweeps.csv and run.json here")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "validate MESH [--orderings ori,bfs,rdr] [--iterations K] [--threads P]",
          "Validates the miss model: per ordering and cache level, the fully associative model "
          "(element and line), the set-associative simulation and hardware counters (PAPI, "
          "where the machine has them; otherwise every number is labelled simulated), their "
          "ratios, miss rates and the equation-2 cost; then the paper's Table 3 (misses and the "
          "inverse model's capacities) beside the paper's values.",
          desc, pos, vm))
    return 0;
  CheckOneFormat(vm);
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  if (cfg.iterations < 1 || cfg.iterations > 100000)
    throw po::error("--iterations must be 1..100000");
  if (cfg.threads < 1 || cfg.threads > 255) throw po::error("--threads must be 1..255");
  if (cfg.line_bytes == 0 || (cfg.line_bytes & (cfg.line_bytes - 1)))
    throw po::error("--line-bytes must be a power of two");
  if (cfg.element_bytes == 0) throw po::error("--element-bytes must be positive");
  cfg.levels = SimulatedLevels(cache);
  try {
    cfg.mode = ParseUpdateMode(mode);
    CacheHierarchy(cfg.levels, cfg.line_bytes);
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
  cfg.orderings = SplitList(orderings);
  CheckOrderings(cfg.orderings);
  cfg.triangle_order = TriangleOrderOption(triangle_order);
  cfg.counter_events = counters == "none" ? std::vector<std::string>{} : SplitList(counters);
  cfg.exclude_cold = vm.count("exclude-cold") > 0;
  cfg.mesh_name = std::filesystem::path(mesh).filename().string();
  if (!out_dir.empty() && std::filesystem::exists(out_dir) &&
      !std::filesystem::is_directory(out_dir))
    throw po::error("--out " + out_dir + " exists and is not a folder");
  const Progress progress(vm.count("quiet") > 0);
  if (!cfg.counter_events.empty()) {  // said once, before the work
    const PapiCounters probe(cfg.counter_events, 1);
    if (!probe.reason().empty())
      std::fprintf(stderr, "meshreuse: note: counters: %s%s\n", probe.reason().c_str(),
                   probe.available() ? "" : "; every miss below is simulated");
  }
  const Mesh base = LoadMesh(mesh, progress);
  const std::vector<OrderingValidation> r =
      RunValidation(base, cfg, [&](const std::string& s) { progress.Say(s); });

  const Table v = ValidationTable(r), t3 = Table3(r), sw = ValidationSweepTable(r);
  Table cost({"mesh", "ordering", "accesses", "element_accesses", "cost_model_low",
              "cost_model_high", "cost_simulated_low", "cost_simulated_high", "counters"});
  for (const OrderingValidation& o : r)
    cost.AddRow({o.mesh, o.ordering, std::to_string(o.line_accesses),
                 std::to_string(o.element_accesses), Fixed(o.cost_model.low, 0),
                 Fixed(o.cost_model.high, 0), Fixed(o.cost_simulated.low, 0),
                 Fixed(o.cost_simulated.high, 0), o.counters});
  const std::vector<std::string> notes = Table3Notes(r, cfg.exclude_cold);
  if (vm.count("json")) {
    std::printf("{\"validation\": %s, \"table3\": %s, \"cost\": %s}\n", v.Json().c_str(),
                t3.Json().c_str(), cost.Json().c_str());
  } else if (vm.count("csv")) {
    std::printf("%s", v.Csv().c_str());
  } else if (vm.count("markdown")) {
    std::printf("%s\n%s\n%s", v.Markdown().c_str(), cost.Markdown().c_str(), t3.Markdown().c_str());
    for (const std::string& n : notes) std::printf("\n%s\n", n.c_str());
  } else {
    std::printf("%s\n%s\n%s", v.Aligned().c_str(), cost.Aligned().c_str(), t3.Aligned().c_str());
    for (const std::string& n : notes) std::printf("%s\n", n.c_str());
  }
  if (!out_dir.empty()) {
    WriteText(out_dir + "/validate.csv", v.Csv());
    WriteText(out_dir + "/validate.md", v.Markdown());
    WriteText(out_dir + "/validate.json", v.Json());
    WriteText(out_dir + "/cost.csv", cost.Csv());
    WriteText(out_dir + "/table3.csv", t3.Csv());
    std::string md = t3.Markdown();
    for (const std::string& n : notes) md += "\n" + n + "\n";
    WriteText(out_dir + "/table3.md", md);
    WriteText(out_dir + "/sweeps.csv", sw.Csv());
    WriteText(out_dir + "/run.json",
              "{\n" + RunJsonHeader("meshreuse validate") + "  \"config\": {\"mesh\": " +
                  JsonString(mesh) + ", \"orderings\": " + JsonString(orderings) + ", \"seed\": " +
                  std::to_string(cfg.seed) + ", \"iterations\": " + std::to_string(cfg.iterations) +
                  ", \"threads\": " + std::to_string(cfg.threads) +
                  ", \"mode\": " + JsonString(mode) + ", \"cache\": " + JsonString(cache) +
                  ", \"element_bytes\": " + std::to_string(cfg.element_bytes) +
                  ", \"line_bytes\": " + std::to_string(cfg.line_bytes) +
                  ", \"triangle_order\": " + JsonString(triangle_order) +
                  ", \"exclude_cold\": " + (cfg.exclude_cold ? "true" : "false") +
                  ", \"counters\": " + JsonString(r.empty() ? "" : r[0].counters) + "}\n}\n");
    progress.Say("wrote " + out_dir +
                 "/{validate.csv,validate.md,validate.json,cost.csv,table3.csv,table3.md,"
                 "sweeps.csv,run.json}");
  }
  return 0;
}

}  // namespace meshreuse::cli
