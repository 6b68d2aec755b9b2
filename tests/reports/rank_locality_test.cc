// Per-rank locality: the stream the serial smoother's traced sweep makes on a rank's part
// (RankMesh, core/rank_part.h) against what the rank's own sweep does (halo_smoother.h), read off
// the part directly: the moves in local order, each reading its row of the part in the part's
// order, then the owned triangles' corners in order; at one rank the moved coordinates equal the
// distributed smoother's bit for bit. And AnalyzeRankParts: one analysis per rank, whose moves add
// up to the whole mesh's interior.
#include "reports/rank_locality.h"

#include <gtest/gtest.h>

#include "core/halo_smoother.h"
#include "core/halo_threads.h"
#include "core/partition.h"
#include "core/rank_part.h"
#include "reports/inputs.h"
#include "tests/test_util.h"
#include "tracer/sink.h"

namespace meshreuse {
namespace {

using namespace testing;

std::vector<RankPart> PartsOf(const Mesh& m, int32_t P, const std::string& ordering) {
  const std::vector<int32_t> part = P == 3 ? MetisParts(m, P, 2) : HilbertRangeParts(m, P);
  const PartitionStats ps = MeasurePartition(m, part, P);
  std::vector<RankPart> parts;
  for (int32_t r = 0; r < P; ++r)
    parts.push_back(BuildRankPart(m, part, P, ps.colour, r, ordering));
  return parts;
}

SmoothOptions PerSweep(int sweeps) {
  SmoothOptions o = ExactSweeps(sweeps);
  o.quality = QualityMode::kPerSweep;
  return o;
}

TEST(RankMesh, TracedSweepIsTheRanksSweep) {
  for (const Mesh& m : MeshCorpus())
    for (int32_t P : {1, 2, 3}) {
      if (P > m.NumVertices()) continue;
      for (const RankPart& p : PartsOf(m, P, P == 2 ? "bfs" : "ori")) {
        Mesh local = RankMesh(p);
        ASSERT_EQ(local.NumVertices(), p.total);
        ASSERT_EQ(static_cast<int32_t>(local.interior.size()), p.movable);
        RecordingSink sink;
        Smooth(local, PerSweep(1), sink);
        // The element stream: per move, its row's coordinate reads then its write; then per owned
        // triangle its three corners.
        std::vector<std::pair<AccessKind, int32_t>> want, got;
        for (int32_t v = 0; v < p.movable; ++v) {
          want.push_back({AccessKind::kAdjacency, v});
          for (const int32_t* u = p.v2v.RowBegin(v); u != p.v2v.RowEnd(v); ++u)
            want.push_back({AccessKind::kCoordRead, *u});
          want.push_back({AccessKind::kCoordWrite, v});
        }
        for (size_t k = 0; k < p.tri.size(); ++k)
          want.push_back({AccessKind::kCoordRead, p.tri[k]});
        for (const auto& t : sink.touches) got.push_back({t.kind, t.vertex});
        EXPECT_EQ(got, want) << "rank " << p.rank << " of " << P;
      }
    }
}

TEST(RankMesh, OneRankMovesAsTheDistributedSmoother) {
  for (const Mesh& m : MeshCorpus()) {
    std::vector<RankPart> parts = PartsOf(m, 1, "rdr");
    Mesh local = RankMesh(parts[0]);
    NullSink none;
    Smooth(local, PerSweep(3), none);
    HaloOptions opt;
    opt.max_iters = 3, opt.tol = -1;
    HaloThreads::Run(1, [&](HaloTransport& tx) { SmoothRankPart(parts[0], opt, tx); });
    for (int32_t k = 0; k < 2 * parts[0].total; ++k)
      ASSERT_EQ(local.xy[k], parts[0].xy[k]) << "coordinate " << k;
  }
}

TEST(RankLocality, OneAnalysisPerRankCoveringTheInterior) {
  TempDir dir;
  const std::string mesh = DataPath("plate41.msh");
  const Mesh whole = LoadMesh(mesh, Log());
  RankLocalityConfig cfg;
  cfg.mesh = mesh, cfg.ranks = 4, cfg.ordering = "bfs";
  cfg.sweeps = ExactSweeps(2);
  ReuseOptions opt;
  const auto runs = AnalyzeRankParts(cfg, opt, Log());
  ASSERT_EQ(runs.size(), 4u);
  uint64_t moves = 0;
  for (const auto& a : runs) {
    EXPECT_NE(a->info().input.find("of 4]"), std::string::npos);
    EXPECT_EQ(a->info().ordering, "bfs");
    moves += a->moves(0);
  }
  EXPECT_EQ(moves, 2 * whole.interior.size());  // every interior vertex moved once a sweep
  cfg.ranks = static_cast<int32_t>(whole.NumVertices()) + 1;
  EXPECT_THROW(AnalyzeRankParts(cfg, opt, Log()), UsageError);
}

}  // namespace
}  // namespace meshreuse
