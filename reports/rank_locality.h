// Per-rank locality (issue 23): each rank's part of a distributed smoothing run
// (reports/distributed_smooth.h) laid out as that rank lays it out (core/ranks/rank_part.h:
// non-cut, cut, boundary, ghosts, each group in the rank's ordering) and swept by the distributed
// smoother itself, traced (core/ranks/halo_smoother.h SmoothRankPart with a sink): the loads and
// stores a rank makes, its ghost messages' packs and unpacks included, as one stream per rank for
// the reuse-distance analyzer and the simulator. Ranks are traced one after another in one process
// (a rank's part, not the whole mesh, is what is held per analysis), each alone: it receives its
// ghosts' current values (values never change an address), and makes exactly the configured
// number of sweeps. Gauss-Seidel is the ordered mode, Jacobi the Jacobi mode.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/reuse_analysis.h"
#include "core/ranks/halo_smoother.h"
#include "core/ranks/rank_part.h"
#include "core/smoother.h"
#include "reports/log.h"
#include "tracer/access_stream.h"

namespace meshreuse {

struct RankLocalityConfig {
  std::string mesh;
  int32_t ranks = 2;
  std::string partition = "hilbert";  // hilbert or metis
  OrderingSpec ordering = "ori";      // inside each part
  CutPlacement placement = CutPlacement::kLast;
  uint64_t seed = 1;
  SmoothOptions sweeps;  // max_iters sweeps, its mode (RankStreamOptions)
};

// UsageError unless ranks is 0 (no per-rank run) or 1..65536 with a known partition method and
// every input a mesh.
void CheckRankParts(int32_t ranks, const std::string& partition,
                    const std::vector<std::string>& inputs);

// The distributed smoother's options for `sweeps`: exactly max_iters sweeps, ordered Gauss-Seidel
// or Jacobi as sweeps.mode says.
HaloOptions RankStreamOptions(const SmoothOptions& sweeps);

// Streams rank r's part, for r = 0..P-1 in turn, into the consumer to(r) returns (an analysis or a
// simulation per rank), labelled "MESH [rank r of P]" and the ordering. UsageError: more ranks
// than vertices, an unknown partition or ordering.
void StreamRankParts(const RankLocalityConfig& cfg, const Log& log,
                     const std::function<AccessConsumer&(int32_t rank)>& to);
// The reuse analyzer per rank, with the caller's options.
std::vector<std::unique_ptr<ReuseAnalysis>> AnalyzeRankParts(const RankLocalityConfig& cfg,
                                                             const ReuseOptions& opt,
                                                             const Log& log);

}  // namespace meshreuse
