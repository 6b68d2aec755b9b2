// Per-rank locality: the distributed smoother's traced sweep (halo_smoother.h SmoothRankPart with
// a sink) against a reference read off the part directly, written from the schedule that
// halo_smoother.h documents: per mode and cut placement, which moves, packs and unpacks come in
// which order, and what each loads and stores. The traced run moves the vertices exactly as the
// untraced one; a rank traced alone (StreamRankParts) streams exactly what it streams inside a
// real run of all ranks; the counts match TracedPerSweep; and AnalyzeRankParts gives one analysis
// per rank, whose moves add up to the whole mesh's interior.
#include "reports/rank_locality.h"

#include <gtest/gtest.h>

#include <mutex>
#include <tuple>

#include "core/ranks/halo_smoother.h"
#include "core/ranks/partition.h"
#include "core/ranks/rank_part.h"
#include "core/ranks/thread_communicator.h"
#include "reports/distributed_smooth.h"
#include "reports/inputs.h"
#include "tests/test_util.h"
#include "tracer/sink.h"

namespace meshreuse {
namespace {

using namespace testing;

std::vector<RankPart> PartsOf(const Mesh& m, int32_t P, const std::string& ordering,
                              CutPlacement placement = CutPlacement::kLast) {
  const std::vector<int32_t> part = P == 3 ? MetisParts(m, P, 2) : HilbertRangeParts(m, P);
  const PartitionStats ps = MeasurePartition(m, part, P);
  std::vector<RankPart> parts;
  for (int32_t r = 0; r < P; ++r)
    parts.push_back(BuildRankPart(m, part, P, ps.colour, r, ordering, 1, placement));
  return parts;
}

HaloOptions Sweeps(int n, HaloMode mode) {
  HaloOptions o;
  o.max_iters = n, o.tol = -std::numeric_limits<double>::infinity(), o.mode = mode;
  return o;
}

// One access as the reference states it: array, store, bytes, element kind, vertex.
using Ref = std::tuple<Array, bool, uint32_t, AccessKind, int32_t>;
constexpr AccessKind kNo = AccessKind::kNone;

// One sweep of rank p, from the schedule of halo_smoother.h.
std::vector<Ref> ReferenceSweep(const RankPart& p, HaloMode mode) {
  std::vector<Ref> want;
  const bool jacobi = mode == HaloMode::kJacobi;
  const Array src = Array::kCoords, dst = jacobi ? Array::kCoordsNext : Array::kCoords;
  auto moves = [&](int32_t b, int32_t e) {
    for (int32_t v = b; v < e; ++v) {
      want.emplace_back(Array::kAdjOffsets, false, 8, AccessKind::kAdjacency, v);
      want.emplace_back(Array::kAdjOffsets, false, 8, kNo, -1);
      for (const int32_t* u = p.v2v.RowBegin(v); u != p.v2v.RowEnd(v); ++u) {
        want.emplace_back(Array::kAdjIndex, false, 4, kNo, -1);
        want.emplace_back(src, false, 16, AccessKind::kCoordRead, *u);
      }
      want.emplace_back(dst, true, 16, AccessKind::kCoordWrite, v);
    }
  };
  auto pack_all = [&] {
    for (const RankLink& l : p.links)
      for (int32_t v : l.send) {
        want.emplace_back(Array::kSendIndex, false, 4, kNo, -1);
        want.emplace_back(dst, false, 16, AccessKind::kCoordRead, v);
        want.emplace_back(Array::kSendBuffer, true, 16, kNo, -1);
      }
  };
  auto unpack = [&](auto from) {  // the links whose colour `from` accepts, in link order
    for (const RankLink& l : p.links)
      if (from(l.colour))
        for (int32_t g : l.recv) {
          want.emplace_back(Array::kRecvIndex, false, 4, kNo, -1);
          want.emplace_back(Array::kRecvBuffer, false, 16, kNo, -1);
          want.emplace_back(dst, true, 16, AccessKind::kCoordWrite, g);
        }
  };
  auto lower = [&](int32_t c) { return c < p.colour; };
  auto higher = [&](int32_t c) { return c > p.colour; };
  auto any = [](int32_t) { return true; };
  if (mode != HaloMode::kOrdered) {
    moves(0, p.movable), pack_all(), unpack(any);
  } else if (p.placement == CutPlacement::kLast) {
    moves(0, p.noncut), unpack(lower), moves(p.noncut, p.movable), pack_all(), unpack(higher);
  } else if (p.placement == CutPlacement::kFirst) {
    unpack(lower), moves(0, p.cut()), pack_all(), moves(p.cut(), p.movable), unpack(higher);
  } else {
    unpack(lower), moves(0, p.movable), pack_all(), unpack(higher);
  }
  for (size_t t = 0; t < p.weight.size(); ++t) {
    for (int j = 0; j < 3; ++j) want.emplace_back(Array::kTriangles, false, 4, kNo, -1);
    for (int j = 0; j < 3; ++j) {
      want.emplace_back(Array::kCoords, false, 8, AccessKind::kCoordRead, p.tri[3 * t + j]);
      want.emplace_back(Array::kCoords, false, 8, kNo, -1);
    }
    want.emplace_back(Array::kWeights, false, 8, kNo, -1);
  }
  return want;
}

// Runs all ranks of `parts` on threads, each traced into its own RecordingSink.
std::vector<RecordingSink> TraceAll(std::vector<RankPart>& parts, const HaloOptions& opt) {
  std::vector<RecordingSink> sinks(parts.size());
  ThreadCommunicator::Run(static_cast<int32_t>(parts.size()), [&](Communicator& tx) {
    SmoothRankPart(parts[tx.rank()], opt, tx, sinks[tx.rank()]);
  });
  return sinks;
}

TEST(TracedRankSweep, IsTheScheduleReadOffThePart) {
  const HaloMode modes[] = {HaloMode::kOrdered, HaloMode::kJacobi, HaloMode::kHybrid};
  const CutPlacement places[] = {CutPlacement::kLast, CutPlacement::kFirst,
                                 CutPlacement::kInterleaved};
  int with_messages = 0;
  for (const Mesh& m : MeshCorpus())
    for (int32_t P : {1, 2, 3}) {
      if (P > m.NumVertices()) continue;
      for (HaloMode mode : modes)
        for (CutPlacement place : places) {
          if (mode != HaloMode::kOrdered && place != CutPlacement::kLast) continue;
          std::vector<RankPart> parts = PartsOf(m, P, P == 2 ? "bfs" : "ori", place);
          const std::vector<RecordingSink> sinks = TraceAll(parts, Sweeps(2, mode));
          for (const RankPart& p : parts) {
            const RecordingSink& s = sinks[p.rank];
            const std::vector<Ref> one = ReferenceSweep(p, mode);
            ASSERT_EQ(s.sweep_starts.size(), 2u);
            std::vector<Ref> got;
            for (const auto& r : s.refs)
              got.emplace_back(r.ref.array, r.ref.write, r.ref.size, r.ref.element, r.ref.vertex);
            std::vector<Ref> want = one;
            want.insert(want.end(), one.begin(), one.end());
            ASSERT_EQ(got, want) << HaloModeName(mode) << " " << CutPlacementName(place)
                                 << ", rank " << p.rank << " of " << P;
            const HaloSweepCounts c = TracedPerSweep(p);
            EXPECT_EQ(c.refs, one.size());
            EXPECT_EQ(c.elements, s.touches.size() / 2);
            for (const auto& r : s.refs) EXPECT_EQ(r.thread, 0);
            with_messages += !p.links.empty();
          }
        }
    }
  EXPECT_GT(with_messages, 100);  // the corpus exercises packs and unpacks
}

TEST(TracedRankSweep, ElementAddressesAreTheRecords) {
  // Each element touch's address is its vertex's coordinates (in one of the two buffers for
  // Jacobi) or its row offset; each message access lies in its own array.
  const Mesh m = ReadMesh(DataPath("plate41.msh"));
  for (HaloMode mode : {HaloMode::kOrdered, HaloMode::kJacobi}) {
    std::vector<RankPart> parts = PartsOf(m, 3, "rdr");
    const std::vector<RecordingSink> sinks = TraceAll(parts, Sweeps(1, mode));
    for (const RankPart& p : parts) {
      const ArrayLayout& l = sinks[p.rank].layout;
      auto in = [&](Array a, const void* addr, uint64_t off) {
        return reinterpret_cast<uintptr_t>(addr) == l.base[static_cast<int>(a)] + off;
      };
      for (const auto& r : sinks[p.rank].refs) {
        const MemRef& x = r.ref;
        const uint64_t v = static_cast<uint64_t>(x.vertex);
        if (x.element == AccessKind::kAdjacency) {
          EXPECT_TRUE(in(Array::kAdjOffsets, x.address, 8 * v));
        } else if (x.element != kNo) {
          EXPECT_TRUE(in(Array::kCoords, x.address, 16 * v) ||
                      in(Array::kCoordsNext, x.address, 16 * v));
        } else if (x.array >= Array::kSendIndex) {
          const uintptr_t a = reinterpret_cast<uintptr_t>(x.address);
          const int k = static_cast<int>(x.array);
          EXPECT_GE(a, l.base[k]);
          EXPECT_LE(a + x.size, l.base[k] + l.bytes[k]);
        }
      }
    }
  }
}

TEST(TracedRankSweep, MovesAsTheUntracedRun) {
  for (const Mesh& m : MeshCorpus())
    for (HaloMode mode : {HaloMode::kOrdered, HaloMode::kJacobi}) {
      const int32_t P = std::min<int32_t>(3, m.NumVertices());
      std::vector<RankPart> traced = PartsOf(m, P, "rdr"), plain = traced;
      TraceAll(traced, Sweeps(3, mode));
      ThreadCommunicator::Run(
          P, [&](Communicator& tx) { SmoothRankPart(plain[tx.rank()], Sweeps(3, mode), tx); });
      for (int32_t r = 0; r < P; ++r)
        for (size_t k = 0; k < plain[r].xy.size(); ++k)
          ASSERT_EQ(traced[r].xy[k], plain[r].xy[k]) << "rank " << r << ", coordinate " << k;
    }
}

TEST(TracedRankSweep, OneRankMovesAsTheSerialSmoother) {
  // At one rank in `ori` order the rank visits the interior vertices in increasing global id
  // reading rows in increasing global id, as the serial sweep does: the same bits, and the same
  // element stream for the moves (local ids mapped to global ones; the rank's loop reads no
  // interior list or bound, which are no element touches).
  for (const Mesh& m : MeshCorpus()) {
    std::vector<RankPart> parts = PartsOf(m, 1, "ori");
    const RankPart& p = parts[0];
    std::vector<RecordingSink> sinks = TraceAll(parts, Sweeps(2, HaloMode::kOrdered));
    Mesh serial = m.Clone();
    SmoothOptions so = ExactSweeps(2);
    so.quality = QualityMode::kPerSweep;
    RecordingSink ss;
    Smooth(serial, so, ss);
    for (int32_t k = 0; k < p.total; ++k)
      for (int j = 0; j < 2; ++j)
        ASSERT_EQ(p.xy[2 * k + j], serial.xy[2 * p.gid[k] + j]) << "vertex " << p.gid[k];
    for (int sweep = 0; sweep < 2; ++sweep) {
      const size_t a = sinks[0].sweep_starts[sweep], b = ss.sweep_starts[sweep];
      uint64_t n = 0;
      for (int32_t v : m.interior) n += 2 + m.v2v.RowSize(v);
      for (size_t i = 0; i < n; ++i) {
        const auto& x = sinks[0].touches[a + i];
        const auto& y = ss.touches[b + i];
        ASSERT_EQ(x.kind, y.kind) << i;
        ASSERT_EQ(p.gid[x.vertex], y.vertex) << i;
      }
    }
  }
}

TEST(RankLocality, ARankTracedAloneStreamsAsInTheRealRun) {
  // StreamRankParts traces each rank alone (its ghosts frozen); the accesses, canonical addresses
  // included, are those of the same rank inside a threaded run of all ranks.
  const std::string mesh = DataPath("plate41.msh");
  const Mesh whole = LoadMesh(mesh, Log());
  for (CutPlacement place : {CutPlacement::kLast, CutPlacement::kFirst}) {
    RankLocalityConfig cfg;
    cfg.mesh = mesh, cfg.ranks = 3, cfg.partition = "metis", cfg.ordering = "bfs";
    cfg.placement = place;
    cfg.sweeps = ExactSweeps(2);
    std::vector<RecordingConsumer> alone(3), together(3);
    StreamRankParts(cfg, Log(), [&](int32_t r) -> AccessConsumer& { return alone[r]; });
    const PartitionedMesh pm = LoadPartitioned(mesh, "metis", 3, 1, Log());
    const PartitionStats ps = MeasurePartition(pm.mesh, pm.part, 3);
    std::vector<RankPart> parts;
    for (int32_t r = 0; r < 3; ++r)
      parts.push_back(BuildRankPart(pm.mesh, pm.part, 3, ps.colour, r, "bfs", 1, place));
    ThreadCommunicator::Run(3, [&](Communicator& tx) {
      StreamRankPart(parts[tx.rank()], RankStreamOptions(cfg.sweeps), tx, "x", "bfs",
                     together[tx.rank()]);
    });
    for (int32_t r = 0; r < 3; ++r) {
      ASSERT_EQ(alone[r].all.size(), together[r].all.size());
      ASSERT_EQ(alone[r].all.size(), alone[r].info.records);
      ASSERT_EQ(alone[r].sweep_starts, together[r].sweep_starts);
      for (size_t i = 0; i < alone[r].all.size(); ++i) {
        const Access &a = alone[r].all[i], &b = together[r].all[i];
        ASSERT_EQ(std::tie(a.address, a.element, a.size, a.kind, a.array, a.write),
                  std::tie(b.address, b.element, b.size, b.kind, b.array, b.write))
            << "rank " << r << ", access " << i;
      }
    }
  }
}

TEST(RankLocality, OneAnalysisPerRankCoveringTheInterior) {
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
  // every interior vertex moved once a sweep; unpacking a ghost is not a move
  EXPECT_EQ(moves, 2 * whole.interior.size());
  cfg.ranks = static_cast<int32_t>(whole.NumVertices()) + 1;
  EXPECT_THROW(AnalyzeRankParts(cfg, opt, Log()), UsageError);
}

}  // namespace
}  // namespace meshreuse
