// The smoother: one sweep computed by hand (Gauss-Seidel and Jacobi differ exactly as they
// should), a naive reference smoother, boundary vertices never move, the incremental global
// quality equals the direct definition, and the stop rule.
#include "core/smoother.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

constexpr double kNoStop = -std::numeric_limits<double>::infinity();

SmoothOptions Sweeps(int n, UpdateMode mode = UpdateMode::kGaussSeidel, int threads = 1) {
  SmoothOptions o;
  o.max_iters = n;
  o.tol = kNoStop;
  o.mode = mode;
  o.threads = threads;
  return o;
}

Mesh Synthetic(uint64_t seed, int nx = 30, int ny = 24, int holes = 2) {
  SyntheticOptions o;
  o.nx = nx, o.ny = ny, o.holes = holes, o.seed = seed;
  return BuildMesh(MakeSyntheticMesh(o));
}

// Interior p = vertex 6 at (0.5, 0.75) with neighbours 0 1 4 5 7; q = vertex 7 at (3.25, 1.5)
// with neighbours 1 2 3 4 6. Boundary: (0,0) (2,0) (4,0) (4,2) (2,2) (0,2).
TEST(Smoother, HandComputedGaussSeidelSweep) {
  Mesh m = testing::TwoInterior();
  const SmoothResult r = Smooth(m, Sweeps(1));
  // p = ((0+2+2+0+3.25)/5, (0+0+2+2+1.5)/5); q then sees the new p.
  EXPECT_DOUBLE_EQ(m.xy[12], 1.45);
  EXPECT_DOUBLE_EQ(m.xy[13], 1.1);
  EXPECT_DOUBLE_EQ(m.xy[14], (2 + 4 + 4 + 2 + 1.45) / 5);  // 2.69
  EXPECT_DOUBLE_EQ(m.xy[15], (0 + 0 + 2 + 2 + 1.1) / 5);   // 1.02
  ASSERT_EQ(r.sweeps.size(), 1u);
  EXPECT_NEAR(r.sweeps[0].quality, GlobalQuality(m), 1e-15);
  EXPECT_NEAR(r.sweeps[0].improvement, r.quality_after - r.quality_before, 1e-15);
}

TEST(Smoother, HandComputedJacobiSweep) {
  Mesh m = testing::TwoInterior();
  const SmoothResult r = Smooth(m, Sweeps(1, UpdateMode::kJacobi));
  EXPECT_DOUBLE_EQ(m.xy[12], 1.45);
  EXPECT_DOUBLE_EQ(m.xy[13], 1.1);
  // q sees the old p (0.5, 0.75): Jacobi differs from Gauss-Seidel here.
  EXPECT_DOUBLE_EQ(m.xy[14], 2.5);
  EXPECT_DOUBLE_EQ(m.xy[15], 0.95);
  EXPECT_NEAR(r.sweeps[0].quality, GlobalQuality(m), 1e-15);
}

// A from-scratch Gauss-Seidel: neighbour sets from the triangles, boundary from edge counts.
std::vector<double> NaiveGaussSeidel(const Mesh& m, int sweeps) {
  const int32_t nv = m.NumVertices();
  std::vector<std::set<int32_t>> nbr(nv);
  std::map<std::pair<int32_t, int32_t>, int> edges;
  for (int32_t t = 0; t < m.NumTriangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.tri[3 * t + k], b = m.tri[3 * t + (k + 1) % 3];
      nbr[a].insert(b), nbr[b].insert(a);
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<bool> fixed(nv, false);
  for (const auto& [e, n] : edges)
    if (n == 1) fixed[e.first] = fixed[e.second] = true;
  std::vector<double> xy(m.xy.begin(), m.xy.end());
  for (int s = 0; s < sweeps; ++s)
    for (int32_t v = 0; v < nv; ++v) {
      if (fixed[v]) continue;
      double x = 0, y = 0;
      for (int32_t u : nbr[v]) x += xy[2 * u], y += xy[2 * u + 1];
      xy[2 * v] = x / nbr[v].size();
      xy[2 * v + 1] = y / nbr[v].size();
    }
  return xy;
}

TEST(Smoother, MatchesNaiveGaussSeidel) {
  for (uint64_t seed : {1, 2, 3, 4, 5}) {
    Mesh m = Synthetic(seed);
    const std::vector<double> expect = NaiveGaussSeidel(m, 7);
    Smooth(m, Sweeps(7));
    ASSERT_EQ(m.xy.size(), expect.size());
    for (size_t i = 0; i < expect.size(); ++i) ASSERT_NEAR(m.xy[i], expect[i], 1e-12) << i;
  }
}

TEST(Smoother, BoundaryVerticesNeverMove) {
  for (UpdateMode mode : {UpdateMode::kGaussSeidel, UpdateMode::kJacobi})
    for (int threads : {1, 2}) {
      Mesh m = Synthetic(11, 40, 30, 3);
      const std::vector<double> before(m.xy.begin(), m.xy.end());
      Smooth(m, Sweeps(15, mode, threads));
      int moved_interior = 0;
      for (int32_t v = 0; v < m.NumVertices(); ++v) {
        if (m.boundary[v]) {
          ASSERT_EQ(m.xy[2 * v], before[2 * v]) << "boundary vertex " << v << " moved";
          ASSERT_EQ(m.xy[2 * v + 1], before[2 * v + 1]) << "boundary vertex " << v << " moved";
        } else {
          moved_interior += m.xy[2 * v] != before[2 * v];
        }
      }
      EXPECT_GT(moved_interior, 0);
    }
}

TEST(Smoother, IncrementalQualityEqualsDirectDefinition) {
  for (UpdateMode mode : {UpdateMode::kGaussSeidel, UpdateMode::kJacobi}) {
    Mesh m = Synthetic(5);
    const SmoothResult r = Smooth(m, Sweeps(25, mode));
    EXPECT_NEAR(r.sweeps.back().quality, r.quality_after, 1e-12);
    EXPECT_GT(r.quality_after, r.quality_before);  // graded, jittered meshes do improve
  }
}

TEST(Smoother, JacobiDoesNotDependOnThreadCount) {
  Mesh a = Synthetic(8), b = Synthetic(8);
  Smooth(a, Sweeps(10, UpdateMode::kJacobi, 1));
  Smooth(b, Sweeps(10, UpdateMode::kJacobi, 2));
  EXPECT_EQ(a.xy, b.xy);
}

TEST(Smoother, StopRuleStopsAtTheFirstSweepBelowTol) {
  // Record the improvements of an unstopped run, then choose tol so the rule must stop at sweep k.
  Mesh probe = Synthetic(3);
  const SmoothResult all = Smooth(probe, Sweeps(30));
  ASSERT_EQ(all.sweeps.size(), 30u);
  EXPECT_FALSE(all.converged);  // tol = -inf never stops: max_iters did
  for (int k : {1, 4, 9}) {
    double tol = all.sweeps[k - 1].improvement * (1 + 1e-9);  // sweep k is just below tol...
    bool ok = true;
    for (int j = 0; j < k - 1; ++j) ok &= all.sweeps[j].improvement >= tol;  // ...earlier ones not
    if (!ok) continue;
    Mesh m = Synthetic(3);
    SmoothOptions o = Sweeps(30);
    o.tol = tol;
    const SmoothResult r = Smooth(m, o);
    EXPECT_EQ(r.sweeps.size(), static_cast<size_t>(k)) << "tol " << tol;
    EXPECT_TRUE(r.converged);
  }
  Mesh m = Synthetic(3);
  SmoothOptions o = Sweeps(30);
  o.tol = 1.0;  // no sweep improves the mean quality by 1
  EXPECT_EQ(Smooth(m, o).sweeps.size(), 1u);
  o.tol = 0;
  o.max_iters = 3;
  Mesh m2 = Synthetic(3);
  const SmoothResult r = Smooth(m2, o);
  EXPECT_EQ(r.sweeps.size(), 3u);
  EXPECT_FALSE(r.converged);
}

TEST(Smoother, SweepCallbackSeesEverySweep) {
  Mesh m = Synthetic(4);
  std::vector<int> seen;
  NullSink sink;
  const SmoothResult r =
      Smooth(m, Sweeps(5), sink, [&](const SweepRecord& s) { seen.push_back(s.sweep); });
  EXPECT_EQ(seen, (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(r.sweeps.size(), 5u);
}

// The lean sweep (--quality per-sweep) moves exactly as the default one (moves do not read the
// quality), and its once-per-sweep quality is the direct definition's, on 1 and 2 threads; the
// stop rule then stops at the same sweep.
TEST(Smoother, LeanSweepMovesAlikeAndMeasuresQualityPerSweep) {
  for (int threads : {1, 2}) {
    Mesh a = Synthetic(7), b = Synthetic(7);
    SmoothOptions per_move = Sweeps(12, UpdateMode::kGaussSeidel, threads), lean = per_move;
    lean.quality = QualityMode::kPerSweep;
    const SmoothResult ra = Smooth(a, per_move);
    Mesh c = Synthetic(7);
    const SmoothResult rb = Smooth(b, lean);
    ASSERT_EQ(ra.sweeps.size(), rb.sweeps.size());
    EXPECT_NEAR(rb.sweeps.back().quality, GlobalQuality(b), 1e-12);
    if (threads == 1) {  // with 2, reads across the chunk border race (as in the paper)
      EXPECT_EQ(a.xy, b.xy) << "the same moves in the same order";
      for (size_t i = 0; i < rb.sweeps.size(); ++i)
        EXPECT_NEAR(rb.sweeps[i].quality, ra.sweeps[i].quality, 1e-12) << "sweep " << i + 1;
    }
    // Sweep by sweep against the direct definition, one sweep at a time.
    SmoothOptions one = lean;
    one.max_iters = 1;
    for (int k = 0; k < 3; ++k) {
      const SmoothResult r = Smooth(c, one);
      EXPECT_NEAR(r.sweeps[0].quality, GlobalQuality(c), 1e-13);
    }
    if (threads == 1) {  // with a tolerance, both stop at the same sweep
      Mesh d = Synthetic(7), e = Synthetic(7);
      SmoothOptions tol_move = per_move, tol_lean = lean;
      tol_move.max_iters = tol_lean.max_iters = 100;
      tol_move.tol = tol_lean.tol = 1e-5;
      EXPECT_EQ(Smooth(d, tol_move).sweeps.size(), Smooth(e, tol_lean).sweeps.size());
    }
  }
  EXPECT_EQ(ParseQualityMode("per-sweep"), QualityMode::kPerSweep);
  EXPECT_EQ(ParseQualityMode("per-move"), QualityMode::kPerMove);
  EXPECT_THROW(ParseQualityMode("sometimes"), std::invalid_argument);
}

// Tracing sinks that count the loop-bound reads (ForStatic): one fed serially (in thread shares or
// interleaved), one from the real threads (kParallelTrace).
struct LoopSink {
  static constexpr bool kEnabled = true;
  int interleave = kSerialShares;
  std::atomic<int64_t> bounds{0};
  void Access(int, const MemRef& r) { bounds += r.array == Array::kLoopBound; }
};
struct ParallelLoopSink : LoopSink {
  static constexpr bool kParallelTrace = true;
};

// Every item visited once with its own index and the visits' values summed, in the loop `sink`
// gives; `bounds`: the bound reads it saw (one per item and one per thread's share each run).
template <class Sink>
void CheckIndexedLoop(Sink& sink, int threads, const std::string& what) {
  constexpr int64_t kStride = 3, kN = 101;
  std::vector<int32_t> items(kStride * kN);
  std::vector<int64_t> seen(kN, 0);
  std::atomic<int64_t> wrong{0};
  smoother_detail::ForStatic<kStride>(items.data(), kN, threads, sink, nullptr,
                                      [&](int32_t* p, int64_t i, int) {
                                        if (i < 0 || i >= kN || p != items.data() + kStride * i)
                                          return void(++wrong);
                                        ++seen[i];  // each thread its own items
                                      });
  EXPECT_EQ(wrong.load(), 0) << what;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), kN) << what;
  // A body returning its index sums to 0 + 1 + ... + n-1.
  const double sum = smoother_detail::ForStatic<kStride>(
      items.data(), kN, threads, sink, nullptr,
      [](int32_t*, int64_t i, int) { return static_cast<double>(i); });
  EXPECT_EQ(sum, kN * (kN - 1) / 2) << what;
  if constexpr (Sink::kEnabled) {
    EXPECT_EQ(sink.bounds.load(), 2 * (kN + threads)) << what;
  }
}

// ForStatic gives a body that asks for it the item's index in every form of the loop (untraced
// threads, traced in shares, traced interleaved, traced from the threads), and a body may return
// nothing.
TEST(Smoother, ForStaticGivesTheItemsIndexInEveryLoop) {
  for (int threads : {1, 2, 3}) {
    const std::string at = std::to_string(threads) + " threads";
    NullSink null;
    CheckIndexedLoop(null, threads, at + ", untraced");
    for (int grain : {kSerialShares, 1, 4}) {
      LoopSink traced;
      traced.interleave = grain;
      CheckIndexedLoop(traced, threads, at + ", traced, grain " + std::to_string(grain));
    }
    ParallelLoopSink parallel;
    CheckIndexedLoop(parallel, threads, at + ", traced from the threads");
  }
}

TEST(Smoother, UpdateModeNames) {
  EXPECT_EQ(ParseUpdateMode("gs"), UpdateMode::kGaussSeidel);
  EXPECT_EQ(ParseUpdateMode("gauss-seidel"), UpdateMode::kGaussSeidel);
  EXPECT_EQ(ParseUpdateMode("jacobi"), UpdateMode::kJacobi);
  EXPECT_THROW(ParseUpdateMode("sor"), std::invalid_argument);
}

}  // namespace
}  // namespace meshreuse
