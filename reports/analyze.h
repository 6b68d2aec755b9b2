// The runner behind `meshreuse analyze`: exact LRU reuse distances (or a SHARDS estimate) of
// meshes streamed through the traced smoother (one run per mesh x ordering), meshreuse trace files
// and other tools' traces, each through tracer/access_stream.h into a ReuseAnalysis. Then the
// tables: one row per input x ordering x thread stream x granularity with accesses, cold, distinct
// ids, the exact sum and mean, quantiles, modelled misses per cache level (fully associative LRU),
// the equation-2 cost where latencies are known, and the inverse model's capacities; and the
// histograms, profiles and miss-ratio curves in the analysis' own schemas.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/cache_model.h"
#include "analysis/reuse_analysis.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "core/table.h"
#include "reports/log.h"
#include "reports/output.h"
#include "reports/reuse_job.h"
#include "reports/run_info.h"

namespace meshreuse {

class Communicator;

struct AnalyzeConfig : ReuseJob {
  // ReuseJob: the inputs (meshes, meshreuse traces, other tools' traces), orderings, sweeps and
  // threads -- for trace files the analyzer's threads (exact): a plain file in a chunk per thread
  // (reports/chunks/chunk_threads.h), else batches (ReuseOptions::workers) --, the granularity,
  // line size, sampling and profiles.
  std::vector<double> quantiles = {0.5, 0.75, 0.9, 1.0};  // fractions
  CacheSpec cache = ParseCacheSpec("westmere-ex");
  uint32_t element_bytes = 66;
  std::vector<CacheLevel> inverse;  // measured misses per level (bytes holds the count)
  // One mesh x one ordering: write the laid-out mesh (before the sweeps) as VTK with, per vertex,
  // its rank in the ordering, its original id and the reuse distances of its element touches
  // over the analysed sweeps (mean, max, cold touches): the ordering and its locality in ParaView.
  std::string vtk;
  // Chunk summaries (reports/chunks/): analyse chunk (r, P) of the one trace into summary_out; or,
  // with merge, the inputs are the summaries of chunks 0..P-1, merged.
  std::optional<std::pair<uint32_t, uint32_t>> chunk;
  std::string summary_out;
  bool merge = false;
  // A distributed run (one trace, chunk = rank of size ranks; reports/chunks/): the message
  // layer, or nullptr.
  Communicator* transport = nullptr;
};

// "50,75,90,100" -> {0.5, 0.75, 0.9, 1}: each a percentage in 0..100 (UsageError saying which one
// is not, and why).
std::vector<double> ParseQuantiles(const std::string& list);

// Checks what can be checked before any work (UsageError): formats, orderings, sizes.
void CheckAnalyzeConfig(const AnalyzeConfig& cfg);
AnalyzeResult RunAnalyze(const AnalyzeConfig& cfg, const Log& log);

// The summary table; `human` rounds the mean to one decimal (the aligned view), otherwise every
// number is exact or at full precision.
Table AnalyzeTable(const AnalyzeResult& r, const AnalyzeConfig& cfg, bool human);
Table HistogramTable(const AnalyzeResult& r);  // ReuseAnalysis::HistogramColumns()
Table ProfileTable(const AnalyzeResult& r);    // ReuseAnalysis::ProfileColumns()
Table MrcTable(const AnalyzeResult& r);        // ReuseAnalysis::MrcColumns()
// A sampled stream of fewer ids than this is too small to trust (SHARDS' own experiments keep
// thousands): SampleWarnings names each.
inline constexpr uint64_t kTrustedSampleIds = 1000;
std::vector<std::string> SampleWarnings(const AnalyzeResult& r, const AnalyzeConfig& cfg);
// The lines printed under the aligned table: units, the model, the seed, the default chosen.
std::vector<std::string> AnalyzeNotes(const AnalyzeResult& r, const AnalyzeConfig& cfg);
Json AnalyzeConfigJson(const AnalyzeConfig& cfg, const AnalyzeResult& r);
// What `analyze` prints and writes: the summary table (aligned with the notes under it for people,
// at full precision for --csv, --json and --out), and under --out analyze.{csv,json},
// histogram.csv, profile.csv (unless the input has no sweeps) and run.json.
RunOutput AnalyzeOutput(const AnalyzeResult& r, const AnalyzeConfig& cfg);

}  // namespace meshreuse
