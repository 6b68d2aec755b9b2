// The access sequence of a sweep on the tiny mesh (spelled out), accesses per sweep, the static
// split against OpenMP's own, and the binary trace: round trip, and rejection of a wrong magic, an
// unknown version and a truncated file.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "analysis/trace_analysis.h"
#include "core/error.h"
#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"
#include "tracer/trace_reader.h"
#include "tracer/trace_writer.h"

namespace meshreuse {
namespace {

namespace fs = std::filesystem;
using K = AccessKind;

SmoothOptions OneSweep(int threads = 1) {
  SmoothOptions o;
  o.max_iters = 1;
  o.threads = threads;
  return o;
}

TEST(AccessSequence, OneGaussSeidelSweepOnTheTinyMesh) {
  Mesh m = testing::TwoInterior();
  RecordingSink sink;
  Smooth(m, OneSweep(2), sink);
  const double* xy = m.xy.data();
  auto adj = [&](int v) { return static_cast<const void*>(m.v2v.off.data() + v); };
  auto at = [&](int v) { return static_cast<const void*>(xy + 2 * v); };
  std::vector<RecordingSink::Touched> expect;
  auto visit = [&](int thread, int v, std::vector<int> nbrs, std::vector<std::vector<int>> tris) {
    expect.push_back({thread, K::kAdjacency, v, adj(v)});
    for (int u : nbrs) expect.push_back({thread, K::kCoordRead, u, at(u)});
    expect.push_back({thread, K::kCoordWrite, v, at(v)});
    for (const auto& t : tris)
      for (int c : t) expect.push_back({thread, K::kCoordRead, c, at(c)});
  };
  // Vertex 6 (thread 0 of 2): neighbours 0 1 4 5 7; triangles 0..4 = (0 1 6) (1 7 6) (6 7 4)
  // (6 4 5) (6 5 0). Vertex 7 (thread 1): neighbours 1 2 3 4 6; triangles 1 2 5 6 7 = (1 7 6)
  // (6 7 4) (1 2 7) (2 3 7) (7 3 4).
  visit(0, 6, {0, 1, 4, 5, 7}, {{0, 1, 6}, {1, 7, 6}, {6, 7, 4}, {6, 4, 5}, {6, 5, 0}});
  visit(1, 7, {1, 2, 3, 4, 6}, {{1, 7, 6}, {6, 7, 4}, {1, 2, 7}, {2, 3, 7}, {7, 3, 4}});
  ASSERT_EQ(sink.touches.size(), expect.size());
  for (size_t i = 0; i < expect.size(); ++i) EXPECT_EQ(sink.touches[i], expect[i]) << "touch " << i;
  EXPECT_EQ(sink.sweep_starts, (std::vector<size_t>{0}));
  EXPECT_EQ(AccessesPerSweep(m, 2), (std::vector<uint64_t>{22, 22}));
}

TEST(AccessSequence, TracedAndUntracedSmoothingAgree) {
  SyntheticOptions so;
  so.nx = 30, so.ny = 20, so.holes = 2, so.seed = 9;
  Mesh a = BuildMesh(MakeSyntheticMesh(so)), b = BuildMesh(MakeSyntheticMesh(so));
  SmoothOptions o;
  o.max_iters = 5;
  o.tol = -1;
  CountingSink counts;
  Smooth(a, o, counts);
  Smooth(b, o);
  EXPECT_EQ(a.xy, b.xy);  // tracing observes, it does not change the computation
  EXPECT_EQ(counts.sweeps, 5);
  EXPECT_EQ(counts.Total(), 5 * AccessesPerSweep(a)[0]);
}

TEST(AccessSequence, PerSweepCountMatchesACountingSinkForEveryThreadCount) {
  SyntheticOptions so;
  so.nx = 25, so.ny = 17, so.holes = 1, so.seed = 4;
  for (int threads : {1, 2, 3, 7}) {
    Mesh m = BuildMesh(MakeSyntheticMesh(so));
    CountingSink c;
    Smooth(m, OneSweep(threads), c);
    const std::vector<uint64_t> want = AccessesPerSweep(m, threads);
    ASSERT_EQ(c.per_thread.size(), want.size());
    for (int t = 0; t < threads; ++t)
      EXPECT_EQ(c.per_thread[t][0] + c.per_thread[t][1] + c.per_thread[t][2], want[t]);
  }
}

TEST(StaticOwner, MatchesOpenMPStaticSchedule) {
  for (int threads : {1, 2, 3, 4, 7})
    for (int64_t n : {0, 1, 2, 5, 7, 100, 1001}) {
      std::vector<int> owner(n, -1);
#pragma omp parallel for num_threads(threads) schedule(static)
      for (int64_t k = 0; k < n; ++k) owner[k] = omp_get_thread_num();
      int team = 1;
#pragma omp parallel num_threads(threads)
#pragma omp single
      team = omp_get_num_threads();
      if (team != threads) GTEST_SKIP() << "OpenMP gave " << team << " threads, not " << threads;
      for (int64_t k = 0; k < n; ++k)
        ASSERT_EQ(smoother_detail::StaticOwner(k, n, threads), owner[k])
            << "k " << k << " n " << n << " threads " << threads;
    }
}

class TraceFile : public ::testing::Test {
 protected:
  std::string Path(const std::string& n) const { return (dir_ / n).string(); }
  // Traces `sweeps` sweeps of the tiny mesh with 2 threads into PATH; returns the recording.
  RecordingSink Write(const std::string& path, int sweeps) {
    Mesh m = testing::TwoInterior();
    TraceHeader h;
    h.threads = 2;
    h.vertices = 8;
    h.mesh = "two_interior";
    h.ordering = "ori";
    TraceWriter w(path, h, sweeps);
    SmoothOptions o;
    o.max_iters = sweeps;
    o.tol = -1;
    o.threads = 2;
    Smooth(m, o, w);
    w.Close();
    Mesh m2 = testing::TwoInterior();
    RecordingSink r;
    Smooth(m2, o, r);
    return r;
  }
  void ExpectRejected(const std::string& path, const std::string& message) {
    try {
      TraceReader r(path);
      ADD_FAILURE() << "accepted " << path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_NE(e.problem().find(message), std::string::npos) << e.what();
    }
  }
  testing::TempDir tmp_;
  const fs::path& dir_ = tmp_.path();
};

TEST_F(TraceFile, RoundTrip) {
  const RecordingSink rec = Write(Path("t.trace"), 3);
  TraceReader r(Path("t.trace"));
  EXPECT_EQ(r.header().version, kTraceVersion);
  EXPECT_EQ(r.header().threads, 2u);
  EXPECT_EQ(r.header().element_bytes, 66u);
  EXPECT_EQ(r.header().records, 3u * 44);
  EXPECT_EQ(r.header().iteration_starts, (std::vector<uint64_t>{0, 44, 88}));
  EXPECT_EQ(r.header().vertices, 8u);
  // Each of the 3 sweeps: thread 0 visits vertex 6, thread 1 vertex 7, 22 touches each.
  EXPECT_EQ(r.header().sweep_records, (std::vector<std::vector<uint64_t>>(3, {22, 22})));
  EXPECT_EQ(r.header().mesh, "two_interior");
  EXPECT_EQ(r.header().ordering, "ori");
  std::vector<TraceRecord> batch, all;
  while (r.Next(&batch, 10)) all.insert(all.end(), batch.begin(), batch.end());
  ASSERT_EQ(all.size(), rec.touches.size());
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].vertex, static_cast<uint32_t>(rec.touches[i].vertex));
    EXPECT_EQ(all[i].kind, static_cast<uint8_t>(rec.touches[i].kind));
    EXPECT_EQ(all[i].thread, rec.touches[i].thread);
  }
  EXPECT_TRUE(TraceReader::LooksLikeTrace(Path("t.trace")));
  EXPECT_FALSE(fs::exists(Path("t.trace") + ".tmp." + std::to_string(::getpid())));
}

TEST_F(TraceFile, Rejections) {
  Write(Path("good"), 2);
  std::ifstream in(Path("good"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto write = [&](const std::string& name, std::string b) {
    std::ofstream(Path(name), std::ios::binary) << b;
    return Path(name);
  };
  std::string bad = bytes;
  bad[0] = 'X';
  ExpectRejected(write("magic", bad), "not a meshreuse trace (wrong magic");
  bad = bytes;
  bad[8] = 7;
  ExpectRejected(write("version", bad), "unknown trace version 7 (this reader knows version 1)");
  ExpectRejected(write("cut", bytes.substr(0, bytes.size() - 5)),
                 "truncated trace: the header says 88 records (1408 bytes), the file holds 1403");
  ExpectRejected(write("header", bytes.substr(0, 20)), "truncated trace header");
  ExpectRejected(write("empty", ""), "not a meshreuse trace");
  ExpectRejected(Path("missing"), "cannot open");
}

TEST_F(TraceFile, AnalysisFromFileEqualsStreaming) {
  Write(Path("t"), 2);
  TraceAnalysisOptions o;
  o.threads = 2;
  o.dense_elements = 8;
  TraceAnalysis from_file(o), streamed(o);
  TraceReader r(Path("t"));
  std::vector<TraceRecord> batch;
  while (r.Next(&batch))
    for (const TraceRecord& rec : batch) from_file.Add(rec.thread, rec.vertex, rec.address);
  Mesh m = testing::TwoInterior();
  SmoothOptions so;
  so.max_iters = 2;
  so.tol = -1;
  so.threads = 2;
  AnalysisSink sink{&streamed};
  Smooth(m, so, sink);
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(from_file.element(t)->hist.counts(), streamed.element(t)->hist.counts());
    EXPECT_EQ(from_file.line(t)->hist.counts(), streamed.line(t)->hist.counts());
    EXPECT_EQ(from_file.element(t)->hist.accesses(), 44u);
  }
}

TEST(ExternalTrace, TextAndBinary) {
  const fs::path dir = fs::temp_directory_path();
  const std::string text = (dir / ("meshreuse-ext-" + std::to_string(::getpid()))).string();
  std::ofstream(text) << "# a comment\n1\n0x10\n  2  \n\n0X1f # trailing\n";
  std::vector<uint64_t> got;
  ReadExternalTrace(text, ExternalFormat::kText, [&](uint64_t v) { got.push_back(v); });
  EXPECT_EQ(got, (std::vector<uint64_t>{1, 16, 2, 31}));
  std::ofstream(text) << "1\n2\nzz\n";
  try {
    ReadExternalTrace(text, ExternalFormat::kText, [](uint64_t) {});
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.problem().find("'zz'"), std::string::npos);
  }
  const uint32_t u32[3] = {5, 0, 4000000000u};
  std::ofstream(text, std::ios::binary).write(reinterpret_cast<const char*>(u32), sizeof u32);
  got.clear();
  ReadExternalTrace(text, ExternalFormat::kU32, [&](uint64_t v) { got.push_back(v); });
  EXPECT_EQ(got, (std::vector<uint64_t>{5, 0, 4000000000u}));
  EXPECT_EQ(ExternalTraceLength(text, ExternalFormat::kU32), 3u);
  EXPECT_THROW(ReadExternalTrace(text, ExternalFormat::kU64, [](uint64_t) {}),
               InputError);  // 12 bytes
  fs::remove(text);
}

}  // namespace
}  // namespace meshreuse
