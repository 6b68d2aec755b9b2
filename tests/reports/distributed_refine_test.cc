// The distributed refinement (reports/distributed_refine.h) with its ranks as threads: at 1..4
// ranks the file is byte for byte the whole pieces-layout mesh written by one process
// (WriteMeshFile of RefineMeshPieces, rows and flags built from scratch by BuildMesh), at every
// level including those where blocks hold no vertex, on meshes of either orientation; the
// result's sizes, Euler characteristic and content id are the file's; an output that is not a
// regular mesh file is refused on every rank with nothing written.
#include "reports/distributed_refine.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>

#include "core/error.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/ranks/thread_communicator.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

using namespace testing;

int64_t Euler(const Mesh& m) {
  return m.NumVertices() - static_cast<int64_t>(m.v2v.idx.size()) / 2 + m.NumTriangles();
}

DistRefineResult RunOnThreads(const DistRefineConfig& cfg, int32_t ranks) {
  DistRefineResult rank0;
  std::mutex mu;
  ThreadCommunicator::Run(ranks, [&](Communicator& tx) {
    DistRefineResult r = RunDistributedRefine(cfg, tx, Log{});
    std::lock_guard<std::mutex> lock(mu);
    if (tx.rank() == 0) rank0 = std::move(r);
  });
  return rank0;
}

TEST(DistributedRefine, EveryRankCountWritesTheOneProcessFile) {
  TempDir dir;
  std::vector<std::string> coarse = {DataPath("plate41.msh"), DataPath("two_components.node")};
  {
    SyntheticOptions o;
    o.nx = 9, o.ny = 6, o.holes = 2, o.seed = 4;
    const Mesh m = BuildMesh(MakeSyntheticMesh(o));
    WriteMesh(m, dir / "synthetic");
    RawMesh raw;  // the same, clockwise
    raw.xy = m.xy;
    raw.tri = m.tri;
    for (size_t t = 0; t < raw.tri.size(); t += 3) std::swap(raw.tri[t + 1], raw.tri[t + 2]);
    WriteMesh(BuildMesh(std::move(raw)), dir / "clockwise");
    coarse.push_back(dir / "synthetic.node");
    coarse.push_back(dir / "clockwise.node");
  }
  for (const std::string& path : coarse)
    for (int k : {0, 2, 3}) {
      SCOPED_TRACE(path + " K " + std::to_string(k));
      RefineOptions o;
      o.levels = k, o.jitter = k ? 0.3 : 0, o.seed = 5;
      Mesh c = ReadMesh(path);
      LayOutForRanks(&c);
      const Mesh whole = BuildMesh(RefineMeshPieces(c, o));
      WriteMeshFile(whole, dir / "one.mrm");
      const std::string expected = ReadBytes(dir / "one.mrm");
      for (int32_t P : {1, 2, 3, 4}) {
        DistRefineConfig cfg;
        cfg.mesh = path, cfg.output = dir / "ranks.mrm", cfg.refine = o;
        const DistRefineResult r = RunOnThreads(cfg, P);
        ASSERT_EQ(ReadBytes(cfg.output), expected) << P << " ranks";
        EXPECT_EQ(r.vertices, whole.NumVertices());
        EXPECT_EQ(r.triangles, whole.NumTriangles());
        EXPECT_EQ(r.content_id, MeshFile(cfg.output).content_id());
        EXPECT_EQ(r.euler, Euler(whole));
        EXPECT_EQ(r.coarse_euler, Euler(c));
        EXPECT_GT(r.min_area2, 0);
        ASSERT_EQ(r.ranks.size(), static_cast<size_t>(P));
        int64_t v = 0, t = 0;
        for (const RefineRankStats& s : r.ranks) v += s.vertices, t += s.triangles;
        EXPECT_EQ(v, whole.NumVertices());
        EXPECT_EQ(t, whole.NumTriangles());
        // Read back as any mesh: the reader checks the stored rows and flags against the
        // triangles.
        EXPECT_EQ(Euler(ReadMesh(cfg.output)), Euler(c));
      }
    }
}

TEST(DistributedRefine, OutputsThatCannotBeWrittenInRangesAreRefusedOnEveryRank) {
  TempDir dir;
  DistRefineConfig cfg;
  cfg.mesh = DataPath("plate41.msh");
  cfg.output = dir / "fine.node";
  EXPECT_THROW(RunOnThreads(cfg, 2), UsageError);
  // A link named like a mesh file onto a device: written in place elsewhere, refused here.
  ASSERT_EQ(::symlink("/dev/null", (dir / "null.mrm").c_str()), 0);
  cfg.output = dir / "null.mrm";
  EXPECT_THROW(RunOnThreads(cfg, 3), UsageError);
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "null.mrm"));
  // A FIFO: refused before rank 0 opens it (opening one for writing would wait for a reader).
  ASSERT_EQ(::mkfifo((dir / "pipe.mrm").c_str(), 0600), 0);
  cfg.output = dir / "pipe.mrm";
  EXPECT_THROW(RunOnThreads(cfg, 2), UsageError);
  std::filesystem::remove(dir / "pipe.mrm");
  // A coarse mesh that does not exist: every rank fails, none hangs, nothing is left behind.
  cfg.mesh = dir / "missing.node";
  cfg.output = dir / "fine.mrm";
  EXPECT_ANY_THROW(RunOnThreads(cfg, 3));
  EXPECT_FALSE(std::filesystem::exists(dir / "fine.mrm"));
  size_t left = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) left += !e.is_symlink();
  EXPECT_EQ(left, 0u);  // no temporary either
}

}  // namespace
}  // namespace meshreuse
