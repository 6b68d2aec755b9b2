// The distributed smoother (reports/distributed_smooth.h) with its ranks as threads and a job
// partition that stands in for PT-Scotch (any function of the graph rows the ranks hand it): from
// a mesh file each rank reads only its part and its ghost ring (its range's rows, then the
// directory of core/ranks/part_directory.h says which ids are its own and who owns its ghosts), and
// the run equals, bit for bit, the same partition applied to the whole mesh read by every rank:
// the same visit order pi, the same exact quality every sweep, the same smoothed coordinates,
// whether the output is gathered or written by every rank into a mesh file. Scattered parts
// (every vertex's part a hash of its id), compact ones (ranges of a stripe), a part with no
// vertex, and P = 1..4.
#include "reports/distributed_smooth.h"

#include <gtest/gtest.h>

#include <cstring>
#include <mutex>

#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/mix.h"
#include "core/ranks/thread_communicator.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

using namespace testing;

// The parts the stand-in gives the rows' vertices (`kind`: 0 hashed, 1 stripes of ids, 2 hashed
// with the last part left empty).
std::vector<int32_t> StandIn(const GraphRows& rows, int32_t parts, int kind) {
  std::vector<int32_t> p(rows.off.size() - 1);
  for (size_t i = 0; i < p.size(); ++i) {
    const int64_t v = rows.first + static_cast<int64_t>(i);
    const int32_t used = kind == 2 && parts > 1 ? parts - 1 : parts;
    p[i] = kind == 1 ? static_cast<int32_t>((v / 7) % parts)
                     : static_cast<int32_t>(Mix64(static_cast<uint64_t>(v) * 31 + 7) % used);
  }
  return p;
}

struct Outcome {
  DistSmoothResult rank0;
  std::vector<uint64_t> bytes_read;
};

Outcome RunOnThreads(DistSmoothConfig cfg, int32_t ranks, int kind) {
  cfg.job_partition = [kind](const GraphRows& rows, int32_t parts, uint64_t) {
    return StandIn(rows, parts, kind);
  };
  Outcome out;
  out.bytes_read.resize(ranks);
  std::mutex mu;
  ThreadCommunicator::Run(ranks, [&](Communicator& tx) {
    DistSmoothResult r = RunDistributedSmooth(cfg, tx, Log{});
    std::lock_guard<std::mutex> lock(mu);
    if (tx.rank() == 0) out.rank0 = std::move(r);
  });
  for (const SmoothRankStats& s : out.rank0.ranks) out.bytes_read[s.rank] = s.bytes_read;
  return out;
}

TEST(DistributedSmooth, APartReadFromAMeshFileSmoothsAsTheWholeMeshWithTheSameParts) {
  TempDir dir;
  SyntheticOptions o;
  o.nx = 40, o.ny = 30, o.holes = 2, o.seed = 9;
  Mesh m = BuildMesh(MakeSyntheticMesh(o));
  LayOutForRanks(&m);
  WriteMeshFile(m, dir / "m.mrm");
  WriteMesh(m, dir / "m.node");  // the same mesh, the same ids, read whole by every rank
  for (int kind : {0, 1, 2})
    for (int32_t P : {1, 2, 3, 4}) {
      SCOPED_TRACE("kind " + std::to_string(kind) + ", P " + std::to_string(P));
      DistSmoothConfig cfg;
      cfg.partition = "ptscotch";
      cfg.ordering = "bfs";
      cfg.smooth.max_iters = 4, cfg.smooth.tol = -1;
      cfg.mesh = dir / "m.node";
      cfg.output = dir / "whole.vtk", cfg.pi_out = dir / "whole.pi";
      const Outcome whole = RunOnThreads(cfg, P, kind);
      cfg.mesh = dir / "m.mrm";
      cfg.output = dir / "part.vtk", cfg.pi_out = dir / "part.pi";
      const Outcome part = RunOnThreads(cfg, P, kind);
      auto body = [](const std::string& pi) { return pi.substr(pi.find('\n')); };  // no header
      EXPECT_EQ(body(ReadBytes(dir / "whole.pi")), body(ReadBytes(dir / "part.pi")));
      EXPECT_EQ(ReadBytes(dir / "whole.vtk"), ReadBytes(dir / "part.vtk"));
      ASSERT_EQ(whole.rank0.result.sweeps.size(), part.rank0.result.sweeps.size());
      EXPECT_TRUE(whole.rank0.result.quality_after == part.rank0.result.quality_after);
      EXPECT_EQ(whole.rank0.colours, part.rank0.colours);
      EXPECT_EQ(whole.rank0.cut_edges, part.rank0.cut_edges);
      ASSERT_EQ(whole.rank0.ranks.size(), part.rank0.ranks.size());
      for (int32_t r = 0; r < P; ++r) {
        const SmoothRankStats &a = whole.rank0.ranks[r], &b = part.rank0.ranks[r];
        EXPECT_EQ(a.owned, b.owned);
        EXPECT_EQ(a.ghosts, b.ghosts);
        EXPECT_EQ(a.cut, b.cut);
        EXPECT_EQ(a.triangles, b.triangles);
        EXPECT_GT(part.bytes_read[r], 0u);  // a distributed read, not the whole file
      }
      if (kind == 2 && P > 1) {
        EXPECT_EQ(part.rank0.ranks[P - 1].owned, 0);
      }
      // Written by every rank into a mesh file: byte for byte the file rank 0 writes from what it
      // gathered in the whole run.
      cfg.pi_out.clear();
      cfg.output = dir / "part.mrm";
      RunOnThreads(cfg, P, kind);
      cfg.mesh = dir / "m.node", cfg.output = dir / "whole.mrm";
      RunOnThreads(cfg, P, kind);
      EXPECT_EQ(ReadBytes(dir / "whole.mrm"), ReadBytes(dir / "part.mrm"));
    }
}

}  // namespace
}  // namespace meshreuse
