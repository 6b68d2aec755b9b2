// What a reuse analysis computes, over which streams, and what it returns: the narrow description
// the whole analysis (reports/analyze.h), a chunk of it and a distributed run (reports/chunks/)
// share. The source (stream_source.h) and the analysis' own options: granularity, line size,
// exact and/or SHARDS sampling, profiles; the tables' options (quantiles, the cache model, the
// outputs) stay with the analyze runner.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/reuse_analysis.h"
#include "analysis/shards.h"
#include "reports/run_info.h"
#include "reports/stream_source.h"

namespace meshreuse {

struct ReuseJob : StreamSource {
  // Default: both for meshes and meshreuse traces; line for address traces, element for ids.
  std::optional<Granularity> granularity;
  uint32_t line_bytes = 64;
  bool sample = false;        // SHARDS instead of (or with sample_error, beside) exact
  bool sample_error = false;  // the exact analysis too, and the estimate's error
  ShardsOptions shards;
  // Sampling: the capacities (element and line ids; the cache levels') whose miss estimates get
  // a sampling bound (ReuseOptions::watch_element, watch_line).
  std::vector<uint64_t> watch_element, watch_line;
  bool profile = true;  // compute the profiles (the CLI asks only when it writes them)
  // From this many ranks on, a distributed run adds its histograms up by distance (a
  // reduce-scatter, each rank one slice), below up a tree of ranks (RunDistributed).
  int32_t scatter_from_ranks = 16;

  // The analyzer's options at granularity g (exact unless sampling without the error).
  ReuseOptions Options(Granularity g) const;
};

// What one rank of a distributed run spent (reports/chunks/distributed_analysis.h): thread CPU
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
Json RankStatsJson(const std::vector<RankStats>& ranks);

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

}  // namespace meshreuse
