// Per-rank locality: see rank_locality.h.
#include "reports/rank_locality.h"

#include "core/error.h"
#include "core/partition.h"
#include "core/rank_part.h"
#include "reports/distributed_smooth.h"
#include "reports/inputs.h"

namespace meshreuse {

void CheckRankParts(int32_t ranks, const std::string& partition,
                    const std::vector<std::string>& inputs) {
  if (ranks < 0 || ranks > 65536) throw UsageError("--ranks must be 1..65536");
  if (ranks == 0) return;
  CheckPartitionMethod(partition);
  for (const std::string& in : inputs)
    if (ClassifyInput(in) != InputKind::kMesh)
      throw UsageError("--ranks: " + in + " is not a mesh (each rank's part is a mesh's)");
}

void StreamRankParts(const RankLocalityConfig& cfg, const Log& log,
                     const std::function<AccessConsumer&(int32_t rank)>& to) {
  const PartitionedMesh pm = LoadPartitioned(cfg.mesh, cfg.partition, cfg.ranks, cfg.seed, log);
  const Mesh& m = pm.mesh;
  const std::vector<int32_t>& part = pm.part;
  const PartitionStats ps = MeasurePartition(m, part, cfg.ranks);
  SmoothOptions sweeps = cfg.sweeps;
  sweeps.quality = QualityMode::kPerSweep;  // what a rank does: moves, then one quality pass
  sweeps.threads = 1;
  for (int32_t r = 0; r < cfg.ranks; ++r) {
    const RankPart p =
        BuildRankPart(m, part, cfg.ranks, ps.colour, r, cfg.ordering, cfg.seed, cfg.placement);
    Mesh local = RankMesh(p);
    log.Say("rank " + std::to_string(r) + " of " + std::to_string(cfg.ranks) + ": " +
            std::to_string(p.owned) + " owned, " + std::to_string(p.ghosts()) + " ghosts, " +
            std::to_string(sweeps.max_iters) + " sweep(s) in " + cfg.ordering + " order");
    StreamMesh(local, sweeps,
               cfg.mesh + " [rank " + std::to_string(r) + " of " + std::to_string(cfg.ranks) + "]",
               cfg.ordering, to(r));
  }
}

std::vector<std::unique_ptr<ReuseAnalysis>> AnalyzeRankParts(const RankLocalityConfig& cfg,
                                                             const ReuseOptions& opt,
                                                             const Log& log) {
  std::vector<std::unique_ptr<ReuseAnalysis>> out;
  StreamRankParts(cfg, log, [&](int32_t) -> AccessConsumer& {
    out.push_back(std::make_unique<ReuseAnalysis>(opt));
    return *out.back();
  });
  return out;
}

}  // namespace meshreuse
