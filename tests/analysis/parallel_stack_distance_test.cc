// The parallel analyzer (chunk-and-merge, streamed merge) against the serial one, access for
// access: random, scan, uniform and mesh-like traces, dense and hashed ids, 1..6 chunks, traces
// continued over several batches; and TraceAnalysis with workers > 1 against workers = 1 on a
// mesh's streams (histograms, distinct ids and profiles identical).
#include "analysis/parallel_stack_distance.h"

#include <gtest/gtest.h>

#include "analysis/reuse_analysis.h"
#include "analysis/synthetic_trace.h"
#include "core/smoother.h"
#include "core/synthetic.h"

namespace meshreuse {
namespace {

std::vector<uint64_t> Serial(const std::vector<uint64_t>& t) {
  StackDistance sd(1u << 20);
  std::vector<uint64_t> out;
  for (uint64_t id : t) out.push_back(sd.Access(id));
  return out;
}

TEST(ParallelStackDistance, EqualsSerialAccessForAccess) {
  SplitMix64 rng(5);
  std::vector<std::vector<uint64_t>> traces = {CyclicScanTrace(5000, 6),
                                               UniformTrace(3000, 40000, 2),
                                               MeshLikeTrace(8000, 90000, 0.1, 3),
                                               {},
                                               {7},
                                               {1, 1, 1, 2, 1}};
  for (int k = 0; k < 20; ++k) {  // random lengths and alphabets, some chunks without reuse
    const uint64_t alphabet = 1 + rng.Below(k % 2 ? 50 : 5000);
    traces.push_back(UniformTrace(alphabet, rng.Below(20000), 100 + k));
  }
  for (size_t k = 0; k < traces.size(); ++k)
    for (int threads = 1; threads <= 6; ++threads)
      for (bool hashed : {false, true}) {
        std::vector<uint64_t> t = traces[k];
        if (hashed)
          for (uint64_t& id : t) id = id * 0x9E3779B97F4A7C15ull | (uint64_t{1} << 63);
        SCOPED_TRACE("trace " + std::to_string(k) + " threads " + std::to_string(threads) +
                     (hashed ? " hashed" : " dense"));
        std::vector<uint64_t> stack;
        ASSERT_EQ(ParallelStackDistances(t, threads, hashed ? 0 : 1u << 20, &stack), Serial(t));
        StackDistance serial(0);
        for (uint64_t id : t) serial.Access(id);
        EXPECT_EQ(stack, serial.StackBottomUp());
      }
}

TEST(ParallelStackDistance, ContinuesAcrossBatches) {
  // Three batches cut at arbitrary places through one trace, one running stack: the batches'
  // distances, concatenated, equal the whole trace's.
  const std::vector<uint64_t> t = MeshLikeTrace(6000, 120000, 0.05, 9);
  std::vector<uint64_t> running;
  std::vector<uint64_t> got;
  const size_t cuts[] = {0, 17, 70001, t.size()};
  for (int b = 0; b < 3; ++b) {
    const std::vector<uint64_t> part(t.begin() + cuts[b], t.begin() + cuts[b + 1]);
    const std::vector<uint64_t> d = ParallelStackDistances(part, 3, 1u << 20, &running);
    got.insert(got.end(), d.begin(), d.end());
  }
  EXPECT_EQ(got, Serial(t));
  // The running stack is the serial analyzer's stack.
  StackDistance serial(1u << 20);
  for (uint64_t id : t) serial.Access(id);
  EXPECT_EQ(running, serial.StackBottomUp());
  EXPECT_EQ(running.size(), serial.distinct());
}

void ExpectSameStreams(const ReuseAnalysis& a, const ReuseAnalysis& b) {
  ASSERT_EQ(a.threads(), b.threads());
  for (int t = 0; t < a.threads(); ++t)
    for (int g = 0; g < 2; ++g) {
      const StreamAnalysis* x = g ? a.line(t) : a.element(t);
      const StreamAnalysis* y = g ? b.line(t) : b.element(t);
      ASSERT_EQ(!x, !y);
      if (!x) continue;
      SCOPED_TRACE("stream " + std::to_string(t) + (g ? " line" : " element"));
      EXPECT_EQ(x->hist.Pairs(), y->hist.Pairs());
      EXPECT_EQ(x->hist.cold(), y->hist.cold());
      EXPECT_EQ(x->hist.finite(), y->hist.finite());
      EXPECT_EQ(x->hist.mean(), y->hist.mean());
      EXPECT_EQ(x->distinct(), y->distinct());
      ASSERT_EQ(x->profile.steps().size(), y->profile.steps().size());
      for (size_t s = 0; s < x->profile.steps().size(); ++s) {
        EXPECT_EQ(x->profile.steps()[s].accesses, y->profile.steps()[s].accesses) << s;
        EXPECT_EQ(x->profile.steps()[s].cold, y->profile.steps()[s].cold) << s;
        EXPECT_TRUE(x->profile.steps()[s].sum == y->profile.steps()[s].sum) << s;
      }
    }
}

TEST(ParallelStackDistance, TraceAnalysisWithWorkersEqualsSerial) {
  for (int threads : {1, 2}) {
    SyntheticOptions so0;
    so0.nx = 40, so0.ny = 30, so0.holes = 1, so0.seed = 4;
    const Mesh base = BuildMesh(MakeSyntheticMesh(so0));
    auto run = [&](int workers, size_t batch) {
      Mesh m = base.Clone();
      SmoothOptions so;
      so.max_iters = 3;
      so.tol = -1;
      so.threads = threads;
      ReuseOptions o;  // profiles from the stream's sweep lengths
      o.workers = workers;
      o.batch_per_worker = batch;
      if (batch < 10000) o.batch_per_distinct = 0;  // fixed small batches: many per stream
      auto a = std::make_unique<ReuseAnalysis>(o);
      StreamMesh(m, so, "mesh", "ori", *a);
      EXPECT_TRUE(a->element(0)->profile.enabled());
      return a;
    };
    const auto serial = run(1, 1);
    for (int workers : {2, 3, 5})
      for (size_t batch : {size_t{5000}, size_t{1} << 20}) {
        SCOPED_TRACE("smoother threads " + std::to_string(threads) + " workers " +
                     std::to_string(workers) + " batch " + std::to_string(batch));
        ExpectSameStreams(*run(workers, batch), *serial);
      }
  }
}

TEST(ParallelStackDistance, ResultsBeforeEndAreRefused) {
  ReuseOptions o;
  o.workers = 2;
  ReuseAnalysis a(o);
  a.Begin(StreamInfo());
  a.AddElement(0, 3);
  EXPECT_THROW(a.element(0), std::logic_error);
  a.End();
  EXPECT_EQ(a.element(0)->hist.cold(), 1u);
}

}  // namespace
}  // namespace meshreuse
