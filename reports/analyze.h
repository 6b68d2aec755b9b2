// The runner behind `meshreuse analyze`: exact LRU reuse distances (or a SHARDS estimate) of
// meshes streamed through the traced smoother (one run per mesh x ordering), meshreuse trace files
// and other tools' traces, each through tracer/access_stream.h into a ReuseAnalysis. Then the
// tables: one row per input x ordering x thread stream x granularity with accesses, cold, distinct
// ids, the exact sum and mean, quantiles, modelled misses per cache level (fully associative LRU),
// the equation-2 cost where latencies are known, and the inverse model's capacities; and the
// histograms, profiles and miss-ratio curves in the analysis' own schemas.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "analysis/reuse_analysis.h"
#include "core/permutation.h"
#include "core/ranks/rank_part.h"
#include "core/smoother.h"
#include "core/table.h"
#include "reports/log.h"
#include "reports/run_info.h"

namespace meshreuse {

class Communicator;

struct AnalyzeConfig {
  std::vector<std::string> inputs;  // meshes, meshreuse traces, or other tools' traces ("-": stdin)
  std::string format;               // "": meshes and meshreuse traces; else a TraceFormat name
  std::vector<std::string> orderings = {"ori"};  // for meshes
  uint64_t seed = 1;                             // orderings and the sampling hash
  int iterations = 1;                            // for meshes: sweeps
  // For meshes: the smoother's threads (one stream each); for trace files: the analyzer's
  // threads (exact): a plain file in a chunk per thread (chunk_threads.h), else batches
  // (ReuseOptions::workers).
  int threads = 1;
  UpdateMode mode = UpdateMode::kGaussSeidel;
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  // Default: both for meshes and meshreuse traces; line for address traces, element for ids.
  std::optional<Granularity> granularity;
  std::vector<double> quantiles = {0.5, 0.75, 0.9, 1.0};  // fractions
  CacheSpec cache = ParseCacheSpec("westmere-ex");
  uint32_t element_bytes = 66, line_bytes = 64;
  std::vector<CacheLevel> inverse;  // measured misses per level (bytes holds the count)
  bool sample = false;              // SHARDS instead of (or with sample_error, beside) exact
  bool sample_error = false;
  ShardsOptions shards;
  bool instructions = false;  // lackey: instruction fetches count too
  bool profile = true;        // compute the profiles (the CLI asks only when it writes them)
  // One mesh x one ordering: write the laid-out mesh (before the sweeps) as VTK with, per vertex,
  // its rank in the ordering, its original id and the reuse distances of its element touches
  // over the analysed sweeps (mean, max, cold touches): the ordering and its locality in ParaView.
  std::string vtk;
  // Chunk summaries (reports/chunk_summary.h): analyse chunk (r, P) of the one trace into
  // summary_out; or, with merge, the inputs are the summaries of chunks 0..P-1, merged.
  std::optional<std::pair<uint32_t, uint32_t>> chunk;
  std::string summary_out;
  bool merge = false;
  // Meshes: analyse each of `ranks` parts as a rank of the distributed smoother lays it out and
  // sweeps it (reports/rank_locality.h; the orderings apply inside each part), 0: the whole mesh.
  int32_t ranks = 0;
  std::string partition = "hilbert";
  CutPlacement cut_placement = CutPlacement::kLast;
  // A distributed run (one trace, chunk = rank of size ranks; reports/chunk_summary.h): the
  // message layer, or nullptr.
  Communicator* transport = nullptr;
  // From this many ranks on, a distributed run adds its histograms up by distance (a
  // reduce-scatter, each rank one slice), below up a tree of ranks (RunDistributed).
  int32_t scatter_from_ranks = 16;
};

// What one rank of a distributed run spent (reports/chunk_summary.h, RunDistributed): thread CPU
// seconds per phase, wall seconds, what it held and sent. The scaling model's constants
// (scripts/scale_mpi.sh) come from these.
struct RankStats {
  int rank = 0;
  double analyse_cpu = 0, stream_cpu = 0, resolve_cpu = 0, reduce_cpu = 0, wall = 0;
  uint64_t records = 0, accesses = 0, distinct = 0, stack_ids_in = 0, stack_ids_sent = 0,
           bytes_sent = 0, peak_rss_bytes = 0;
  // The reuse-distance counters this rank held at most at once: its chunks' resolved histograms,
  // on rank 0 also the merged ones (paged: reuse_histogram.h); and what one array as long as the
  // largest distance would have taken (8 bytes a distance), for comparison.
  uint64_t histogram_bytes = 0, dense_histogram_bytes = 0;
  // (distance, count) pairs of this rank's resolved chunk, and those it received and added in
  // the reduction tree (the reduction's cost per pair comes from these).
  uint64_t pairs = 0, pairs_added = 0;
  double merge_cpu = 0;  // thread CPU seconds adding them (in reduce_cpu; no waiting, no decoding)
};

struct AnalyzeResult {
  std::vector<std::unique_ptr<ReuseAnalysis>> runs;  // one per input (x ordering for meshes)
  Granularity granularity = Granularity::kBoth;
  std::string granularity_note;  // the default chosen for a foreign trace, to say under the table
  std::vector<RankStats> ranks;  // a distributed run (or threads), on rank 0: every rank's
  // Merged summaries that were sampled: the sampling the chunk runs used (the tables need it),
  // and whether they ran the exact analysis too.
  std::optional<ShardsOptions> sampling;
  bool sampling_with_exact = false;
};
Json RankStatsJson(const std::vector<RankStats>& ranks);

// "50,75,90,100" -> {0.5, 0.75, 0.9, 1}: each a percentage in 0..100 (UsageError saying which one
// is not, and why).
std::vector<double> ParseQuantiles(const std::string& list);

// The smoother's options for analysing meshes: exactly cfg.iterations sweeps on cfg.threads
// streams in cfg.mode.
SmoothOptions AnalyzeSweeps(const AnalyzeConfig& cfg);

// Progress of reading a file, said as "analysing: 42% (1.2 s, about 1.6 s left)" at most every
// 2 s.
ProgressFn FileProgress(const Log& log);

// Checks what can be checked before any work (UsageError): formats, orderings, sizes.
void CheckAnalyzeConfig(const AnalyzeConfig& cfg);
AnalyzeResult RunAnalyze(const AnalyzeConfig& cfg, const Log& log);

// The summary table; `human` rounds the mean to one decimal (the aligned view), otherwise every
// number is exact or at full precision.
Table AnalyzeTable(const AnalyzeResult& r, const AnalyzeConfig& cfg, bool human);
Table HistogramTable(const AnalyzeResult& r);  // ReuseAnalysis::HistogramColumns()
Table ProfileTable(const AnalyzeResult& r);    // ReuseAnalysis::ProfileColumns()
Table MrcTable(const AnalyzeResult& r);        // ReuseAnalysis::MrcColumns()
// The lines printed under the aligned table: units, the model, the seed, the default chosen.
std::vector<std::string> AnalyzeNotes(const AnalyzeResult& r, const AnalyzeConfig& cfg);
Json AnalyzeConfigJson(const AnalyzeConfig& cfg, const AnalyzeResult& r);

}  // namespace meshreuse
