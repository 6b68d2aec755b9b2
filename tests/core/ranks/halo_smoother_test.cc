// The distributed smoother (core/ranks/rank_part.h, core/ranks/halo_smoother.h) run with its real
// schedule on P threads (core/ranks/thread_communicator.h), against serial references written here:
//   ordered == a literal serial Gauss-Seidel along the gathered pi, bit for bit, sweep by sweep
//              quality (exact fixed-point sums of the serial mesh) and stop sweep included;
//   jacobi  == the serial smoother's Jacobi, bit for bit, and the same Q and sweep count for every
//   P; P = 1, ori == today's Smooth(), bit for bit.
// On the 26-mesh corpus, Hilbert and METIS partitions, P = 1..5, layouts ori/bfs/random; an empty
// part, parts without interior vertices, one part. The references are shown to tell apart what
// they must: ordered differs from the serial storage-order sweep and from hybrid when parts touch.
// The layout is checked on its own: groups, rows by global id, links that agree end to end.
#include "core/ranks/halo_smoother.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "core/quality.h"
#include "core/ranks/partition.h"
#include "core/ranks/rank_part.h"
#include "core/ranks/thread_communicator.h"
#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {
using namespace testing;

struct DistRun {
  std::vector<RankPart> parts;
  std::vector<HaloResult> results;
  std::vector<std::vector<HaloSweep>> seen;  // on_sweep's records, per rank
};

DistRun RunParts(const Mesh& m, const std::vector<int32_t>& part, int32_t P, const HaloOptions& opt,
                 const std::string& ordering = "ori",
                 CutPlacement placement = CutPlacement::kLast) {
  const PartitionStats ps = MeasurePartition(m, part, P);
  DistRun d;
  for (int32_t r = 0; r < P; ++r)
    d.parts.push_back(BuildRankPart(m, part, P, ps.colour, r, ordering, 7, placement));
  d.results.resize(P);
  d.seen.resize(P);
  ThreadCommunicator::Run(P, [&](Communicator& tx) {
    const int32_t r = tx.rank();
    d.results[r] = SmoothRankPart(d.parts[r], opt, tx,
                                  [&d, r](const HaloSweep& s) { d.seen[r].push_back(s); });
  });
  return d;
}

// The whole mesh with every rank's owned vertices written back.
Mesh Assemble(const Mesh& m, const std::vector<RankPart>& parts) {
  Mesh out = m.Clone();
  for (const RankPart& p : parts)
    for (int32_t k = 0; k < p.owned; ++k) {
      out.xy[2 * p.gid[k]] = p.xy[2 * int64_t{k}];
      out.xy[2 * p.gid[k] + 1] = p.xy[2 * int64_t{k} + 1];
    }
  return out;
}

bool SameBits(const Mesh& a, const Mesh& b) {
  return a.xy.size() == b.xy.size() &&
         std::memcmp(a.xy.data(), b.xy.data(), a.xy.size() * sizeof(double)) == 0;
}

// The serial Gauss-Seidel sweep along `order`, literally: each vertex to the average of its
// neighbours in increasing id order (the mesh's rows), in place. Returns Q after each sweep, and
// stops as the distributed run does.
std::vector<FixedSum> SerialAlong(Mesh* m, const std::vector<int64_t>& order,
                                  const HaloOptions& opt) {
  std::vector<FixedSum> q{FixedGlobalQuality(*m)};
  for (int it = 1; it <= opt.max_iters; ++it) {
    for (int64_t v : order) {
      double sx = 0, sy = 0;
      const int32_t* b = m->v2v.RowBegin(static_cast<int32_t>(v));
      const int32_t* e = m->v2v.RowEnd(static_cast<int32_t>(v));
      for (const int32_t* u = b; u != e; ++u) sx += m->xy[2 * *u], sy += m->xy[2 * *u + 1];
      const double inv = 1.0 / static_cast<double>(e - b);
      m->xy[2 * v] = sx * inv;
      m->xy[2 * v + 1] = sy * inv;
    }
    q.push_back(FixedGlobalQuality(*m));
    if (q.back().Minus(q[q.size() - 2]) < opt.tol) break;
  }
  return q;
}

HaloOptions Sweeps(int k, HaloMode mode = HaloMode::kOrdered) {
  HaloOptions o;
  o.max_iters = k;
  o.tol = -1;
  o.mode = mode;
  return o;
}

// method 0: Hilbert ranges, 1 (or true): METIS, 2: Scotch.
std::vector<int32_t> PartsOf(const Mesh& m, int32_t P, int method) {
  return method == 2 ? ScotchParts(m, P, 3)
         : method    ? MetisParts(m, P, 3)
                     : HilbertRangeParts(m, P);
}

TEST(RankPart, LayoutGroupsRowsAndLinksAgree) {
  for (const Mesh& m : MeshCorpus())
    for (int32_t P : {1, 2, 3, 5}) {
      if (P > m.NumVertices()) continue;
      const std::vector<int32_t> part = PartsOf(m, P, P == 3);
      const PartitionStats ps = MeasurePartition(m, part, P);
      std::vector<RankPart> parts;
      for (int32_t r = 0; r < P; ++r)
        parts.push_back(BuildRankPart(m, part, P, ps.colour, r, P == 5 ? "bfs" : "ori"));
      std::map<std::pair<int32_t, int32_t>, std::vector<int64_t>> sent, received;
      int64_t owned = 0, triangles = 0;
      for (const RankPart& p : parts) {
        owned += p.owned;
        triangles += static_cast<int64_t>(p.weight.size());
        std::set<int64_t> ghosts;  // naive: every other part's vertex next to an owned one
        for (int32_t k = 0; k < p.owned; ++k) {
          const int32_t v = static_cast<int32_t>(p.gid[k]);
          ASSERT_EQ(part[v], p.rank);
          bool cut = false;
          for (const int32_t* u = m.v2v.RowBegin(v); u != m.v2v.RowEnd(v); ++u)
            if (part[*u] != p.rank) cut = true, ghosts.insert(*u);
          const int group = m.boundary[v] ? 2 : cut ? 1 : 0;
          EXPECT_EQ(group, k < p.noncut ? 0 : k < p.movable ? 1 : 2) << "vertex " << v;
          if (k < p.movable) {  // the row: the mesh's row, same order, through gid
            ASSERT_EQ(p.v2v.RowSize(k), m.v2v.RowSize(v));
            for (int64_t i = 0; i < p.v2v.RowSize(k); ++i)
              EXPECT_EQ(p.gid[p.v2v.RowBegin(k)[i]], m.v2v.RowBegin(v)[i]);
          }
        }
        EXPECT_EQ(std::set<int64_t>(p.gid.begin() + p.owned, p.gid.end()), ghosts);
        for (const RankLink& l : p.links) {
          EXPECT_NE(l.colour, p.colour);
          for (int32_t k : l.send) sent[{p.rank, l.rank}].push_back(p.gid[k]);
          for (int32_t k : l.recv) received[{l.rank, p.rank}].push_back(p.gid[k]);
        }
      }
      EXPECT_EQ(owned, m.NumVertices());
      EXPECT_EQ(triangles, m.NumTriangles());  // each triangle on exactly one rank
      EXPECT_EQ(sent, received) << "P " << P;  // what r sends q is what q expects, in order
    }
}

TEST(HaloSmoother, OrderedEqualsSerialGaussSeidelAlongPi) {
  int differs_from_storage_order = 0, differs_from_hybrid = 0, cases = 0;
  for (const Mesh& m : MeshCorpus())
    for (int32_t P : {1, 2, 3, 4, 5})
      for (int metis : {0, 1, 2}) {  // Hilbert, METIS, Scotch
        if (P > m.NumVertices()) continue;
        const std::string ordering = P % 2 ? "ori" : metis ? "random" : "bfs";
        const std::vector<int32_t> part = PartsOf(m, P, metis);
        const DistRun d = RunParts(m, part, P, Sweeps(4), ordering);
        Mesh serial = m.Clone();
        const std::vector<FixedSum> q =
            SerialAlong(&serial, GatheredVisitOrder(d.parts), Sweeps(4));
        const Mesh got = Assemble(m, d.parts);
        ASSERT_TRUE(SameBits(got, serial)) << "P " << P << " metis " << metis << " " << ordering;
        for (int32_t r = 0; r < P; ++r) {
          EXPECT_EQ(d.results[r].quality_before, q[0]);
          EXPECT_EQ(d.results[r].quality_after, q.back());
          ASSERT_EQ(d.seen[r].size(), 4u);
          for (int s = 0; s < 4; ++s) EXPECT_EQ(d.seen[r][s].quality, q[s + 1].ToDouble());
        }
        ++cases;
        Mesh storage = m.Clone();
        Smooth(storage, ExactSweeps(4));
        differs_from_storage_order += !SameBits(got, storage);
        differs_from_hybrid +=
            !SameBits(got, Assemble(m, RunParts(m, part, P, Sweeps(4, HaloMode::kHybrid)).parts));
      }
  // The references tell orders apart: with several parts the order (and so the bits) change.
  EXPECT_GT(differs_from_storage_order, cases / 3);
  EXPECT_GT(differs_from_hybrid, cases / 3);
}

// Cut vertices first (moved and sent before the non-cut ones) and interleaved (where the ordering
// puts them): each equals the serial sweep along its own pi, and the three placements are three
// different orders.
TEST(HaloSmoother, EveryCutPlacementEqualsItsSerialOrder) {
  int first_differs = 0, interleaved_differs = 0, cases = 0;
  for (const Mesh& m : MeshCorpus())
    for (int32_t P : {2, 3, 4})
      for (bool metis : {false, true}) {
        if (P > m.NumVertices()) continue;
        const std::string ordering = metis ? "bfs" : "ori";
        const std::vector<int32_t> part = PartsOf(m, P, metis);
        const Mesh last = Assemble(m, RunParts(m, part, P, Sweeps(3), ordering).parts);
        for (CutPlacement c : {CutPlacement::kFirst, CutPlacement::kInterleaved}) {
          const DistRun d = RunParts(m, part, P, Sweeps(3), ordering, c);
          for (const RankPart& p : d.parts) {  // the layout: cut vertices where asked
            for (int32_t k = 0; k < p.movable; ++k) {
              const int32_t v = static_cast<int32_t>(p.gid[k]);
              bool cut = false;
              for (const int32_t* u = m.v2v.RowBegin(v); u != m.v2v.RowEnd(v); ++u)
                cut = cut || part[*u] != p.rank;
              if (c == CutPlacement::kFirst) {
                EXPECT_EQ(cut, k < p.cut()) << "vertex " << v;
              }
            }
            EXPECT_EQ(p.placement, c);
          }
          Mesh serial = m.Clone();
          const std::vector<FixedSum> q =
              SerialAlong(&serial, GatheredVisitOrder(d.parts), Sweeps(3));
          const Mesh got = Assemble(m, d.parts);
          ASSERT_TRUE(SameBits(got, serial))
              << "P " << P << " metis " << metis << " " << CutPlacementName(c);
          for (int32_t r = 0; r < P; ++r) EXPECT_EQ(d.results[r].quality_after, q.back());
          (c == CutPlacement::kFirst ? first_differs : interleaved_differs) += !SameBits(got, last);
        }
        ++cases;
      }
  EXPECT_GT(first_differs, cases / 3);
  EXPECT_GT(interleaved_differs, cases / 3);
}

TEST(HaloSmoother, OnePartOriEqualsTodaysSmoother) {
  for (const Mesh& m : MeshCorpus()) {
    const DistRun d = RunParts(m, std::vector<int32_t>(m.NumVertices(), 0), 1, Sweeps(5));
    Mesh serial = m.Clone();
    Smooth(serial, ExactSweeps(5));
    EXPECT_TRUE(SameBits(Assemble(m, d.parts), serial));
    const DistRun j =
        RunParts(m, std::vector<int32_t>(m.NumVertices(), 0), 1, Sweeps(5, HaloMode::kJacobi));
    Mesh jacobi = m.Clone();
    Smooth(jacobi, ExactSweeps(5, 1, UpdateMode::kJacobi));
    EXPECT_TRUE(SameBits(Assemble(m, j.parts), jacobi));
    const DistRun h =
        RunParts(m, std::vector<int32_t>(m.NumVertices(), 0), 1, Sweeps(5, HaloMode::kHybrid));
    EXPECT_TRUE(SameBits(Assemble(m, h.parts), serial));  // one part: no halo, plain GS
  }
}

TEST(HaloSmoother, JacobiEqualsSerialJacobiWithTheSameQualityForEveryP) {
  SyntheticOptions o;
  o.nx = 40, o.ny = 30, o.holes = 2, o.seed = 6;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  HaloOptions opt;  // stops by the tolerance: the stop sweep must agree too
  opt.mode = HaloMode::kJacobi;
  opt.tol = 1e-5;
  Mesh serial = m.Clone();
  SmoothOptions so = ExactSweeps(0, 1, UpdateMode::kJacobi);
  std::vector<FixedSum> q{FixedGlobalQuality(serial)};
  for (int it = 1; it <= opt.max_iters; ++it) {  // one serial sweep at a time, Q summed exactly
    so.max_iters = 1;
    Smooth(serial, so);
    q.push_back(FixedGlobalQuality(serial));
    if (q.back().Minus(q[q.size() - 2]) < opt.tol) break;
  }
  ASSERT_GT(q.size(), 3u);
  ASSERT_LT(q.size(), static_cast<size_t>(opt.max_iters) + 1);
  for (int32_t P : {1, 2, 3, 4, 7})
    for (bool metis : {false, true}) {
      const DistRun d = RunParts(m, PartsOf(m, P, metis), P, opt, metis ? "bfs" : "ori");
      EXPECT_TRUE(SameBits(Assemble(m, d.parts), serial)) << P;
      for (int32_t r = 0; r < P; ++r) {
        EXPECT_EQ(d.results[r].sweeps.size() + 1, q.size()) << P;
        EXPECT_TRUE(d.results[r].converged);
        EXPECT_EQ(d.results[r].quality_after, q.back());
      }
    }
}

TEST(HaloSmoother, OrderedStopsWhereTheSerialSweepAlongPiStops) {
  SyntheticOptions o;
  o.nx = 30, o.ny = 25, o.holes = 1, o.seed = 9;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  HaloOptions opt;
  opt.tol = 1e-5;
  for (int32_t P : {2, 3, 4}) {
    const DistRun d = RunParts(m, HilbertRangeParts(m, P), P, opt);
    Mesh serial = m.Clone();
    const std::vector<FixedSum> q = SerialAlong(&serial, GatheredVisitOrder(d.parts), opt);
    ASSERT_GT(q.size(), 3u);
    EXPECT_TRUE(SameBits(Assemble(m, d.parts), serial));
    for (const HaloResult& r : d.results) {
      EXPECT_EQ(r.sweeps.size() + 1, q.size());
      EXPECT_TRUE(r.converged);
    }
  }
}

TEST(HaloSmoother, EmptyPartsAndPartsWithoutInteriorVertices) {
  SyntheticOptions o;
  o.nx = 12, o.ny = 9, o.holes = 1, o.seed = 4;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  // Parts 1 and 3 empty; vertices dealt to parts 0, 2, 4 by id.
  std::vector<int32_t> part(m.NumVertices());
  for (int32_t v = 0; v < m.NumVertices(); ++v) part[v] = 2 * (v % 3);
  std::vector<std::vector<int32_t>> partitions{part};
  // Many small parts: most hold no interior vertex (and one rank per vertex).
  partitions.push_back(HilbertRangeParts(m, m.NumVertices() / 2));
  partitions.push_back(HilbertRangeParts(m, m.NumVertices()));
  for (const std::vector<int32_t>& p : partitions) {
    const int32_t P = *std::max_element(p.begin(), p.end()) + 1;
    for (HaloMode mode : {HaloMode::kOrdered, HaloMode::kJacobi}) {
      const DistRun d = RunParts(m, p, P, Sweeps(3, mode));
      Mesh serial = m.Clone();
      if (mode == HaloMode::kOrdered)
        SerialAlong(&serial, GatheredVisitOrder(d.parts), Sweeps(3));
      else
        Smooth(serial, ExactSweeps(3, 1, UpdateMode::kJacobi));
      EXPECT_TRUE(SameBits(Assemble(m, d.parts), serial)) << P << " " << HaloModeName(mode);
    }
  }
}

TEST(HaloSmoother, HybridConvergesToTheSameMesh) {
  SyntheticOptions o;
  o.nx = 10, o.ny = 8, o.seed = 2;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  Mesh serial = m.Clone();
  Smooth(serial, ExactSweeps(1500));  // converged: the error shrinks by about 0.9 a sweep here
  for (int32_t P : {2, 4}) {
    const Mesh h =
        Assemble(m, RunParts(m, HilbertRangeParts(m, P), P, Sweeps(1500, HaloMode::kHybrid)).parts);
    for (size_t i = 0; i < h.xy.size(); ++i) ASSERT_NEAR(h.xy[i], serial.xy[i], 1e-9) << P;
  }
}

TEST(HaloSmoother, AFailingRankEndsEveryRank) {
  EXPECT_THROW(ThreadCommunicator::Run(3,
                                       [](Communicator& tx) {
                                         if (tx.rank() == 1)
                                           throw std::invalid_argument("rank 1 fails");
                                         double x;
                                         tx.RecvValues(1, &x, sizeof x);  // would wait forever
                                       }),
               std::invalid_argument);
}

// Add works from the double's bits; the reference scales exactly with ldexp and lets the compiler
// convert (truncating), one term at a time, on terms of every binade in [0, 64), subnormals,
// values just below 64 and the unit's neighbourhood.
TEST(FixedSum, AddFromBitsEqualsScaleAndTruncate) {
  std::mt19937_64 rng(5);
  std::vector<double> xs = {0.0,
                            -0.0,  // accepted, and zero (its sign bit once read as exponent)
                            std::nextafter(64.0, 0.0),
                            1.0,
                            0.5,
                            std::ldexp(1.0, -120),
                            std::ldexp(1.0, -121),
                            std::ldexp(1.5, -120),
                            std::ldexp(3.0, -122),
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::min(),
                            std::ldexp(1.0, -68),
                            std::ldexp(1.0 + std::ldexp(1.0, -52), -68)};
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> binade(-130, 5);
  for (int i = 0; i < 200000; ++i) xs.push_back(std::ldexp(unit(rng), binade(rng)));
  for (double x : xs) {
    FixedSum fast;
    fast.Add(x);
    const unsigned __int128 ref = static_cast<unsigned __int128>(std::ldexp(x, 120));
    uint64_t w[2];
    fast.ToWords(w);
    ASSERT_EQ(w[0], static_cast<uint64_t>(ref)) << x;
    ASSERT_EQ(w[1], static_cast<uint64_t>(ref >> 64)) << x;
  }
}

TEST(FixedSum, ExactWhateverTheOrderAndCloseToTheFloatingSum) {
  const Mesh m = std::move(MeshCorpus()[5]);
  const FixedSum q = FixedGlobalQuality(m);
  EXPECT_NEAR(q.ToDouble(), GlobalQuality(m), 1e-12);
  FixedSum back;  // the same terms added backwards, and split in two halves
  for (int32_t t = m.NumTriangles() - 1; t >= 0; --t)
    back.Add(GlobalQualityWeight(m, t) * TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{t}]));
  EXPECT_EQ(back, q);
  FixedSum a, b;
  a.Add(0.1), a.Add(0.2), b.Add(0.3);
  uint64_t w[2];
  a.ToWords(w);
  FixedSum c = FixedSum::FromWords(w);
  c.Add(b);
  FixedSum d;
  d.Add(0.3), d.Add(0.2), d.Add(0.1);
  EXPECT_EQ(c, d);  // (0.1 + 0.2) + 0.3 == 0.1 + (0.2 + 0.3) in floating point it is not
  EXPECT_NE(0.1 + 0.2 + 0.3, 0.3 + 0.2 + 0.1);
  EXPECT_THROW(d.Add(-1e-300), std::logic_error);
  EXPECT_THROW(d.Add(64.0), std::logic_error);
}

}  // namespace
}  // namespace meshreuse
