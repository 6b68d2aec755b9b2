// meshreuse simulate: the set-associative cache simulator on meshes, trace files or other tools'
// traces (reports/simulate.h).
#include <cstdio>
#include <string>

#include "analysis/machine.h"
#include "cli/common.h"
#include "cli/configs.h"
#include "core/error.h"
#include "reports/simulate.h"
#include "tracer/access_stream.h"
#include "tracer/trace_formats.h"

namespace meshreuse::cli {

namespace {

// Parses `args` into cfg, vm and out_dir: false when --help was printed.
bool ParseSimulate(const Args& args, const InMemory& in_memory, SimulateConfig& cfg,
                   po::variables_map& vm, std::string& out_dir) {
  po::options_description desc("options");
  std::string cache = "westmere-ex", line_bytes = "64", placement = "compact", interleave = "1";
  SourceOptionText source;
  desc.add_options()("input", po::value(&cfg.inputs)->required()->multitoken(),
                     "mesh(es) (the smoother streams into the simulator), a trace file from "
                     "`meshreuse trace`, or another tool's trace with --format ('-': stdin)");
  const std::string format_help =
      "other tools' traces (values are byte addresses; any may be zstd-compressed):\n" +
      TraceFormatHelp();
  SourceHelp help;
  help.iterations = "for meshes: sweeps to simulate";
  help.thread_list = true;
  help.threads =
      "for meshes: streams (static schedule); with --machine a list, a run per count (1,4,32)";
  help.format = format_help;
  help.instructions =
      "lackey: simulate instruction fetches (I lines) too: through a level named I1 "
      "(cachegrind's instruction cache) and the data levels below the first, or the data path "
      "when there is no I1";
  help.ranks =
      "meshes, private caches: simulate each of P ranks' parts as the distributed smoother lays it "
      "out and sweeps it (--orderings inside each part): one row per rank and level";
  AddSourceOptions(desc, &cfg, &source, help);
  desc.add_options()("cache", po::value(&cache)->default_value("westmere-ex"),
                     "westmere-ex (alias westmere: L1=32K/8,L2=256K/8,L3=24M/24) or "
                     "NAME=SIZE/WAYS[/lru|fifo|random],... "
                     "(cachegrind's: I1=32K/8,D1=32K/8,LL=8M/16)")(
      "line-bytes", po::value(&line_bytes)->default_value("64"),
      "cache line size (a power of two)")("per-sweep",
                                          "one row per sweep as well (meshes and trace files)")(
      "by-array",
      "print each level's lookups and misses per array instead (the smoother's arrays: xy, "
      "v2v.idx, ..., a rank's send.buf and recv.buf; 'trace' for other tools' traces); with "
      "--out also simulate-arrays.{csv,json}")(
      "machine", po::value(&cfg.machine),
      "westmere-ex (alias westmere) or a machine file: the many-core simulator (sockets, private "
      "and shared "
      "levels, inclusion, coherence, NUMA; --threads up to its cores) instead of --cache")(
      "placement", po::value(&placement)->default_value(placement),
      "with --machine: compact (fill socket 0 first, OpenMP proc_bind(close)) or scatter "
      "(thread t on socket t % sockets, proc_bind(spread)), or both: compact,scatter")(
      "interleave", po::value(&interleave)->default_value(interleave),
      "with --machine: how the threads' streams meet: serial (whole shares in turn), access "
      "(a visit each per turn, accesses dealt one at a time) or N vertex visits per turn")(
      "prefetch", po::value(&cfg.prefetch),
      "with --machine: levels with a next-line prefetcher, e.g. L1,L2 (none: off)")(
      "warm",
      "with --machine: per-thread rows of the last sweep only (caches warm from those "
      "before; the summary is always the last sweep's)")(
      "per-thread", "with --machine: print each thread's rows instead of the summary")(
      "out", po::value(&out_dir), "write simulate.{csv,json} and run.json here")(
      "quiet,q", "no progress on stderr");
  AddFormatOptions(desc);
  po::positional_options_description pos;
  pos.add("input", -1);
  if (!ParseOptions(args, "simulate INPUT... [--orderings ori,bfs,rdr] [--cache L1=32K/8,...]",
                    "Set-associative simulation (valgrind's model: LRU by default, write-allocate, "
                    "an access straddling two lines counts once and misses if either misses, each "
                    "level sees the misses of the one above) of every load and store: hits, "
                    "misses, cold misses and the excess over them, read, write and instruction "
                    "fetch misses, per level and thread stream.",
                    desc, pos, vm))
    return false;
  SourceOf(source, vm, &cfg);
  if (in_memory) in_memory(cfg);
  cfg.line_bytes = static_cast<uint32_t>(ParseCount(line_bytes, "--line-bytes", 1, 1 << 20));
  cfg.cache = ParseCacheSpec(cache);
  cfg.placements.clear();
  for (const std::string& pl : SplitList(placement)) cfg.placements.push_back(ParsePlacement(pl));
  if (source.thread_list.size() > 1) cfg.machine_threads = source.thread_list;
  cfg.warm = vm.count("warm") > 0;
  cfg.per_thread = vm.count("per-thread") > 0;
  cfg.machine = CanonicalMachine(cfg.machine);
  if (!cfg.machine.empty()) cfg.interleave = ParseInterleave(interleave);
  cfg.by_array = vm.count("by-array") > 0;
  if (!cfg.machine.empty() && !vm["cache"].defaulted())
    throw UsageError("--cache and --machine exclude each other (a machine names its caches)");
  if (cfg.machine.empty())
    for (const char* o : {"placement", "interleave"})
      if (!vm[o].defaulted()) throw UsageError(std::string("--") + o + " needs --machine");
  // A trace file holds its streams one after another, so only the serial meeting can be
  // simulated from it (and is, said so); a mesh's streams are generated side by side, at any
  // interleaving.
  if (!cfg.machine.empty()) {
    bool traces = !cfg.inputs.empty();
    for (const std::string& in : cfg.inputs) {
      const bool trace = cfg.KindOf(in) != InputKind::kMesh;
      if (trace && !vm["interleave"].defaulted() && cfg.interleave != kSerialShares)
        throw UsageError("--interleave " + interleave + ": " + in +
                         " is a trace file, whose streams follow one another: it can only be "
                         "simulated serially (--interleave serial); give the mesh to interleave "
                         "its streams");
      traces = traces && trace;
    }
    if (traces) cfg.interleave = kSerialShares;
  }
  if (cfg.machine.empty() && (!cfg.prefetch.empty() || cfg.warm || cfg.per_thread))
    throw UsageError("--prefetch, --warm and --per-thread need --machine");
  CheckSimulateConfig(cfg);
  return true;
}

}  // namespace

SimulateConfig SimulateConfigFromArgs(const Args& args, const InMemory& in_memory) {
  SimulateConfig cfg;
  po::variables_map vm;
  std::string out_dir;
  if (!ParseSimulate(args, in_memory, cfg, vm, out_dir))
    throw UsageError("--help is the command's");
  RefuseCommandOptions(vm, {"out", "json", "csv", "quiet", "per-sweep"});
  return cfg;
}

int SimulateCommand(const Args& args) {
  SimulateConfig cfg;
  po::variables_map vm;
  std::string out_dir;
  if (!ParseSimulate(args, {}, cfg, vm, out_dir)) return 0;
  const OutputFormat fmt = FormatOption(vm);
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  const Progress progress(vm.count("quiet") > 0);
  if (!cfg.machine.empty())
    Emit(MachineOutput(RunMachineSimulate(cfg, MakeLog(progress)), cfg), fmt, out_dir, progress);
  else
    Emit(SimulateOutput(RunSimulate(cfg, MakeLog(progress)), cfg, vm.count("per-sweep") > 0), fmt,
         out_dir, progress);
  return 0;
}

}  // namespace meshreuse::cli
