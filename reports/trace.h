// The runner behind `meshreuse trace`: a mesh laid out in an ordering, K sweeps streamed through
// the traced smoother into a TraceWriter (tracer/trace_writer.h), zstd-compressed when asked; or,
// with --ranks, each rank's part of a distributed smoothing run into a file of its own.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/kernels/kernel.h"
#include "core/permutation.h"
#include "core/ranks/rank_part.h"
#include "core/smoother.h"
#include "reports/log.h"

namespace meshreuse {

struct TraceConfig {
  std::string mesh, ordering = "ori", output;
  std::string kernel = kPaperKernel;  // core/kernels/
  uint64_t seed = 1;
  int iterations = 1, threads = 1;
  UpdateMode mode = UpdateMode::kGaussSeidel;
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  uint32_t element_bytes = 66;
  bool compress = false;
  // Per-rank traces (reports/rank_locality.h): with ranks > 0, one file per rank's part,
  // OUTPUT.rank0 ... OUTPUT.rank(P-1), each the stream `analyze MESH --ranks P` analyses.
  int32_t ranks = 0;
  std::string partition = "hilbert";
  CutPlacement cut_placement = CutPlacement::kLast;
};
// The files a per-rank trace writes (OUTPUT.rankR), or {OUTPUT}.
std::vector<std::string> TraceOutputs(const TraceConfig& cfg);

struct TraceRunResult {
  uint64_t records = 0, elements = 0;
  int32_t vertices = 0;
  double seconds = 0;
  uint64_t compressed_bytes = 0;  // with compress
};

void CheckTraceConfig(const TraceConfig& cfg);  // UsageError
TraceRunResult RunTrace(const TraceConfig& cfg, const Log& log);

}  // namespace meshreuse
