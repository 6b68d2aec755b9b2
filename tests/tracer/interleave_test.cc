// The p thread streams of a traced run (SmoothOptions::interleave): generated on one OS thread,
// each thread's stream equals what that thread records when p real OpenMP threads run the traced
// sweep (p = 1..4 here), and every interleaving (thread shares in turn, a visit each, 64 visits
// each, accesses dealt one at a time) keeps each thread's stream and only changes the order
// between threads, which follows the stated rule.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"
#include "tracer/access_stream.h"

namespace meshreuse {
namespace {

Mesh SmallMesh() { return testing::Synthetic(20, 16, 1, 5); }

// One (thread, canonical address, size, direction, kind) per access.
struct Rec {
  int thread;
  uint64_t address;
  uint32_t size;
  bool write;
  uint8_t kind;
  bool operator==(const Rec& o) const {
    return thread == o.thread && address == o.address && size == o.size && write == o.write &&
           kind == o.kind;
  }
};

struct Recorder : AccessConsumer {
  std::vector<Rec> all;
  void Begin(const StreamInfo&) override {}
  void Consume(const Access* a, size_t n) override {
    for (size_t i = 0; i < n; ++i)
      all.push_back({a[i].thread, a[i].address, a[i].size, a[i].write, a[i].kind});
  }
};

std::vector<std::vector<Rec>> PerThread(const std::vector<Rec>& all, int p) {
  std::vector<std::vector<Rec>> out(p);
  for (const Rec& r : all) out[r.thread].push_back(r);
  return out;
}

std::vector<Rec> Traced(int p, int interleave, int sweeps = 2) {
  Mesh m = SmallMesh();
  SmoothOptions o;
  o.max_iters = sweeps, o.tol = -1, o.threads = p, o.interleave = interleave;
  Recorder r;
  StreamMesh(m, o, "m", "ori", r);
  return r.all;
}

// Real threads: the traced sweep in the OpenMP region, each thread appending to its own stream.
struct ParallelRecorder {
  static constexpr bool kEnabled = true;
  static constexpr bool kParallelTrace = true;
  AddressCanonicalizer canon;
  std::vector<std::vector<Rec>> per_thread;
  void Bind(const ArrayLayout& l) { canon = AddressCanonicalizer(l); }
  void BeginSweep(int) {}
  void Access(int thread, const MemRef& r) {
    per_thread[thread].push_back(
        {thread, canon(thread, r), r.size, r.write, static_cast<uint8_t>(r.element)});
  }
};

TEST(Interleave, EachThreadsStreamIsWhatARealThreadRecords) {
  for (int p = 1; p <= 4; ++p) {
    Mesh m = SmallMesh();
    SmoothOptions o;
    o.max_iters = 2, o.tol = -1, o.threads = p;
    ParallelRecorder real;
    real.per_thread.resize(p);
    Smooth(m, o, real);
    const auto serial = PerThread(Traced(p, kSerialShares), p);
    for (int t = 0; t < p; ++t) {
      SCOPED_TRACE("p " + std::to_string(p) + " thread " + std::to_string(t));
      ASSERT_EQ(real.per_thread[t].size(), serial[t].size());
      EXPECT_TRUE(real.per_thread[t] == serial[t]);
    }
  }
}

TEST(Interleave, EveryGrainKeepsEachThreadsStream) {
  for (int p : {1, 2, 3, 8}) {
    const std::vector<Rec> serial = Traced(p, kSerialShares);
    const auto want = PerThread(serial, p);
    for (int grain : {1, 64, kAccessGrain}) {
      SCOPED_TRACE("p " + std::to_string(p) + " grain " + std::to_string(grain));
      const std::vector<Rec> mixed = Traced(p, grain);
      ASSERT_EQ(mixed.size(), serial.size());
      EXPECT_TRUE(PerThread(mixed, p) == want);
      // The order between threads changes, unless a turn holds a whole share.
      const int64_t share = static_cast<int64_t>(SmallMesh().interior.size()) / p;
      if (p > 1 && (grain < 0 || grain < share)) {
        EXPECT_FALSE(mixed == serial);
      }
    }
  }
}

// With a visit per turn, the threads' streams alternate: between two consecutive accesses of one
// thread's visits, every other unfinished thread has a visit; counted by the first access of each
// visit (its interior-list read, array kInterior).
TEST(Interleave, AVisitEachInTurn) {
  const int p = 3;
  Mesh m = SmallMesh();
  SmoothOptions o;
  o.max_iters = 1, o.tol = -1, o.threads = p, o.interleave = 1;
  struct Order : AccessConsumer {
    std::vector<int> visit_threads;
    void Begin(const StreamInfo&) override {}
    void Consume(const Access* a, size_t n) override {
      for (size_t i = 0; i < n; ++i)
        if (a[i].array == static_cast<uint8_t>(Array::kInterior))
          visit_threads.push_back(a[i].thread);
    }
  } order;
  StreamMesh(m, o, "m", "ori", order);
  const int64_t n = static_cast<int64_t>(m.interior.size());
  ASSERT_EQ(static_cast<int64_t>(order.visit_threads.size()), n);
  // While every thread still has visits, they come 0, 1, 2, 0, 1, 2, ...
  int64_t shortest = n;
  for (int t = 0; t < p; ++t) {
    int64_t b, e;
    StaticRange(n, p, t, &b, &e);
    shortest = std::min(shortest, e - b);
  }
  for (int64_t i = 0; i < shortest * p; ++i) EXPECT_EQ(order.visit_threads[i], i % p) << i;
}

}  // namespace
}  // namespace meshreuse
