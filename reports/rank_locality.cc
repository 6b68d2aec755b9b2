// Per-rank locality: see rank_locality.h.
#include "reports/rank_locality.h"

#include <limits>
#include <stdexcept>

#include "core/error.h"
#include "core/ranks/halo_smoother.h"
#include "core/ranks/partition.h"
#include "core/ranks/rank_part.h"
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

namespace {

// The transport of a rank traced alone: what it sends is dropped, what it receives is its ghosts'
// current values (as if their owners had not moved them), and the sum over ranks is its own. The
// addresses a rank touches do not depend on the values, the geometry stays a mesh's, and the
// stream config asks for a fixed number of sweeps (the stop rule never reads the sums).
class SoloTransport : public Communicator {
 public:
  explicit SoloTransport(const RankPart& p) : p_(p) {}
  int32_t rank() const override { return p_.rank; }
  int32_t size() const override { return p_.parts; }
  void Send(int32_t, std::string&&) override {}
  std::string Recv(int32_t) override {
    throw std::logic_error("SoloTransport: a traced rank receives values only");
  }
  void SendValues(int32_t, const void*, size_t) override {}
  void RecvValues(int32_t from, void* bytes, size_t n) override {
    double* data = static_cast<double*>(bytes);
    for (const RankLink& l : p_.links) {
      if (l.rank != from) continue;
      if (n != 16 * l.recv.size()) throw std::logic_error("SoloTransport: message size mismatch");
      for (size_t j = 0; j < l.recv.size(); ++j) {
        data[2 * j] = p_.xy[2 * int64_t{l.recv[j]}];
        data[2 * j + 1] = p_.xy[2 * int64_t{l.recv[j]} + 1];
      }
      return;
    }
    throw std::logic_error("SoloTransport: no link to rank " + std::to_string(from));
  }
  FixedSum AllReduceSum(const FixedSum& mine) override { return mine; }
  std::vector<std::string> AllGather(const std::string&) override {
    throw std::logic_error("SoloTransport: a traced rank gathers nothing");
  }

 private:
  const RankPart& p_;
};

}  // namespace

HaloOptions RankStreamOptions(const SmoothOptions& sweeps) {
  HaloOptions o;
  o.max_iters = sweeps.max_iters;
  o.tol = -std::numeric_limits<double>::infinity();
  o.mode = sweeps.mode == UpdateMode::kJacobi ? HaloMode::kJacobi : HaloMode::kOrdered;
  return o;
}

void StreamRankParts(const RankLocalityConfig& cfg, const Log& log,
                     const std::function<AccessConsumer&(int32_t rank)>& to) {
  const PartitionedMesh pm = LoadPartitioned(cfg.mesh, cfg.partition, cfg.ranks, cfg.seed, log);
  const Mesh& m = pm.mesh;
  const std::vector<int32_t>& part = pm.part;
  const PartitionStats ps = MeasurePartition(m, part, cfg.ranks);
  const HaloOptions opt = RankStreamOptions(cfg.sweeps);
  for (int32_t r = 0; r < cfg.ranks; ++r) {
    RankPart p =
        BuildRankPart(m, part, cfg.ranks, ps.colour, r, cfg.ordering, cfg.seed, cfg.placement);
    log.Say("rank " + std::to_string(r) + " of " + std::to_string(cfg.ranks) + ": " +
            std::to_string(p.owned) + " owned, " + std::to_string(p.ghosts()) + " ghosts, " +
            std::to_string(opt.max_iters) + " " + HaloModeName(opt.mode) + " sweep(s) in " +
            cfg.ordering.text + " order");
    SoloTransport tx(p);
    StreamRankPart(
        p, opt, tx,
        cfg.mesh + " [rank " + std::to_string(r) + " of " + std::to_string(cfg.ranks) + "]",
        cfg.ordering.text, to(r));
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
