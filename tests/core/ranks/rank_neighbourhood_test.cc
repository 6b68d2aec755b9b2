// A rank's read of a mesh file (core/ranks/rank_neighbourhood.h): the part it lays out equals,
// member for member, the part BuildRankPart makes from the whole mesh with the range partition
// (every corpus mesh, P = 1..4, three orderings, every cut placement); the part graph learnt from
// the shares is MeasurePartition's (same colouring, same cut edges); a rank reads a fraction of a
// large file; and inconsistent files (mended so the hashes pass) are refused by the rank that owns
// the fault, while what no rank sees alone is refused by CheckRankShares on every rank.
#include "core/ranks/rank_neighbourhood.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "core/mesh_file.h"
#include "core/ranks/part_directory.h"
#include "core/ranks/partition.h"
#include "core/ranks/rank_part.h"
#include "core/ranks/thread_communicator.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {
using namespace testing;

int64_t Pad8(int64_t n) { return (n + 7) / 8 * 8; }

void ExpectSameParts(const RankPart& a, const RankPart& b) {
  EXPECT_EQ(a.rank, b.rank);
  EXPECT_EQ(a.colour, b.colour);
  EXPECT_EQ(a.colours, b.colours);
  EXPECT_EQ(a.noncut, b.noncut);
  EXPECT_EQ(a.movable, b.movable);
  EXPECT_EQ(a.owned, b.owned);
  EXPECT_EQ(a.total, b.total);
  EXPECT_EQ(a.gid, b.gid);
  ASSERT_EQ(a.xy.size(), b.xy.size());
  if (!a.xy.empty()) {
    EXPECT_EQ(std::memcmp(a.xy.data(), b.xy.data(), a.xy.size() * sizeof(double)), 0);
  }
  EXPECT_TRUE(std::equal(a.v2v.off.begin(), a.v2v.off.end(), b.v2v.off.begin(), b.v2v.off.end()));
  EXPECT_TRUE(std::equal(a.v2v.idx.begin(), a.v2v.idx.end(), b.v2v.idx.begin(), b.v2v.idx.end()));
  EXPECT_EQ(a.tri, b.tri);
  ASSERT_EQ(a.weight.size(), b.weight.size());
  if (!a.weight.empty()) {  // a part may own no triangle (memcmp of null is undefined)
    EXPECT_EQ(std::memcmp(a.weight.data(), b.weight.data(), a.weight.size() * sizeof(double)), 0);
  }
  ASSERT_EQ(a.links.size(), b.links.size());
  for (size_t i = 0; i < a.links.size(); ++i) {
    EXPECT_EQ(a.links[i].rank, b.links[i].rank);
    EXPECT_EQ(a.links[i].colour, b.links[i].colour);
    EXPECT_EQ(a.links[i].send, b.links[i].send);
    EXPECT_EQ(a.links[i].recv, b.links[i].recv);
  }
}

// The corpus laid out as a mesh file stores it (Hilbert order), so ids are the file's.
std::vector<Mesh> LaidOutCorpus() {
  std::vector<Mesh> corpus = MeshCorpus();
  for (Mesh& m : corpus) LayOutForRanks(&m);
  return corpus;
}

// SortedIds against a search of the ids themselves: one long run among short ones (a range and
// its ghosts), scattered ids, runs at both ends, empty.
TEST(RankNeighbourhood, SortedIdsFindWhatASearchFinds) {
  uint64_t state = 7;
  auto next = [&state] {
    return (state = state * 6364136223846793005ull + 1442695040888963407ull) >> 33;
  };
  for (int kind = 0; kind < 4; ++kind) {
    std::vector<int64_t> ids;
    for (int64_t v = 0; v < 20000; ++v) {
      const bool in = kind == 0   ? (v >= 5000 && v < 15000) || next() % 50 == 0
                      : kind == 1 ? next() % 3 == 0
                      : kind == 2 ? v < 100 || v >= 19900 || next() % 7 == 0
                                  : false;
      if (in) ids.push_back(v);
    }
    const SortedIds index(ids);
    for (int64_t g = -3; g < 20003; ++g) {
      const auto it = std::lower_bound(ids.begin(), ids.end(), g);
      const int64_t want = it != ids.end() && *it == g ? it - ids.begin() : -1;
      ASSERT_EQ(index.Find(g), want) << "kind " << kind << " id " << g;
    }
  }
  EXPECT_THROW(SortedIds({3, 3}), std::logic_error);
}

TEST(RankNeighbourhood, RangeFormulaIsHilbertRangePartsOwn) {
  for (int64_t n : {1, 2, 3, 7, 10, 1000, 1001})
    for (int32_t P = 1; P <= std::min<int64_t>(n, 9); ++P) {
      std::vector<int64_t> first(P + 1, n);  // by a scan of HilbertRangeParts' i * P / n
      for (int64_t v = n - 1; v >= 0; --v) {
        EXPECT_EQ(RangeOwner(v, n, P), v * P / n);
        first[v * P / n] = v;
      }
      for (int32_t r = 0; r <= P; ++r) EXPECT_EQ(RangeFirst(r, n, P), first[r]) << n << " " << P;
      for (int32_t r = 0; r < P; ++r) EXPECT_LT(first[r], first[r + 1]);  // none empty if P <= n
    }
}

TEST(RankNeighbourhood, PartsEqualTheWholeMeshsWithRangeParts) {
  TempDir dir;
  const std::string p = dir / "m.mrm";
  for (const Mesh& m : LaidOutCorpus()) {
    WriteMeshFile(m, p);
    for (int32_t P = 1; P <= std::min(4, m.NumVertices()); ++P) {
      const std::vector<int32_t> part = RangeParts(m, P);
      const PartitionStats ps = MeasurePartition(m, part, P);
      std::vector<RankNeighbourhood> nbs;
      std::vector<RankShare> shares;
      for (int32_t r = 0; r < P; ++r) {
        nbs.push_back(ReadRankNeighbourhood(p, r, P));
        shares.push_back(UnpackShare(PackShare(ShareOf(nbs.back()))));
      }
      int32_t colours = 0;
      const std::vector<int32_t> colour = GreedyPartColouring(CheckRankShares(p, shares), &colours);
      EXPECT_EQ(colour, ps.colour);
      EXPECT_EQ(colours, ps.colours);
      int64_t cut = 0;
      for (const RankShare& s : shares) cut += s.cut_edges;
      EXPECT_EQ(cut, ps.cut_edges);
      for (const char* ordering : {"ori", "bfs", "hilbert"})
        for (CutPlacement pl :
             {CutPlacement::kLast, CutPlacement::kFirst, CutPlacement::kInterleaved})
          for (int32_t r = 0; r < P; ++r) {
            SCOPED_TRACE(std::to_string(m.NumVertices()) + " vertices, P " + std::to_string(P) +
                         ", rank " + std::to_string(r) + ", " + ordering);
            ExpectSameParts(BuildRankPart(nbs[r], colour, ordering, 5, pl),
                            BuildRankPart(m, part, P, ps.colour, r, ordering, 5, pl));
          }
    }
  }
}

// Any partition, not only ranges: a rank that reads the ids of its part (METIS's compact parts, a
// hash's scattered ones, one with an empty part) lays out the part BuildRankPart makes from the
// whole mesh with the same partition -- with ghosts from the file, and with ghosts from their
// owners and the owned ids and ghost owners from the directory (part_directory.h) on threads.
TEST(RankNeighbourhood, AnyPartitionsPartsEqualTheWholeMeshs) {
  TempDir dir;
  const std::string p = dir / "m.mrm";
  int checked = 0;
  for (const Mesh& m : LaidOutCorpus()) {
    WriteMeshFile(m, p);
    const int64_t n = m.NumVertices();
    for (int32_t P = 2; P <= std::min<int64_t>(4, n); ++P)
      for (int kind = 0; kind < 3; ++kind) {
        std::vector<int32_t> part(static_cast<size_t>(n));
        if (kind == 0) part = MetisParts(m, P, 3);
        for (int64_t v = 0; v < n && kind; ++v)
          part[v] = static_cast<int32_t>((v * 2654435761u >> 7) % (kind == 2 ? P - 1 : P));
        SCOPED_TRACE(std::to_string(n) + " vertices, P " + std::to_string(P) + ", kind " +
                     std::to_string(kind));
        const PartitionStats ps = MeasurePartition(m, part, P);
        const GhostOwners owners = [&](const std::vector<int64_t>& g) {
          std::vector<int32_t> q;
          for (int64_t v : g) q.push_back(part[v]);
          return q;
        };
        std::vector<RankShare> shares;
        std::vector<RankNeighbourhood> nbs;
        for (int32_t r = 0; r < P; ++r) {
          std::vector<int64_t> owned;
          for (int64_t v = 0; v < n; ++v)
            if (part[v] == r) owned.push_back(v);
          nbs.push_back(ReadPartNeighbourhood(p, r, P, owned, owners));
          shares.push_back(ShareOf(nbs.back()));
        }
        int32_t colours = 0;
        const std::vector<int32_t> colour =
            GreedyPartColouring(CheckRankShares(p, shares), &colours);
        EXPECT_EQ(colour, ps.colour);
        int64_t cut = 0;
        for (const RankShare& s : shares) cut += s.cut_edges;
        EXPECT_EQ(cut, ps.cut_edges);
        // On threads: the directory from each rank's range of parts, the ghosts from the owners.
        std::vector<RankNeighbourhood> got(P);
        ThreadCommunicator::Run(P, [&](Communicator& tx) {
          const int64_t a = RangeFirst(tx.rank(), n, P), b = RangeFirst(tx.rank() + 1, n, P);
          const std::vector<int32_t> mine(part.begin() + a, part.begin() + b);
          got[tx.rank()] = ReadPartNeighbourhood(
              p, tx.rank(), P, GatherOwnedIds(tx, n, mine),
              [&](const std::vector<int64_t>& g) { return LookUpParts(tx, n, mine, g); },
              GhostExchange(tx));
        });
        for (int32_t r = 0; r < P; ++r) {
          SCOPED_TRACE("rank " + std::to_string(r));
          const RankPart whole =
              BuildRankPart(m, part, P, ps.colour, r, "bfs", 5, CutPlacement::kLast);
          ExpectSameParts(BuildRankPart(nbs[r], colour, "bfs", 5, CutPlacement::kLast), whole);
          ExpectSameParts(BuildRankPart(got[r], colour, "bfs", 5, CutPlacement::kLast), whole);
          ++checked;
        }
      }
  }
  EXPECT_GT(checked, 20);
}

// The graph rows a rank hands a distributed partitioner: the same from the file as from the mesh.
TEST(RankNeighbourhood, GraphRowsFromTheFileAreTheMeshs) {
  TempDir dir;
  const std::string p = dir / "m.mrm";
  for (const Mesh& m : LaidOutCorpus()) {
    WriteMeshFile(m, p);
    for (int32_t P = 1; P <= std::min(4, m.NumVertices()); ++P)
      for (int32_t r = 0; r < P; ++r) {
        const GraphRows a = RangeGraphRows(m, r, P), b = ReadRangeGraphRows(p, r, P);
        EXPECT_EQ(a.vertices, b.vertices);
        EXPECT_EQ(a.first, b.first);
        EXPECT_EQ(a.off, b.off);
        EXPECT_EQ(a.adj, b.adj);
        EXPECT_EQ(a.first, RangeFirst(r, m.NumVertices(), P));
        EXPECT_EQ(static_cast<int64_t>(a.off.size()) - 1,
                  RangeFirst(r + 1, m.NumVertices(), P) - a.first);
        for (size_t i = 0; i + 1 < a.off.size(); ++i)  // each row the vertex's neighbours, sorted
          EXPECT_TRUE(std::is_sorted(a.adj.begin() + a.off[i], a.adj.begin() + a.off[i + 1]));
        EXPECT_GT(b.bytes_read, 0u);
      }
  }
}

// The ghosts from their owners (GhostExchange, ranks as threads) equal the ghosts read from the
// file, and a rank then reads its share of the file and little more.
TEST(RankNeighbourhood, GhostsFromTheirOwnersEqualTheFilesAndReadingIsTheRanksShare) {
  TempDir dir;
  SyntheticOptions o;
  o.nx = 400, o.ny = 320, o.holes = 1, o.seed = 2;
  Mesh m = BuildMesh(MakeSyntheticMesh(o));
  LayOutForRanks(&m);
  const std::string p = dir / "m.mrm";
  WriteMeshFile(m, p);
  const double size = static_cast<double>(ReadBytes(p).size());
  for (int32_t P : {1, 2, 4, 7}) {
    std::vector<RankNeighbourhood> got(P);
    ThreadCommunicator::Run(P, [&](Communicator& tx) {
      got[tx.rank()] = ReadRankNeighbourhood(p, tx.rank(), P, GhostExchange(tx));
    });
    for (int32_t r = 0; r < P; ++r) {
      const RankNeighbourhood file = ReadRankNeighbourhood(p, r, P);
      const RankNeighbourhood& nb = got[r];
      ASSERT_EQ(nb.gid, file.gid);
      EXPECT_EQ(std::memcmp(nb.mesh.xy.data(), file.mesh.xy.data(), 8 * nb.mesh.xy.size()), 0);
      EXPECT_EQ(nb.mesh.boundary, file.mesh.boundary);
      if (!nb.weight.empty()) {
        EXPECT_EQ(std::memcmp(nb.weight.data(), file.weight.data(), 8 * nb.weight.size()), 0);
      }
      EXPECT_EQ(nb.part, file.part);
      // Its share of the vertex-indexed sections and of the triangles, plus the blocks its range
      // straddles and the pages of the block table: within 4% of the file beyond 1/P.
      EXPECT_LT(static_cast<double>(nb.bytes_read), size * (1.0 / P + 0.04)) << P << " " << r;
      EXPECT_LT(nb.bytes_read, file.bytes_read + (P == 1 ? 1 : 0)) << P << " " << r;
    }
  }
}

TEST(RankNeighbourhood, InconsistentFilesAreRefusedByTheOwner) {
  TempDir dir;
  SyntheticOptions o;
  o.nx = 30, o.ny = 20, o.seed = 4;
  Mesh m = BuildMesh(MakeSyntheticMesh(o));
  LayOutForRanks(&m);
  const std::string good = dir / "good.mrm", bad = dir / "bad.mrm";
  WriteMeshFile(m, good);
  const std::string b = ReadBytes(good);
  const int64_t v = m.NumVertices(), t = m.NumTriangles();
  const int64_t flags = 128 + 16 * v, offs = flags + Pad8(v), rows = offs + 8 * (v + 1);
  const int64_t tris = rows + Pad8(12 * t);
  constexpr int32_t P = 3;
  // Which rank throws, and what: the others read their parts.
  auto refused_by = [&](const std::string& bytes, int32_t owner, const std::string& expect) {
    WriteBytes(bad, RehashMeshFile(bytes));
    for (int32_t r = 0; r < P; ++r) {
      try {
        ReadRankNeighbourhood(bad, r, P);
        EXPECT_NE(r, owner) << expect;
      } catch (const InputError& e) {
        EXPECT_EQ(r, owner) << e.what();
        EXPECT_TRUE(HasText(e.what(), bad + ": ")) << e.what();
        EXPECT_TRUE(HasText(e.what(), expect)) << e.what();
      }
    }
  };
  // A boundary vertex flagged interior: only its owner can tell.
  const int32_t bv =
      static_cast<int32_t>(std::find(m.boundary.begin(), m.boundary.end(), 1) - m.boundary.begin());
  std::string x = b;
  x[flags + bv] = 0;
  refused_by(x, RangeOwner(bv, v, P),
             "vertex " + std::to_string(bv) +
                 ": boundary flag 0, but its triangles make it a "
                 "boundary vertex");
  // A triangle's corner moved to another vertex: the old corner's row lists a triangle without it.
  const int32_t tt = t / 2;
  const int32_t old = m.tri[3 * tt];
  int32_t other = m.tri[3 * tt + 1];
  for (int32_t w = 0; w < v; ++w)
    if (w != m.tri[3 * tt] && w != m.tri[3 * tt + 1] && w != m.tri[3 * tt + 2]) other = w;
  x = b;
  std::memcpy(&x[tris + 12 * tt], &other, 4);
  {
    WriteBytes(bad, RehashMeshFile(x));
    bool seen = false;
    for (int32_t r = 0; r < P; ++r) try {
        ReadRankNeighbourhood(bad, r, P);
      } catch (const InputError& e) {
        seen = true;
        const std::string w = e.what();
        EXPECT_TRUE(
            HasText(w, "vertex " + std::to_string(old) + ": its v2t row lists triangle " +
                           std::to_string(tt) + ", which does not") ||
            HasText(w, "triangle " + std::to_string(tt) + " has vertex " + std::to_string(other)))
            << w;
      }
    EXPECT_TRUE(seen);
  }
  // A corner repeated (c0, c0, c2): c0's pair with the triangle counts twice, balancing the
  // count of c1's row, which lists the triangle without c1 (the graph-rows reader once overran a
  // row's room on such a file: fuzz_mesh_file). Every rank whose rows list it refuses it, by both
  // readers.
  x = b;
  std::memcpy(&x[tris + 12 * tt + 4], &m.tri[3 * tt], 4);
  {
    WriteBytes(bad, RehashMeshFile(x));
    int refused = 0;
    for (int32_t r = 0; r < P; ++r)
      for (int reader = 0; reader < 2; ++reader) try {
          if (reader == 0)
            ReadRankNeighbourhood(bad, r, P);
          else
            ReadRangeGraphRows(bad, r, P);
        } catch (const InputError& e) {
          ++refused;
          EXPECT_TRUE(HasText(e.what(), "triangle " + std::to_string(tt) +
                                            ": degenerate triangle: vertex " +
                                            std::to_string(m.tri[3 * tt]) + " is used twice"))
              << e.what();
        }
    EXPECT_GE(refused, 2);
  }
  // A row out of order.
  const int32_t rv = m.interior[m.interior.size() / 2];
  x = b;
  const int64_t a = m.v2t.off[rv];
  std::swap(x[rows + 4 * a], x[rows + 4 * (a + 1)]);
  std::swap(x[rows + 4 * a + 1], x[rows + 4 * (a + 1) + 1]);
  std::swap(x[rows + 4 * a + 2], x[rows + 4 * (a + 1) + 2]);
  std::swap(x[rows + 4 * a + 3], x[rows + 4 * (a + 1) + 3]);
  refused_by(x, RangeOwner(rv, v, P), "vertex " + std::to_string(rv) + ": its v2t row lists");
  // An empty row.
  x = b;
  std::memcpy(&x[offs + 8 * (rv + 1)], &a, 8);
  {
    WriteBytes(bad, RehashMeshFile(x));
    EXPECT_THROW(ReadRankNeighbourhood(bad, RangeOwner(rv, v, P), P), InputError);
  }
  // Too many ranks.
  EXPECT_THROW(ReadRankNeighbourhood(good, 0, static_cast<int32_t>(v) + 1), UsageError);
}

TEST(RankNeighbourhood, WhatNoRankSeesAloneIsRefusedOnEveryRank) {
  auto share = [](uint64_t id, int64_t tris, int64_t entries, std::vector<int32_t> nbrs) {
    RankShare s;
    s.content_id = id, s.vertices = 10, s.triangles = 8;
    s.owned_triangles = tris, s.row_entries = entries, s.neighbours = std::move(nbrs);
    s.owned = 5;
    return s;
  };
  const std::vector<RankShare> good = {share(1, 5, 12, {1}), share(1, 3, 12, {0})};
  EXPECT_EQ(CheckRankShares("f", good), (std::vector<std::vector<int32_t>>{{1}, {0}}));
  auto error = [](const std::vector<RankShare>& s) {
    try {
      CheckRankShares("f.mrm", s);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(none)");
  };
  EXPECT_TRUE(HasText(error({share(1, 5, 12, {1}), share(2, 3, 12, {0})}),
                      "rank 1 read another mesh file than rank 0"))
      << error({share(1, 5, 12, {1}), share(2, 3, 12, {0})});
  EXPECT_TRUE(HasText(error({share(1, 4, 12, {1}), share(1, 3, 12, {0})}),
                      "found 7 triangles and 24 v2t entries, the header says 8"))
      << error({share(1, 4, 12, {1}), share(1, 3, 12, {0})});
  EXPECT_TRUE(HasText(error({share(1, 5, 12, {1}), share(1, 3, 11, {0})}), "23 v2t entries"))
      << error({share(1, 5, 12, {1}), share(1, 3, 11, {0})});
  {  // a partition that leaves a vertex out (or gives one to two ranks)
    std::vector<RankShare> s = {share(1, 5, 12, {1}), share(1, 3, 12, {0})};
    s[1].owned = 4;
    EXPECT_TRUE(HasText(error(s), "the ranks own 9 vertices, the header says 10")) << error(s);
  }
  EXPECT_TRUE(HasText(error({share(1, 5, 12, {1}), share(1, 3, 12, {})}), "ranks 0 and 1 disagree"))
      << error({share(1, 5, 12, {1}), share(1, 3, 12, {})});
  EXPECT_TRUE(HasText(error({share(1, 5, 12, {2}), share(1, 3, 12, {})}), "ranks 0 and 2 disagree"))
      << error({share(1, 5, 12, {2}), share(1, 3, 12, {})});
}

}  // namespace
}  // namespace meshreuse
