// Per-rank locality: see rank_locality.h.
#include "reports/rank_locality.h"

#include "core/partition.h"
#include "core/rank_part.h"
#include "reports/distributed_smooth.h"
#include "tracer/access_stream.h"

namespace meshreuse {

std::vector<std::unique_ptr<ReuseAnalysis>> AnalyzeRankParts(const RankLocalityConfig& cfg,
                                                             const ReuseOptions& opt,
                                                             const Log& log) {
  const Mesh m = LoadForRanks(cfg.mesh, cfg.ranks, log);
  const std::vector<int32_t> part = PartsByMethod(m, cfg.partition, cfg.ranks, cfg.seed);
  const PartitionStats ps = MeasurePartition(m, part, cfg.ranks);
  SmoothOptions sweeps = cfg.sweeps;
  sweeps.quality = QualityMode::kPerSweep;  // what a rank does: moves, then one quality pass
  sweeps.threads = 1;
  std::vector<std::unique_ptr<ReuseAnalysis>> out;
  for (int32_t r = 0; r < cfg.ranks; ++r) {
    const RankPart p = BuildRankPart(m, part, cfg.ranks, ps.colour, r, cfg.ordering, cfg.seed);
    Mesh local = RankMesh(p);
    auto a = std::make_unique<ReuseAnalysis>(opt);
    log.Say("rank " + std::to_string(r) + " of " + std::to_string(cfg.ranks) + ": " +
            std::to_string(p.owned) + " owned, " + std::to_string(p.ghosts()) + " ghosts, " +
            std::to_string(sweeps.max_iters) + " sweep(s) in " + cfg.ordering + " order");
    StreamMesh(local, sweeps,
               cfg.mesh + " [rank " + std::to_string(r) + " of " + std::to_string(cfg.ranks) + "]",
               cfg.ordering, *a);
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace meshreuse
