// The kernel registry (core/kernels/): each kernel against a naive reference written here from its
// definition (gapbs-style), the traced and the timed instance agreeing, the documented access
// counts, ordering invariance where it holds, hand-worked untangling, and --kernel's errors.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/kernels/edge_swap.h"
#include "core/kernels/kernel.h"
#include "core/kernels/stiffness.h"
#include "core/kernels/untangle.h"
#include "core/mix.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "core/quality.h"
#include "tests/test_util.h"
#include "tracer/sink.h"

namespace meshreuse {
namespace {

using testing::MeshCorpus;
using testing::Synthetic;

std::vector<Mesh> Meshes() {
  std::vector<Mesh> m;
  m.push_back(testing::TwoInterior());
  m.push_back(Synthetic(12, 9, 1, 3));
  m.push_back(Synthetic(20, 14, 2, 7));
  m.push_back(ReadMesh(testing::DataPath("plate41.msh")));
  return m;
}

const KernelInfo& K(const char* name) { return ParseKernel(name); }

// Two runs of kernel `name` that must be the same: each sweep's measure, and the meshes after.
void ExpectSameSweeps(const SmoothResult& a, const Mesh& ma, const SmoothResult& b, const Mesh& mb,
                      const char* name) {
  ASSERT_EQ(a.sweeps.size(), b.sweeps.size()) << name;
  for (size_t i = 0; i < a.sweeps.size(); ++i)
    EXPECT_EQ(a.sweeps[i].quality, b.sweeps[i].quality) << name << " sweep " << i;
  EXPECT_EQ(ma.xy, mb.xy) << name;
  EXPECT_EQ(ma.tri, mb.tri) << name;
}

TEST(KernelRegistry, FindsEveryKernelAndNamesTheKnownOnesForAnUnknownOne) {
  for (const char* n :
       {"laplacian", "smart-laplacian", "local-opt", "untangle", "assembly", "spmv"})
    ASSERT_NE(FindKernel(n), nullptr) << n;
  try {
    ParseKernel("lapalcian");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_TRUE(testing::HasText(e.what(), "unknown kernel 'lapalcian'"));
    EXPECT_TRUE(testing::HasText(e.what(), "smart-laplacian"));
  }
  SmoothOptions o;
  o.mode = UpdateMode::kJacobi;
  EXPECT_THROW(CheckKernelOptions(K("smart-laplacian"), o), UsageError);
  EXPECT_NO_THROW(CheckKernelOptions(K("laplacian"), o));
  SmoothOptions t;
  t.threads = 2;
  EXPECT_THROW(CheckKernelOptions(K("assembly"), t), UsageError);
  EXPECT_NO_THROW(CheckKernelOptions(K("spmv"), t));
}

// The traced instance (through a KernelSink) computes what the timed one does, bit for bit, on
// one thread; and the counting run gives the closed form where a kernel has one.
TEST(Kernels, TracedAndTimedAgreeAndCountsMatchTheDocumentedSequence) {
  for (const KernelInfo& k : Kernels()) {
    for (const Mesh& base : Meshes()) {
      const SmoothOptions o = ExactSweeps(3);
      Mesh a = base.Clone(), b = base.Clone();
      const SmoothResult ra = RunKernel(k, a, o);
      CountingSink count;
      KernelSinkOf<CountingSink> sink(count);
      const SmoothResult rb = RunKernel(k, b, o, sink);
      EXPECT_EQ(a.xy, b.xy) << k.name;
      EXPECT_EQ(a.tri, b.tri) << k.name;
      ASSERT_EQ(ra.sweeps.size(), rb.sweeps.size()) << k.name;
      for (size_t s = 0; s < ra.sweeps.size(); ++s)
        EXPECT_EQ(ra.sweeps[s].quality, rb.sweeps[s].quality) << k.name << " sweep " << s;
      EXPECT_GT(count.Refs(), 0u) << k.name;
      // The untraced run reads each sweep's thread CPU time (compare's clock) around all its work.
      for (const SweepRecord& rec : ra.sweeps) EXPECT_GT(rec.cpu_seconds, 0.0) << k.name;
      const std::vector<uint64_t> refs = k.refs(base, o);
      if (!refs.empty()) {
        EXPECT_EQ(count.Refs(), refs[0] * rb.sweeps.size()) << k.name;
      }
    }
  }
}

TEST(Kernels, EveryKernelCallsOnSweepAfterEachSweepWithItsRecord) {
  const Mesh base = ReadMesh(testing::DataPath("plate41.msh"));
  for (const KernelInfo& k : Kernels()) {
    std::vector<SweepRecord> seen;
    const std::function<void(const SweepRecord&)> each = [&](const SweepRecord& r) {
      seen.push_back(r);
    };
    SmoothOptions o = ExactSweeps(3);
    o.on_sweep = &each;
    Mesh m = base.Clone();
    const SmoothResult r = RunKernel(k, m, o);
    ASSERT_EQ(seen.size(), r.sweeps.size()) << k.name;
    for (size_t s = 0; s < seen.size(); ++s) {
      EXPECT_EQ(seen[s].sweep, r.sweeps[s].sweep) << k.name;
      EXPECT_EQ(seen[s].quality, r.sweeps[s].quality) << k.name;
      EXPECT_EQ(seen[s].seconds, r.sweeps[s].seconds) << k.name;
    }
  }
}

TEST(Kernels, LaplacianThroughTheRegistryIsTheSmootherBitForBit) {
  for (const Mesh& base : Meshes()) {
    Mesh a = base.Clone(), b = base.Clone();
    SmoothOptions o;
    const SmoothResult ra = Smooth(a, o);
    const SmoothResult rb = RunKernel(K("laplacian"), b, o);
    EXPECT_EQ(a.xy, b.xy);
    EXPECT_EQ(ra.sweeps.size(), rb.sweeps.size());
    EXPECT_EQ(ra.quality_after, rb.quality_after);
  }
}

// Per-thread counts with the static split (spmv's rows), against the closed form.
TEST(Kernels, SpmvCountsPerThreadAreTheClosedForms) {
  const Mesh base = Synthetic(20, 14, 2, 7);
  for (int threads : {1, 2, 3, 7}) {
    Mesh m = base.Clone();
    const SmoothOptions o = ExactSweeps(1, threads);
    CountingSink count;
    KernelSinkOf<CountingSink> sink(count);
    RunKernel(K("spmv"), m, o, sink);
    const std::vector<uint64_t> want = K("spmv").refs(base, o);
    ASSERT_EQ(count.per_thread.size(), want.size());
    for (int t = 0; t < threads; ++t) {
      uint64_t got = 0;
      for (const auto& a : count.per_thread[t].array) got += a[0] + a[1];
      EXPECT_EQ(got, want[t]) << threads << " threads, thread " << t;
    }
  }
}

// smart-laplacian, as its definition reads: per interior vertex in storage order, the neighbours'
// average; kept when the least quality of its triangles does not drop.
void NaiveSmart(Mesh& m, int sweeps) {
  for (int s = 0; s < sweeps; ++s) {
    for (int32_t v : m.interior) {
      double sx = 0, sy = 0;
      for (const int32_t* u = m.v2v.RowBegin(v); u != m.v2v.RowEnd(v); ++u)
        sx += m.xy[2 * *u], sy += m.xy[2 * *u + 1];
      const double inv = 1.0 / static_cast<double>(m.v2v.RowSize(v));
      const double x = sx * inv, y = sy * inv;
      double old_min = 1, new_min = 1;
      for (const int32_t* t = m.v2t.RowBegin(v); t != m.v2t.RowEnd(v); ++t) {
        const int32_t* c = &m.tri[3 * *t];
        old_min = std::min(old_min, TriangleQuality(m.xy.data(), c));
        double p[6];
        for (int j = 0; j < 3; ++j) {
          p[2 * j] = c[j] == v ? x : m.xy[2 * c[j]];
          p[2 * j + 1] = c[j] == v ? y : m.xy[2 * c[j] + 1];
        }
        new_min = std::min(new_min, TriangleQuality(p[0], p[1], p[2], p[3], p[4], p[5]));
      }
      if (new_min >= old_min) m.xy[2 * v] = x, m.xy[2 * v + 1] = y;
    }
  }
}

TEST(Kernels, SmartLaplacianIsItsDefinitionAndNeverLowersAVertexsLeastQuality) {
  for (const Mesh& base : Meshes()) {
    Mesh a = base.Clone(), b = base.Clone();
    const SmoothResult r = RunKernel(K("smart-laplacian"), a, ExactSweeps(4));
    NaiveSmart(b, 4);
    EXPECT_EQ(a.xy, b.xy);  // the same arithmetic in the same order
    EXPECT_NEAR(r.sweeps.back().quality, GlobalQuality(a), 1e-12);
    EXPECT_GE(r.quality_after, r.quality_before - 1e-12);
    // The least triangle quality of the mesh does not drop.
    auto least = [](const Mesh& m) {
      double q = 1;
      for (double x : TriangleQualities(m)) q = std::min(q, x);
      return q;
    };
    EXPECT_GE(least(a), least(base));
  }
}

TEST(Kernels, LocalOptImprovesQualityAndTurnsNoTriangleOver) {
  for (const Mesh& base : Meshes()) {
    Mesh a = base.Clone();
    SmoothOptions o;
    o.max_iters = 20;
    const SmoothResult r = RunKernel(K("local-opt"), a, o);
    EXPECT_EQ(CountInverted(a, 1.0), CountInverted(base, 1.0));
    EXPECT_NEAR(r.sweeps.back().quality, GlobalQuality(a), 1e-12);
    if (!base.interior.empty()) {
      EXPECT_GT(r.quality_after, r.quality_before);
    }
  }
}

// A unit square around a centre vertex (4 triangles, counter-clockwise): the centre moved out
// past the right edge turns two triangles over; one untangle sweep brings it back inside.
Mesh Star(double cx, double cy) {
  RawMesh raw;
  raw.xy = {0, 0, 1, 0, 1, 1, 0, 1, 0.5, 0.5};
  raw.tri = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  Mesh m = BuildMesh(std::move(raw));
  m.xy[8] = cx, m.xy[9] = cy;
  return m;
}

TEST(Kernels, TangleMovesTheChosenVerticesPastANeighbourWhateverTheNumbering) {
  // share 1: every interior vertex moves; the star's centre goes 1.5 times the way to (0, 0).
  Mesh s = Star(0.5, 0.5);
  const TangleStats st = TangleMesh(s, 1.0, 1);
  EXPECT_EQ(st.moved, 1);
  EXPECT_EQ(s.xy[8], 0.5 + 1.5 * (0.0 - 0.5));
  EXPECT_EQ(st.inverted, 2);  // the two triangles on the edge to (0, 0)
  // The same tangle in every ordering: the moved positions are the same set.
  const Mesh base = Synthetic(20, 14, 2, 7);
  auto positions = [](const Mesh& m) {
    std::vector<std::pair<double, double>> p;
    for (int32_t v = 0; v < m.NumVertices(); ++v) p.emplace_back(m.xy[2 * v], m.xy[2 * v + 1]);
    std::sort(p.begin(), p.end());
    return p;
  };
  Mesh ori = base.Clone();
  const TangleStats a = TangleMesh(ori, kTangleShare, kTangleSeed);
  for (const char* ord : {"rdr", "bfs", "random"}) {
    Mesh m = ApplyPermutation(base, ComputeOrdering(ord, base, 5));
    const TangleStats b = TangleMesh(m, kTangleShare, kTangleSeed);
    EXPECT_EQ(a.moved, b.moved) << ord;
    EXPECT_EQ(a.inverted, b.inverted) << ord;
    EXPECT_EQ(positions(ori), positions(m)) << ord;
  }
  EXPECT_GT(a.inverted, 0);
}

TEST(Kernels, UntangleLeavesNoTriangleTurnedOver) {
  // The hand-worked star: the centre out past the right edge turns (1, 0), (1, 1), centre over.
  Mesh s = Star(1.4, 0.5);
  EXPECT_EQ(CountInverted(s, 1.0), 1);
  for (const Mesh& base : Meshes()) {
    Mesh m = base.Clone();
    SmoothOptions o;
    o.max_iters = 50;
    const SmoothResult r = RunKernel(K("untangle"), m, o);
    EXPECT_EQ(CountInverted(m, 1.0), 0)
        << m.NumVertices() << " vertices, " << r.sweeps.size() << " sweeps";
    EXPECT_EQ(r.quality_after, 1.0);
    EXPECT_EQ(r.quality_after, r.sweeps.back().quality);  // the incremental count is the count
    EXPECT_EQ(r.sweeps.back().quality, 1.0);
    if (base.NumVertices() > 100) {
      EXPECT_LT(r.quality_before, 1.0);  // it was tangled
    }
  }
}

// The kite A(0,0) B(4,0) C(2,1) D(2,-1) split along AB: D lies inside the circumcircle of ABC
// (centre (2,-1.5), radius 2.5), so one flip makes CD the diagonal: t = (C, A, D), u = (C, D, B).
TEST(Kernels, EdgeSwapFlipsTheKitesLongDiagonal) {
  RawMesh raw;
  raw.xy = {0, 0, 4, 0, 2, 1, 2, -1};
  raw.tri = {0, 1, 2, 1, 0, 3};
  Mesh m = BuildMesh(std::move(raw));
  EXPECT_FALSE(IsDelaunay(m));
  const SmoothResult r = RunKernel(K("edge-swap"), m, ExactSweeps(10));
  EXPECT_EQ(m.tri, (AlignedVector<int32_t>{2, 0, 3, 2, 3, 1}));
  ASSERT_EQ(r.sweeps.size(), 2u);             // one flip, then a sweep that flips nothing
  EXPECT_EQ(r.sweeps[0].quality, 1.0 - 1.0);  // the one interior edge flipped
  EXPECT_EQ(r.sweeps[1].quality, 1.0);
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(IsDelaunay(m));
}

// JitterMesh (in parallel, by v2t) against the rule written serially over the triangles: each
// interior vertex moved by kJitterAmount times its least altitude over its triangles, at an angle
// from its coordinates' bits; the boundary kept. Bit for bit, on one thread and on several.
TEST(Kernels, JitterMovesEachInteriorVertexByItsLeastAltitude) {
  for (const Mesh& base : Meshes()) {
    std::vector<double> least(static_cast<size_t>(base.NumVertices()), INFINITY);
    for (int32_t t = 0; t < base.NumTriangles(); ++t) {
      const int32_t* c = &base.tri[3 * t];
      const double *a = &base.xy[2 * c[0]], *b = &base.xy[2 * c[1]], *d = &base.xy[2 * c[2]];
      const double area = std::fabs((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
      const double e =
          std::max({std::hypot(b[0] - a[0], b[1] - a[1]), std::hypot(d[0] - b[0], d[1] - b[1]),
                    std::hypot(a[0] - d[0], a[1] - d[1])});
      for (int j = 0; j < 3; ++j) least[c[j]] = std::min(least[c[j]], e > 0 ? area / e : 0.0);
    }
    AlignedVector<double> want = base.xy;
    for (int32_t v : base.interior) {
      uint64_t bx, by;
      std::memcpy(&bx, &base.xy[2 * v], 8);
      std::memcpy(&by, &base.xy[2 * v + 1], 8);
      const double angle =
          static_cast<double>(Mix64(kJitterSeed ^ bx ^ Mix64(by)) >> 11) * 0x1p-53 * 2 * M_PI;
      want[2 * v] += kJitterAmount * least[v] * std::cos(angle);
      want[2 * v + 1] += kJitterAmount * least[v] * std::sin(angle);
    }
    const int before = omp_get_max_threads();
    for (int threads : {1, 3}) {
      Mesh m = base.Clone();
      omp_set_num_threads(threads);
      EXPECT_EQ(JitterMesh(m, kJitterAmount, kJitterSeed),
                static_cast<int64_t>(base.interior.size()));
      omp_set_num_threads(before);
      EXPECT_EQ(m.xy, want) << threads << " thread(s)";
      EXPECT_NE(m.xy, base.xy);
    }
  }
}

// The measure before and after, from the kernel's own neighbour array (kept up to date by the
// flips), is the naive count on the jittered input and on the mesh returned, also when the sweeps
// stop before every edge is Delaunay.
TEST(Kernels, EdgeSwapsMeasureIsTheNaiveCountBeforeAndAfter) {
  int stopped_early = 0;
  for (const Mesh& base : Meshes())
    for (int sweeps : {1, 2, 100}) {
      Mesh jittered = base.Clone();
      JitterMesh(jittered, kJitterAmount, kJitterSeed);
      Mesh m = base.Clone();
      const SmoothResult r = RunKernel(K("edge-swap"), m, ExactSweeps(sweeps));
      std::map<std::pair<int32_t, int32_t>, int> on_edge;  // triangles on each edge
      for (int32_t t = 0; t < m.NumTriangles(); ++t)
        for (int j = 0; j < 3; ++j) {
          const int32_t a = m.tri[3 * t + j], b = m.tri[3 * t + (j + 1) % 3];
          ++on_edge[{std::min(a, b), std::max(a, b)}];
        }
      double interior = 0;
      for (const auto& e : on_edge) interior += e.second == 2;
      EXPECT_EQ(r.quality_before, 1.0 - NotDelaunayEdges(jittered) / (2 * interior)) << sweeps;
      EXPECT_EQ(r.quality_after, 1.0 - NotDelaunayEdges(m) / (2 * interior)) << sweeps;
      stopped_early += r.quality_after < 1.0;
    }
  EXPECT_GT(stopped_early, 0);  // some runs ended with edges left to flip
}

// On every mesh the flips end Delaunay with no triangle turned over, and (the points in general
// position after the jitter) at the one Delaunay triangulation, whatever the numbering.
TEST(Kernels, EdgeSwapEndsAtTheDelaunayTriangulationInEveryOrdering) {
  auto triangles = [](const Mesh& m) {
    std::vector<std::vector<std::pair<double, double>>> t;
    for (int32_t i = 0; i < m.NumTriangles(); ++i) {
      std::vector<std::pair<double, double>> c;
      for (int j = 0; j < 3; ++j)
        c.emplace_back(m.xy[2 * m.tri[3 * i + j]], m.xy[2 * m.tri[3 * i + j] + 1]);
      std::sort(c.begin(), c.end());
      t.push_back(c);
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  for (const Mesh& base : Meshes()) {
    Mesh m = base.Clone();
    SmoothOptions o;
    const SmoothResult r = RunKernel(K("edge-swap"), m, o);
    EXPECT_TRUE(r.converged);
    EXPECT_TRUE(IsDelaunay(m));
    EXPECT_EQ(r.quality_after, 1.0);
    EXPECT_EQ(CountInverted(m, 1.0), CountInverted(base, 1.0));
    EXPECT_EQ(m.NumTriangles(), base.NumTriangles());
  }
  const Mesh base = Synthetic(20, 14, 2, 7);
  Mesh ori = base.Clone();
  const SmoothResult r = RunKernel(K("edge-swap"), ori, SmoothOptions{});
  EXPECT_GT(r.sweeps[0].quality, 0.0);
  EXPECT_LT(r.sweeps[0].quality, 1.0);  // the jitter left edges to flip
  for (const char* ord : {"bfs", "rdr", "random"}) {
    Mesh m = ApplyPermutation(base, ComputeOrdering(ord, base, 5));
    RunKernel(K("edge-swap"), m, SmoothOptions{});
    EXPECT_EQ(triangles(m), triangles(ori)) << ord;
  }
}

// Without the adjacency after (a timed runner's SmoothOptions::adjacency_after = false): the same
// result, triangles and coordinates; the rebuilt adjacency is a fresh BuildMesh of the new
// triangles, the skipped one is the input's.
TEST(Kernels, EdgeSwapWithoutTheAdjacencyAfterIsTheSameRun) {
  int flipped = 0;
  for (const Mesh& base : Meshes()) {
    Mesh with = base.Clone(), without = base.Clone();
    SmoothOptions o = ExactSweeps(3);
    const SmoothResult a = RunKernel(K("edge-swap"), with, o);
    o.adjacency_after = false;
    const SmoothResult b = RunKernel(K("edge-swap"), without, o);
    ExpectSameSweeps(a, with, b, without, "edge-swap");
    EXPECT_EQ(a.quality_before, b.quality_before);
    EXPECT_EQ(a.quality_after, b.quality_after);
    RawMesh raw;
    raw.xy = with.xy, raw.tri = with.tri;
    const Mesh fresh = BuildMesh(std::move(raw));
    EXPECT_EQ(with.v2t.idx, fresh.v2t.idx);
    EXPECT_EQ(with.v2v.idx, fresh.v2v.idx);
    EXPECT_EQ(without.v2t.idx, base.v2t.idx);
    flipped += with.tri != base.tri;
  }
  EXPECT_GT(flipped, 0);
}

// A kernel's set-up made once (PrepareKernel) and handed to several runs on the same mesh: each run
// the same as one that makes its own, bit for bit (its sweeps' measures, both end qualities, the
// mesh after), timed and traced (the same accesses); the set-up itself unchanged by the runs. The
// kernels that share one (edge-swap, assembly, spmv) have one; a set-up of another kernel, or made
// from a mesh of other sizes, is refused.
TEST(Kernels, ASharedSetUpGivesTheSameRunsAsTheirOwn) {
  const std::vector<Mesh> meshes = Meshes();
  std::vector<std::string> with_setup;
  for (const KernelInfo& k : Kernels())
    for (const Mesh& base : meshes) {
      const std::unique_ptr<KernelSetup> setup = PrepareKernel(k, base);
      if (!setup) continue;
      if (&base == &meshes[0]) with_setup.push_back(k.name);
      Mesh own = base.Clone(), own_traced = base.Clone();
      const SmoothResult a = RunKernel(k, own, ExactSweeps(3));
      CountingSink count_own;
      KernelSinkOf<CountingSink> sink_own(count_own);
      RunKernel(k, own_traced, ExactSweeps(3), sink_own);
      SmoothOptions o = ExactSweeps(3);
      o.setup = setup.get();
      for (int run = 0; run < 2; ++run) {  // the second run: the set-up as the first left it
        Mesh shared = base.Clone(), traced = base.Clone();
        const SmoothResult b = RunKernel(k, shared, o);
        ExpectSameSweeps(a, own, b, shared, k.name);
        EXPECT_EQ(a.quality_before, b.quality_before) << k.name;
        EXPECT_EQ(a.quality_after, b.quality_after) << k.name;
        CountingSink count;
        KernelSinkOf<CountingSink> sink(count);
        RunKernel(k, traced, o, sink);
        EXPECT_EQ(count.Refs(), count_own.Refs()) << k.name;
        EXPECT_EQ(traced.xy, own_traced.xy) << k.name;
      }
      Mesh other = meshes[&base == &meshes[1] ? 2 : 1].Clone();
      EXPECT_THROW(RunKernel(k, other, o), std::logic_error) << k.name;
    }
  EXPECT_EQ(with_setup, (std::vector<std::string>{"edge-swap", "assembly", "spmv"}));
  // One kernel's set-up handed to another that has one.
  Mesh m = meshes[1].Clone();
  const std::unique_ptr<KernelSetup> swap = PrepareKernel(K("edge-swap"), m);
  SmoothOptions o = ExactSweeps(1);
  o.setup = swap.get();
  EXPECT_THROW(RunKernel(K("spmv"), m, o), std::logic_error);
}

// Without the end qualities (a pass over the mesh each, which timed and traced runners do not
// read): every kernel's sweeps, their qualities and the mesh the same; the passes' values NaN
// (untangle's starting share kept: its sweeps start from it), values a kernel takes from its
// sweeps the same; with them, the smoothing kernels' are the global quality of the mesh before and
// after. Traced too: the same access count.
TEST(Kernels, WithoutTheEndQualitiesTheSameRun) {
  const std::vector<Mesh> meshes = Meshes();
  const Mesh& base = meshes[0];
  for (const KernelInfo& k : Kernels()) {
    Mesh with = base.Clone(), without = base.Clone(), traced = base.Clone(),
         traced_with = base.Clone();
    SmoothOptions o = ExactSweeps(3);
    const SmoothResult a = RunKernel(k, with, o);
    CountingSink count_with;
    KernelSinkOf<CountingSink> sink_with(count_with);
    RunKernel(k, traced_with, o, sink_with);
    o.end_qualities = false;
    const SmoothResult b = RunKernel(k, without, o);
    CountingSink count;
    KernelSinkOf<CountingSink> sink(count);
    RunKernel(k, traced, o, sink);
    EXPECT_EQ(count.Refs(), count_with.Refs()) << k.name;  // the passes are not traced
    ExpectSameSweeps(a, with, b, without, k.name);
    EXPECT_EQ(traced.xy, without.xy) << k.name;
    const std::vector<uint64_t> refs = k.refs(base, o);
    if (!refs.empty()) {
      EXPECT_EQ(count.Refs(), refs[0] * b.sweeps.size()) << k.name;
    }
    const std::string n = k.name;
    const bool passes = n == "laplacian" || n == "smart-laplacian" || n == "local-opt" ||
                        n == "edge-swap" || n == "untangle";
    if (passes) {
      EXPECT_TRUE(std::isnan(b.quality_after)) << n;
      if (n == "untangle")
        EXPECT_EQ(a.quality_before, b.quality_before);
      else
        EXPECT_TRUE(std::isnan(b.quality_before)) << n;
    } else {
      EXPECT_EQ(a.quality_before, b.quality_before) << n;
      EXPECT_EQ(a.quality_after, b.quality_after) << n;
    }
    if (n == "laplacian" || n == "smart-laplacian" || n == "local-opt") {
      EXPECT_EQ(a.quality_before, GlobalQuality(base)) << n;
      EXPECT_EQ(a.quality_after, GlobalQuality(with)) << n;
    }
  }
  Mesh m = base.Clone();
  SmoothOptions o = ExactSweeps(2);
  o.end_qualities = false;
  const SmoothResult r = Smooth(m, o);  // the smoother itself
  EXPECT_TRUE(std::isnan(r.quality_before) && std::isnan(r.quality_after));
  EXPECT_EQ(r.sweeps.size(), 2u);
}

// The stiffness matrix as a map (i, j) -> value, from the definition, triangles in storage order.
std::map<std::pair<int32_t, int32_t>, double> NaiveStiffness(const Mesh& m) {
  std::map<std::pair<int32_t, int32_t>, double> a;
  for (int32_t t = 0; t < m.NumTriangles(); ++t) {
    const int32_t* c = &m.tri[3 * t];
    double p[6];
    for (int j = 0; j < 3; ++j) p[2 * j] = m.xy[2 * c[j]], p[2 * j + 1] = m.xy[2 * c[j] + 1];
    double area2 = (p[2] - p[0]) * (p[5] - p[1]) - (p[3] - p[1]) * (p[4] - p[0]);
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) {
        // edges opposite r and s: p[r+2] - p[r+1]
        const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, s1 = (s + 1) % 3, s2 = (s + 2) % 3;
        const double ex = p[2 * r2] - p[2 * r1], ey = p[2 * r2 + 1] - p[2 * r1 + 1];
        const double fx = p[2 * s2] - p[2 * s1], fy = p[2 * s2 + 1] - p[2 * s1 + 1];
        a[{c[r], c[s]}] += (ex * fx + ey * fy) / (2 * std::fabs(area2));
      }
  }
  return a;
}

TEST(Kernels, AssemblyIsTheStiffnessMatrixAndItsRowsSumToZero) {
  for (const Mesh& base : Meshes()) {
    Mesh m = base.Clone();
    StiffnessMatrix a = StiffnessPattern(m);
    NullSink none;
    const double trace = AssembleStiffness(m, a, none);
    const auto want = NaiveStiffness(m);
    ASSERT_EQ(static_cast<size_t>(a.nnz()), want.size());
    double naive_trace = 0;
    for (int32_t i = 0; i < m.NumVertices(); ++i) {
      double row = 0, scale = 0;
      for (int64_t j = a.off[i]; j < a.off[i + 1]; ++j) {
        const auto it = want.find({i, a.col[j]});
        ASSERT_NE(it, want.end());
        EXPECT_NEAR(a.val[j], it->second, 1e-12 * std::fabs(it->second) + 1e-15);
        row += a.val[j], scale += std::fabs(a.val[j]);
        if (a.col[j] == i) naive_trace += a.val[j];
      }
      EXPECT_NEAR(row, 0.0, 1e-12 * scale);
    }
    EXPECT_NEAR(trace, naive_trace, 1e-10 * naive_trace);
    // A second sweep starts from zero: the same values.
    const AlignedVector<double> first = a.val;
    AssembleStiffness(m, a, none);
    EXPECT_EQ(first, a.val);
  }
}

TEST(Kernels, SpmvIsTheMatrixTimesTheCoordinatesAndItsEnergyIsTheArea) {
  for (const Mesh& base : Meshes()) {
    Mesh m = base.Clone();
    const SmoothResult r = RunKernel(K("spmv"), m, ExactSweeps(2));
    const auto a = NaiveStiffness(m);
    double energy = 0, area = 0;
    for (int32_t t = 0; t < m.NumTriangles(); ++t) {
      const int32_t* c = &m.tri[3 * t];
      const double* p = &m.xy[2 * c[0]];
      const double* q = &m.xy[2 * c[1]];
      const double* s = &m.xy[2 * c[2]];
      area += 0.5 * std::fabs((q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0]));
    }
    for (const auto& [ij, v] : a) energy += m.xy[2 * ij.first] * v * m.xy[2 * ij.second];
    EXPECT_NEAR(r.sweeps.back().quality, energy, 1e-9 * area);
    EXPECT_NEAR(r.sweeps.back().quality, area, 1e-9 * area);  // the Dirichlet energy of x
  }
}

// Ordering invariance: the FEM kernels' measures are the same in every ordering (up to the
// rounding of a sum taken in another order); the smoothers' are not (Gauss-Seidel).
TEST(Kernels, AssemblyAndSpmvMeasuresDoNotDependOnTheOrdering) {
  const Mesh base = Synthetic(20, 14, 2, 7);
  for (const char* k : {"assembly", "spmv"}) {
    Mesh ori = base.Clone();
    const double want = RunKernel(K(k), ori, ExactSweeps(1)).sweeps[0].quality;
    for (const char* ord : {"bfs", "rdr", "random", "hilbert"}) {
      Mesh m = ApplyPermutation(base, ComputeOrdering(ord, base, 3));
      EXPECT_NEAR(RunKernel(K(k), m, ExactSweeps(1)).sweeps[0].quality, want, 1e-12 * want)
          << k << " " << ord;
    }
  }
}

// The first row of spmv's stream on the two-interior mesh, access by access, as spmv.cc says.
TEST(Kernels, SpmvStreamIsTheDocumentedSequence) {
  Mesh m = testing::TwoInterior();
  RecordingSink rec;
  KernelSinkOf<RecordingSink> sink(rec);
  RunKernel(K("spmv"), m, ExactSweeps(1), sink);
  const int64_t nnz0 = m.v2v.RowSize(0) + 1;
  std::vector<Array> want = {Array::kLoopBound, Array::kMatOffsets, Array::kMatOffsets};
  for (int64_t j = 0; j < nnz0; ++j)
    for (Array a : {Array::kMatColumns, Array::kMatValues, Array::kVectorIn}) want.push_back(a);
  want.push_back(Array::kVectorOut);
  want.push_back(Array::kVectorIn);
  want.push_back(Array::kLoopBound);  // row 1 begins
  ASSERT_GE(rec.refs.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i)
    EXPECT_EQ(rec.refs[i].ref.array, want[i]) << "access " << i;
  EXPECT_TRUE(rec.refs[want.size() - 3].ref.write);  // y[0]
  EXPECT_EQ(rec.refs[want.size() - 3].ref.vertex, 0);
}

}  // namespace
}  // namespace meshreuse
