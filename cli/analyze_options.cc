// analyze's options (analyze_options.h).
#include "cli/analyze_options.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "reports/chunks/summarize_chunk.h"
#include "tracer/trace_formats.h"

namespace meshreuse::cli {

namespace {

void AddAnalyzeOptions(po::options_description& desc, AnalyzeConfig* cfg, AnalyzeOptionText* out) {
  AnalyzeOptionText& t = *out;
  desc.add_options()(
      "input", po::value(&cfg->inputs)->required()->multitoken(),
      "mesh(es) (.node/.ele/.msh: the smoother streams into the analyzer), a trace file from "
      "`meshreuse trace` (plain or zstd), or another tool's trace with --format ('-': stdin)");
  static const std::string format_help =
      "other tools' traces (any may be zstd-compressed):\n" + TraceFormatHelp();
  SourceHelp help;
  help.seed = "seed of seeded orderings and of the sampling hash";
  help.iterations = "for meshes: sweeps to analyse";
  help.threads =
      "for meshes: the smoother's threads (one stream each); for trace files: the analyzer's "
      "threads (exact): a file is cut into one chunk per thread, each read by its own thread "
      "(zstd: when in as many frames, as `trace --compress` writes them); standard input or a "
      "zstd trace in fewer frames is read by one thread in batches";
  help.format = format_help;
  help.instructions = "lackey: count instruction fetches (I lines) too, not only data";
  help.ranks =
      "meshes: analyse each of P ranks' parts as the distributed smoother lays it out and sweeps "
      "it (owned non-cut, cut, boundary, ghosts; --orderings inside each part): one row per rank";
  AddSourceOptions(desc, cfg, &t.source, help);
  desc.add_options()(
      "granularity", po::value(&t.granularity),
      "element, line or both (default: both for meshes and meshreuse traces; line for address "
      "traces: lackey, parda, u32, u64; element for id traces: text, oracle)")(
      "quantiles", po::value(&t.quantiles)->default_value("50,75,90,100"),
      "percentages to report, each in 0..100")(
      "cache", po::value(&t.cache)->default_value("westmere-ex"),
      "westmere-ex (alias westmere) or NAME=SIZE[/WAYS[/POLICY]][@CYCLES],... and mem@CYCLES")(
      "element-bytes", po::value(&t.element_bytes)->default_value("66"),
      "element size for the element miss model")("line-bytes",
                                                 po::value(&t.line_bytes)->default_value("64"),
                                                 "cache line size (a power of two)")(
      "measured-misses", po::value(&t.measured),
      "inverse model: L1=N,L2=N,... measured misses -> the capacity (elements or lines) that "
      "explains them")("sample-rate", po::value(&t.sample_rate),
                       "approximate instead: SHARDS at this fixed rate (e.g. 0.01)")(
      "sample-size", po::value(&t.sample_size),
      "approximate instead: SHARDS tracking at most this many ids (fixed size)")(
      "sample-exact-below", po::value(&t.sample_exact_below),
      "with --sample-*: count the distances below K exactly (every access through an exact LRU "
      "stack of depth K, memory O(K)); the miss ratio at every capacity up to K and every "
      "quantile below K are then exact, where SHARDS' scaling is coarsest. Default: the first "
      "cache level's capacity in lines or elements, whichever is more (512 for westmere-ex); 0 "
      "turns it off; chunks and ranks sample every distance")(
      "sample-error",
      "with --sample-*: run the exact analysis too and report the miss-ratio curve's mean "
      "absolute error")("histogram-csv", po::value(&t.hist_csv),
                        "write the histograms (exact < 64, powers of two beyond, and cold)")(
      "profile-csv", po::value(&t.prof_csv),
      "write the profiles (each sweep in 100 steps; fewer, at least 1, beyond 2,621 sweeps x "
      "streams)")(
      "vtk", po::value(&cfg->vtk),
      "one mesh, one ordering: write the laid-out mesh for ParaView (PATH.vtu: VTK XML, "
      "compressed; "
      "any other name: legacy VTK) with each vertex's rank, original id and the reuse distances "
      "of its touches (mean, max, cold)")(
      "mrc-csv", po::value(&t.mrc_csv),
      "write the miss-ratio curves (capacity -> misses, miss ratio; exact, or the estimate when "
      "sampling)")("out", po::value(&t.out_dir),
                   "write analyze.{csv,json}, histogram.csv, profile.csv, run.json")(
      "chunk", po::value(&t.chunk),
      "r/P: analyse only chunk r (0-based) of P equal parts of one input and write its summary "
      "(--summary-out): records of a meshreuse or fixed-record trace, whole lines of a text or "
      "lackey one (plain files), or of a mesh's stream in one ordering (regenerated, no file); any "
      "batch system can run the P chunks, then --merge")(
      "summary-out", po::value(&cfg->summary_out), "with --chunk: the summary file to write")(
      "merge",
      "the inputs are the summaries of chunks 0..P-1, in order: merge them into exactly the "
      "serial analysis (every table and output below)")(
      "scatter-from", po::value(&t.scatter_from),
      "meshreuse-mpi, or --threads over a plain trace file: from N ranks (threads) on, add the "
      "histograms up by distance, each rank one slice of every rank's (a reduce-scatter; below, "
      "up a tree of ranks: fewer steps, but log2 P merges of whole lists on the way to rank 0); "
      "default 16")(
      "rank-stats", po::value(&t.rank_stats),
      "meshreuse-mpi, or --threads over a plain trace file (a chunk per thread): write each "
      "rank's (thread's) CPU seconds per phase, wall seconds, records, distinct ids, stack ids "
      "received and sent, bytes sent and peak memory (JSON) to this file")("quiet,q",
                                                                           "no progress on stderr");
  AddFormatOptions(desc);
}

// The configuration the options give (UsageError for what they cannot).
void AnalyzeConfigOf(AnalyzeOptionText& t, const po::variables_map& vm, AnalyzeConfig* cfg) {
  SourceOf(t.source, vm, cfg);
  if (!t.granularity.empty()) cfg->granularity = ParseGranularity(t.granularity);
  cfg->quantiles = ParseQuantiles(t.quantiles);
  cfg->cache = ParseCacheSpec(t.cache);
  if (!t.measured.empty()) cfg->inverse = ParseCacheSpec(t.measured).levels;
  cfg->element_bytes =
      static_cast<uint32_t>(ParseCount(t.element_bytes, "--element-bytes", 1, 1 << 20));
  cfg->line_bytes = static_cast<uint32_t>(ParseCount(t.line_bytes, "--line-bytes", 1, 1 << 20));
  cfg->profile = !t.prof_csv.empty() || !t.out_dir.empty();
  cfg->sample = vm.count("sample-rate") || vm.count("sample-size");
  if (vm.count("sample-rate") && vm.count("sample-size"))
    throw UsageError("--sample-rate and --sample-size exclude each other");
  if (vm.count("sample-rate") && !(t.sample_rate > 0 && t.sample_rate <= 1))
    throw UsageError("--sample-rate must be in (0, 1]");
  if (vm.count("sample-size"))
    cfg->shards.s_max = ParseCount(t.sample_size, "--sample-size", 1, 1u << 30);
  cfg->shards.rate = cfg->sample && !cfg->shards.s_max ? t.sample_rate : 1;
  cfg->shards.seed = cfg->seed;
  cfg->sample_error = vm.count("sample-error") > 0;
  cfg->scatter_from_ranks =
      static_cast<int32_t>(ParseCount(t.scatter_from, "--scatter-from", 1, uint64_t{1} << 20));
  if (!t.sample_exact_below.empty()) {
    if (!cfg->sample) throw UsageError("--sample-exact-below needs --sample-rate or --sample-size");
    cfg->shards.exact_below = static_cast<uint32_t>(
        ParseCount(t.sample_exact_below, "--sample-exact-below", 0, uint64_t{1} << 26));
  }
  if (cfg->sample)
    for (const CacheLevel& l : cfg->cache.levels) {
      cfg->watch_element.push_back(l.bytes / cfg->element_bytes);
      cfg->watch_line.push_back(l.bytes / cfg->line_bytes);
    }
  if (cfg->sample_error && !cfg->sample)
    throw UsageError("--sample-error needs --sample-rate or --sample-size");
  if (!t.chunk.empty()) cfg->chunk = ParseChunk(t.chunk);
  cfg->merge = vm.count("merge") > 0;
  // What the chunk runs decided (their summaries say it) is refused at the merge, not ignored.
  if (cfg->merge)
    for (const char* o : {"orderings", "seed", "iterations", "threads", "mode", "triangle-order",
                          "instructions", "ranks", "line-bytes", "scatter-from", "rank-stats"})
      if (vm.count(o) && !vm[o].defaulted())
        throw UsageError(std::string("--merge: --") + o +
                         " was the chunk runs' to choose (their summaries hold it): give it to "
                         "`analyze --chunk`, not here");
}

}  // namespace

bool ParseAnalyze(const Args& args, Communicator* transport, const InMemory& in_memory,
                  AnalyzeConfig* cfg, AnalyzeOptionText* t, po::variables_map* vm) {
  po::options_description desc("options");
  AddAnalyzeOptions(desc, cfg, t);
  po::positional_options_description pos;
  pos.add("input", -1);
  if (!ParseOptions(args,
                    "analyze INPUT... [--orderings ori,bfs,rdr] [--iterations K] [--json|--csv]",
                    "Exact LRU reuse distances (element = vertex id, line = address / line size; "
                    "each thread's stream on its own): accesses, cold, distinct, the exact sum and "
                    "mean, quantiles, modelled misses per cache level (fully associative LRU) and "
                    "the paper's equation-2 cost. Several meshes x --orderings print the paper's "
                    "Table 2. With --sample-rate or --sample-size: a SHARDS estimate instead.",
                    desc, pos, *vm))
    return false;
  AnalyzeConfigOf(*t, *vm, cfg);
  if (in_memory) in_memory(*cfg);
  cfg->transport = transport;
  // Sampling counts the distances below the first cache level's capacity exactly unless told
  // (--sample-exact-below N, 0: off), where the whole stream passes in order: not in chunks.
  if (cfg->sample && t->sample_exact_below.empty() && !transport && !cfg->chunk && !cfg->merge &&
      !cfg->cache.levels.empty())
    cfg->shards.exact_below = static_cast<uint32_t>(std::min<uint64_t>(
        uint64_t{1} << 26,
        cfg->cache.levels[0].bytes / std::min(cfg->element_bytes, cfg->line_bytes)));
  CheckAnalyzeConfig(*cfg);
  return true;
}

AnalyzeConfig AnalyzeConfigFromArgs(const Args& args, const InMemory& in_memory) {
  AnalyzeConfig cfg;
  AnalyzeOptionText t;
  po::variables_map vm;
  if (!ParseAnalyze(args, nullptr, in_memory, &cfg, &t, &vm))
    throw UsageError("--help is the command's");
  RefuseCommandOptions(
      vm, {"histogram-csv", "profile-csv", "mrc-csv", "out", "rank-stats", "json", "csv", "quiet"});
  return cfg;
}

}  // namespace meshreuse::cli
