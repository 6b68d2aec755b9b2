// Every registered ordering, on many random meshes (holes, graded cells, boundary vertices with no
// interior neighbour): a bijection (Theorem 1 for rdr), deterministic for a fixed seed, and Jacobi
// smoothing under it, mapped back, equals Jacobi smoothing without it to 1e-12. Then exact orders
// worked out by hand for rdr, bfs, rbfs and hilbert, properties of rcm, and file: errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/orderings/common.h"
#include "core/orderings/rdr.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

namespace fs = std::filesystem;

// A boundary vertex whose neighbours are all boundary vertices (RDR may never reach it).
bool HasIsolatedBoundaryVertex(const Mesh& m) {
  for (int32_t v = 0; v < m.NumVertices(); ++v) {
    if (!m.boundary[v]) continue;
    bool any_interior = false;
    for (const int32_t* p = m.v2v.RowBegin(v); p != m.v2v.RowEnd(v); ++p)
      any_interior |= !m.boundary[*p];
    if (!any_interior) return true;
  }
  return false;
}

// "file" needs a file: a seeded shuffle written in the file: format.
std::string SpecFor(const OrderingInfo& o, const Mesh& m, const fs::path& dir, int k) {
  if (!o.takes_argument()) return o.name;
  std::vector<int32_t> order(m.NumVertices());
  for (int32_t i = 0; i < m.NumVertices(); ++i) order[i] = i;
  SplitMix64 rng(1000 + k);
  for (int32_t i = m.NumVertices() - 1; i > 0; --i) std::swap(order[i], order[rng.Below(i + 1)]);
  const std::string path = (dir / ("perm" + std::to_string(k))).string();
  WritePermutation(order, path, "test");
  return std::string(o.name) + ":" + path;
}

class EveryOrdering : public ::testing::TestWithParam<OrderingInfo> {
 protected:
  testing::TempDir tmp_;
  const fs::path& dir_ = tmp_.path();
};

TEST_P(EveryOrdering, BijectionDeterministicAndJacobiInvariant) {
  const OrderingInfo& o = GetParam();
  const std::vector<Mesh> corpus = testing::MeshCorpus();
  int isolated = 0;
  for (size_t k = 0; k < corpus.size(); ++k) {
    const Mesh& m = corpus[k];
    SCOPED_TRACE("mesh " + std::to_string(k) + " (" + std::to_string(m.NumVertices()) +
                 " vertices)");
    isolated += HasIsolatedBoundaryVertex(m);
    const std::string spec = SpecFor(o, m, dir_, static_cast<int>(k));
    const Permutation p = ComputeOrdering(spec, m, 42);
    ASSERT_EQ(p.size(), m.NumVertices());
    std::vector<int32_t> sorted = p.new_to_old();
    std::sort(sorted.begin(), sorted.end());
    for (int32_t i = 0; i < m.NumVertices(); ++i) ASSERT_EQ(sorted[i], i) << "not a bijection";
    EXPECT_EQ(ComputeOrdering(spec, m, 42).new_to_old(), p.new_to_old()) << "not deterministic";

    Mesh plain = m.Clone();
    Mesh reordered = ApplyPermutation(m, p);
    SmoothOptions so;
    so.mode = UpdateMode::kJacobi;
    so.max_iters = 6;
    so.tol = -std::numeric_limits<double>::infinity();
    const SmoothResult a = Smooth(plain, so);
    const SmoothResult b = Smooth(reordered, so);
    for (int32_t i = 0; i < m.NumVertices(); ++i) {
      ASSERT_NEAR(reordered.xy[2 * i], plain.xy[2 * p.OldOf(i)], 1e-12) << "new vertex " << i;
      ASSERT_NEAR(reordered.xy[2 * i + 1], plain.xy[2 * p.OldOf(i) + 1], 1e-12)
          << "new vertex " << i;
    }
    EXPECT_NEAR(a.quality_after, b.quality_after, 1e-12);
  }
  EXPECT_GE(isolated, 3)
      << "the corpus should exercise boundary vertices with no interior neighbour";
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryOrdering, ::testing::ValuesIn(Orderings()),
                         [](const ::testing::TestParamInfo<OrderingInfo>& i) {
                           std::string n = i.param.name;  // test names: [A-Za-z0-9_]
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

TEST(Registry, NamesAndErrors) {
  EXPECT_NE(FindOrdering("rdr"), nullptr);
  EXPECT_EQ(FindOrdering("nope"), nullptr);
  const Mesh m = testing::TwoInterior();
  EXPECT_THROW(ComputeOrdering("nope", m), std::invalid_argument);
  EXPECT_THROW(ComputeOrdering("file", m), std::invalid_argument);   // needs :PATH
  EXPECT_THROW(ComputeOrdering("rdr:x", m), std::invalid_argument);  // takes none
  for (const char* required : {"ori", "random", "bfs", "rbfs", "rcm", "rdr", "hilbert", "file"})
    EXPECT_NE(FindOrdering(required), nullptr) << required;
}

TEST(Random, SeedChangesTheOrder) {
  const Mesh m = testing::TwoInterior();
  std::set<std::vector<int32_t>> seen;
  for (uint64_t s = 1; s <= 10; ++s) seen.insert(ComputeOrdering("random", m, s).new_to_old());
  EXPECT_GT(seen.size(), 5u);
}

// two_interior: adjacency 0:{1,5,6} 1:{0,2,6,7} 2:{1,3,7} 3:{2,4,7} 4:{3,5,6,7} 5:{0,4,6}
// 6:{0,1,4,5,7} 7:{1,2,3,4,6}; interior 6 and 7.
TEST(Rdr, HandWorkedWithATie) {
  const Mesh m = testing::TwoInterior();
  const std::vector<double> q = {0.5, 0.3, 0.9, 0.1, 0.3, 0.7, 0.6, 0.2};  // 1 and 4 tie
  // Seeds by quality: 7 (0.2), 6 (0.6).
  // 7: append 7; l = unprocessed nbrs of 7 by quality = 3 (.1), 1 (.3), 4 (.3, tie: id 1 < 4),
  //    6 (.6), 2 (.9) -> append 3 1 4 6 2; process 3.
  // 3: l = 4, 2 -> nothing new; process 4.   4: l = 6, 5 -> append 5; process 6.
  // 6: l = 1 (.3), 0 (.5), 5 (.7) -> append 0; process 1.   1: l = 0, 2; process 0.
  // 0: l = 5; process 5.   5: l = {} -> done. Seed 6 is processed.
  EXPECT_EQ(RdrOrder(m, q).new_to_old(), (std::vector<int32_t>{7, 3, 1, 4, 6, 2, 5, 0}));
}

TEST(Rdr, HandWorkedUnreachedVerticesGoLast) {
  // two_components: triangle 0 1 2 alone (all boundary, no interior vertex: never reached) and a
  // wheel, centre 3 (the only interior vertex), rim 4 5 6 7 with 4:{3,5,7} 5:{3,4,6} 6:{3,5,7}
  // 7:{3,4,6}.
  const Mesh m = ReadMesh(testing::DataPath("two_components.node"));
  ASSERT_EQ(std::vector<int32_t>(m.interior.begin(), m.interior.end()), (std::vector<int32_t>{3}));
  const std::vector<double> q = {0.2, 0.2, 0.2, 0.5, 0.4, 0.4, 0.1, 0.4};
  // 3: append 3; l = 6 (.1), 4 5 7 (.4, by id) -> append 6 4 5 7; process 6.
  // 6: l = 5, 7 -> process 5.  5: l = 4 -> process 4.  4: l = 7 -> process 7.  7: l = {}.
  // Then the unreached 0 1 2 in id order.
  EXPECT_EQ(RdrOrder(m, q).new_to_old(), (std::vector<int32_t>{3, 6, 4, 5, 7, 0, 1, 2}));
}

TEST(Rdr, StartsAtTheWorstInteriorVertex) {
  const std::vector<Mesh> corpus = testing::MeshCorpus();
  for (const Mesh& m : corpus) {
    const std::vector<double> q = VertexQualities(m);
    int32_t worst = m.interior[0];
    for (int32_t v : m.interior)
      if (q[v] < q[worst]) worst = v;
    EXPECT_EQ(ComputeOrdering("rdr", m).OldOf(0), worst);
  }
}

TEST(Bfs, HandWorked) {
  const Mesh m = testing::TwoInterior();
  // From 0: 1 5 6; from 1: 2 7; from 5: 4; from 2: 3.
  EXPECT_EQ(ComputeOrdering("bfs", m).new_to_old(), (std::vector<int32_t>{0, 1, 5, 6, 2, 7, 4, 3}));
  EXPECT_EQ(ComputeOrdering("rbfs", m).new_to_old(),
            (std::vector<int32_t>{3, 4, 7, 2, 6, 5, 1, 0}));
  // Two components: the triangle first (from 0), then the wheel from its lowest id, 3.
  const Mesh c = ReadMesh(testing::DataPath("two_components.node"));
  EXPECT_EQ(ComputeOrdering("bfs", c).new_to_old(), (std::vector<int32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
}

TEST(Hilbert, UnitSquareFollowsTheCurve) {
  // The order-16 curve visits the quadrants (0,0), (0,1), (1,1), (1,0).
  EXPECT_EQ(ComputeOrdering("hilbert", testing::UnitSquare()).new_to_old(),
            (std::vector<int32_t>{0, 2, 3, 1}));
}

int64_t Bandwidth(const Mesh& m, const Permutation& p) {
  int64_t bw = 0;
  for (int32_t v = 0; v < m.NumVertices(); ++v)
    for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
      bw = std::max<int64_t>(bw, std::abs(p.NewOf(v) - p.NewOf(*q)));
  return bw;
}

TEST(Rcm, NarrowsTheBandOfALongStrip) {
  SyntheticOptions o;
  o.nx = 60, o.ny = 5, o.holes = 0, o.graded = false, o.jitter = 0.1, o.seed = 3;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  // Row-major ORI has bandwidth >= 61 (a row); RCM from a far end of the strip sweeps across it.
  EXPECT_GE(Bandwidth(m, ComputeOrdering("ori", m)), 61);
  EXPECT_LE(Bandwidth(m, ComputeOrdering("rcm", m)), 14);
  EXPECT_GT(Bandwidth(m, ComputeOrdering("random", m)), 200);
}

TEST(StableSortByKey, MatchesStdStableSort) {
  SplitMix64 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 1 + static_cast<int>(rng.Below(2000));
    std::vector<double> key(n);
    const int distinct = 1 + static_cast<int>(rng.Below(n + 5));  // many ties sometimes
    for (double& k : key)
      k = static_cast<double>(rng.Below(distinct)) / distinct * (trial % 5 + 0.5);
    if (trial % 7 == 0) key[rng.Below(n)] = 1e9;  // one far outlier crowds the rest into one bucket
    std::vector<int32_t> ids(n);
    for (int i = 0; i < n; ++i) ids[i] = i;
    std::vector<int32_t> expect = ids;
    std::stable_sort(expect.begin(), expect.end(),
                     [&](int32_t a, int32_t b) { return key[a] < key[b]; });
    ASSERT_EQ(orderings::StableSortByKey(ids, key), expect) << "trial " << trial;
  }
}

class FileOrdering : public ::testing::Test {
 protected:
  std::string Write(const std::string& text) {
    const std::string p = (dir_ / "p.perm").string();
    std::ofstream(p) << text;
    return p;
  }
  void ExpectError(const std::string& text, int64_t line, const std::string& msg) {
    const std::string p = Write(text);
    try {
      ComputeOrdering("file:" + p, mesh_);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), p);
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_NE(e.problem().find(msg), std::string::npos) << e.what();
    }
  }
  testing::TempDir tmp_;
  const fs::path& dir_ = tmp_.path();
  Mesh mesh_ = testing::TwoInterior();
};

TEST_F(FileOrdering, ReadsWhatReorderWrites) {
  const std::vector<int32_t> order = {7, 3, 1, 4, 6, 2, 5, 0};
  const std::string p = (dir_ / "w.perm").string();
  WritePermutation(order, p, "a comment");
  EXPECT_EQ(ComputeOrdering("file:" + p, mesh_).new_to_old(), order);
}

TEST_F(FileOrdering, ErrorsNameLineAndProblem) {
  ExpectError("0\n1\n2\nx\n4\n5\n6\n7\n", 4, "expected an integer for a vertex id, found 'x'");
  ExpectError("0\n1\n2\n3 4\n", 4, "one vertex id per line");
  ExpectError("0\n1\n2\n8\n", 4, "vertex id 8 is outside 0..7");
  ExpectError("0\n1\n# c\n2\n1\n", 5, "vertex id 1 is repeated (first on line 2)");
  ExpectError("0\n1\n2\n4\n5\n6\n7\n", 7,
              "the file has 7 ids, the mesh 8 vertices (vertex 3 is missing)");
  ExpectError("", 0, "the file has 0 ids");
  try {
    ComputeOrdering("file:" + (dir_ / "missing").string(), mesh_);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("cannot open"), std::string::npos);
  }
}

}  // namespace
}  // namespace meshreuse
