// The access sequence of a sweep on the tiny mesh (element stream and address stream spelled out),
// per-array access counts against closed forms on every test mesh, the static split against
// OpenMP's own, a kernel's stream without its counts (the same stream), and the binary trace: round
// trip, version-1 files, and rejection of a wrong magic, an unknown version and a truncated file.
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "analysis/reuse_analysis.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/test_util.h"
#include "tracer/access_stream.h"
#include "tracer/foreign_trace.h"
#include "tracer/sink.h"
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

// The address stream of the same sweep, every load and store with its array, size and direction.
TEST(AccessSequence, AddressStreamOfOneGaussSeidelSweepOnTheTinyMesh) {
  Mesh m = testing::TwoInterior();
  RecordingSink sink;
  Smooth(m, OneSweep(2), sink);
  struct Want {
    int thread;
    Array array;
    const void* address;
    uint32_t size;
    bool write;
    AccessKind kind;
    int32_t vertex;
  };
  std::vector<Want> want;
  const double* xy = m.xy.data();
  auto add = [&](int th, Array a, const void* p, uint32_t size, bool write, AccessKind k = K::kNone,
                 int32_t v = -1) {
    want.push_back({th, a, p, size, write, k, v});
  };
  // Triangles of the tiny mesh (two_interior.ele, 0-based).
  const std::vector<std::vector<int>> tri = {{0, 1, 6}, {1, 7, 6}, {6, 7, 4}, {6, 4, 5},
                                             {6, 5, 0}, {1, 2, 7}, {2, 3, 7}, {7, 3, 4}};
  auto visit = [&](int th, int k, int v, std::vector<int> nbrs, std::vector<int> tris) {
    add(th, Array::kInterior, m.interior.data() + k, 4, false);
    add(th, Array::kAdjOffsets, m.v2v.off.data() + v, 8, false, K::kAdjacency, v);
    add(th, Array::kAdjOffsets, m.v2v.off.data() + v + 1, 8, false);
    for (size_t i = 0; i < nbrs.size(); ++i) {
      add(th, Array::kAdjIndex, m.v2v.idx.data() + m.v2v.off[v] + i, 4, false);
      add(th, Array::kCoords, xy + 2 * nbrs[i], 16, false, K::kCoordRead, nbrs[i]);
    }
    add(th, Array::kCoords, xy + 2 * v, 16, true, K::kCoordWrite, v);
    add(th, Array::kTriOffsets, m.v2t.off.data() + v, 8, false);
    add(th, Array::kTriOffsets, m.v2t.off.data() + v + 1, 8, false);
    for (size_t i = 0; i < tris.size(); ++i) {
      const int t = tris[i];
      add(th, Array::kTriIndex, m.v2t.idx.data() + m.v2t.off[v] + i, 4, false);
      for (int j = 0; j < 3; ++j) add(th, Array::kTriangles, m.tri.data() + 3 * t + j, 4, false);
      for (int c : tri[t]) {
        add(th, Array::kCoords, xy + 2 * c, 8, false, K::kCoordRead, c);
        add(th, Array::kCoords, xy + 2 * c + 1, 8, false);
      }
      add(th, Array::kTriQuality, nullptr, 8, false);  // tq and w live inside Smooth:
      add(th, Array::kWeights, nullptr, 8, false);     // their addresses are checked below
      add(th, Array::kTriQuality, nullptr, 8, true);
    }
  };
  auto bound = [&](int th) { add(th, Array::kLoopBound, nullptr, 8, false); };
  bound(0);
  visit(0, 0, 6, {0, 1, 4, 5, 7}, {0, 1, 2, 3, 4});
  bound(0);  // the last test of thread 0's loop
  bound(1);
  visit(1, 1, 7, {1, 2, 3, 4, 6}, {1, 2, 5, 6, 7});
  bound(1);
  ASSERT_EQ(sink.refs.size(), want.size());
  ASSERT_EQ(want.size(), 2u * (6 + 2 * 5 + 13 * 5 + 2));
  // Weight and quality of triangle t at wq[2t] and wq[2t+1]: one base, 16 bytes per triangle.
  const char* wq0 = nullptr;
  for (size_t i = 0; i < want.size(); ++i) {
    const Want& e = want[i];
    const RecordingSink::Ref& g = sink.refs[i];
    SCOPED_TRACE("access " + std::to_string(i));
    EXPECT_EQ(g.thread, e.thread);
    EXPECT_EQ(g.ref.array, e.array);
    EXPECT_EQ(g.ref.size, e.size);
    EXPECT_EQ(g.ref.write, e.write);
    EXPECT_EQ(g.ref.element, e.kind);
    if (e.kind != K::kNone) {
      EXPECT_EQ(g.ref.vertex, e.vertex);
    }
    if (e.address) {
      EXPECT_EQ(g.ref.address, e.address);
      continue;
    }
    if (e.array == Array::kLoopBound) continue;  // a local: any stack address
    // Which triangle: the v2t.idx entry 6 accesses back names it.
    const int t = *static_cast<const int32_t*>(
        sink.refs[i - (e.array == Array::kTriQuality ? (e.write ? 12 : 10) : 11)].ref.address);
    const char* base =
        static_cast<const char*>(g.ref.address) - 16 * t - (e.array == Array::kTriQuality ? 8 : 0);
    if (!wq0) wq0 = base;
    EXPECT_EQ(base, wq0) << "array " << ArrayName(e.array) << " triangle " << t;
  }
  EXPECT_EQ(reinterpret_cast<uintptr_t>(wq0) % 64, 0u);  // aligned: reproducible line numbers
  EXPECT_EQ(RefsPerSweep(m, 2), (std::vector<uint64_t>{83, 83}));
}

// Per array and direction, one sweep's accesses equal closed forms in the mesh's degrees, on every
// test mesh, for both update modes and several thread counts.
TEST(AccessSequence, PerArrayCountsEqualClosedForms) {
  std::vector<std::pair<std::string, Mesh>> meshes;
  for (const char* f : {"two_interior.node", "two_components.node", "two_interior41.msh",
                        "two_interior22.msh", "two_interior0.node"})
    meshes.emplace_back(f, ReadMesh(testing::DataPath(f)));
  for (int variant = 0; variant < 6; ++variant) {
    SyntheticOptions so;
    so.nx = 12 + 5 * variant, so.ny = 9 + 3 * variant, so.holes = variant % 3;
    so.seed = 11 + variant;
    meshes.emplace_back("synthetic " + std::to_string(variant), BuildMesh(MakeSyntheticMesh(so)));
  }
  for (auto& [name, m0] : meshes)
    for (UpdateMode mode : {UpdateMode::kGaussSeidel, UpdateMode::kJacobi})
      for (int threads : {1, 3}) {
        SCOPED_TRACE(name + " " + UpdateModeName(mode) + " threads " + std::to_string(threads));
        Mesh m = m0.Clone();
        uint64_t ni = m.interior.size(), deg = 0, tris = 0;
        for (int32_t v : m.interior) deg += m.v2v.RowSize(v), tris += m.v2t.RowSize(v);
        const uint64_t nt = static_cast<uint64_t>(m.NumTriangles());
        std::array<std::array<uint64_t, 2>, kArrays> want{};  // [array][write]
        auto at = [&](Array a, bool w) -> uint64_t& { return want[static_cast<int>(a)][w]; };
        at(Array::kInterior, false) = ni;
        at(Array::kLoopBound, false) =
            mode == UpdateMode::kGaussSeidel ? ni + threads : ni + nt + 2 * threads;
        at(Array::kAdjOffsets, false) = 2 * ni;
        at(Array::kAdjIndex, false) = deg;
        if (mode == UpdateMode::kGaussSeidel) {
          at(Array::kCoords, false) = deg + 6 * tris;
          at(Array::kCoords, true) = ni;
          at(Array::kTriOffsets, false) = 2 * ni;
          at(Array::kTriIndex, false) = tris;
          at(Array::kTriangles, false) = 3 * tris;
          at(Array::kTriQuality, false) = tris;
          at(Array::kTriQuality, true) = tris;
          at(Array::kWeights, false) = tris;
        } else {
          at(Array::kCoords, false) = deg + 6 * nt;
          at(Array::kCoordsNext, true) = ni;
          at(Array::kTriangles, false) = 3 * nt;
          at(Array::kTriQuality, true) = nt;
          at(Array::kWeights, false) = nt;
        }
        SmoothOptions o = OneSweep(threads);
        o.mode = mode;
        CountingSink c;
        Smooth(m, o, c);
        std::array<std::array<uint64_t, 2>, kArrays> got{};
        uint64_t total = 0;
        for (const auto& p : c.per_thread)
          for (int a = 0; a < kArrays; ++a)
            for (int w = 0; w < 2; ++w) got[a][w] += p.array[a][w], total += p.array[a][w];
        for (int a = 0; a < kArrays; ++a)
          for (int w = 0; w < 2; ++w)
            EXPECT_EQ(got[a][w], want[a][w])
                << ArrayName(static_cast<Array>(a)) << (w ? " stores" : " loads");
        const std::vector<uint64_t> per = RefsPerSweep(m, threads, mode);
        ASSERT_LE(c.per_thread.size(), per.size());
        c.per_thread.resize(per.size());  // threads with no work reported nothing
        for (int t = 0; t < threads; ++t) {
          uint64_t n = 0;
          for (const auto& a : c.per_thread[t].array) n += a[0] + a[1];
          EXPECT_EQ(n, per[t]) << "thread " << t;
        }
        // Element touches: 2 + deg + 3 tris per visit (Gauss-Seidel).
        if (mode == UpdateMode::kGaussSeidel) {
          EXPECT_EQ(c.Elements(), 2 * ni + deg + 3 * tris);
        }
      }
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
  EXPECT_EQ(counts.Elements(), 5 * AccessesPerSweep(a)[0]);
  EXPECT_EQ(counts.Refs(), 5 * RefsPerSweep(a)[0]);
}

// StreamMesh without the counts (the kernels part's simulations): the same accesses in the same
// order and the same result, a StreamInfo without per-sweep counts, for every kernel; with them,
// another kernel's counts equal what its stream delivers.
TEST(AccessSequence, StreamWithoutCountsIsTheSameStream) {
  struct Record : AccessConsumer {
    StreamInfo info;
    std::vector<std::array<uint64_t, 4>> all;
    void Begin(const StreamInfo& i) override { info = i; }
    void Consume(const Access* a, size_t n) override {
      for (size_t i = 0; i < n; ++i)
        all.push_back({a[i].address, a[i].size, a[i].thread, a[i].write});
    }
  };
  SyntheticOptions so;
  so.nx = 21, so.ny = 14, so.holes = 1, so.seed = 5;
  const Mesh base = BuildMesh(MakeSyntheticMesh(so));
  for (const char* name : {"laplacian", "smart-laplacian", "untangle", "edge-swap", "spmv"}) {
    const KernelInfo& k = ParseKernel(name);
    Mesh a = base.Clone(), b = base.Clone();
    Record with, without;
    const SmoothResult ra = StreamMesh(a, ExactSweeps(2, 2), "m", "o", with, &k);
    const SmoothResult rb = StreamMesh(b, ExactSweeps(2, 2), "m", "o", without, &k, false);
    EXPECT_EQ(with.all, without.all) << name;
    EXPECT_EQ(a.xy, b.xy) << name;
    EXPECT_EQ(ra.quality_after, rb.quality_after) << name;
    EXPECT_EQ(without.info.threads, 2) << name;
    EXPECT_TRUE(without.info.canonical) << name;
    uint64_t announced = 0;
    for (const auto& sweep : with.info.sweep_records)
      for (uint64_t n : sweep) announced += n;
    EXPECT_EQ(announced, with.all.size()) << name;
    if (std::string(name) == "laplacian") continue;  // its counts are in closed form anyway
    EXPECT_TRUE(without.info.sweep_records.empty()) << name;
    EXPECT_EQ(without.info.records, 0u) << name;
  }
}

TEST(AccessSequence, PerSweepCountMatchesACountingSinkForEveryThreadCount) {
  SyntheticOptions so;
  so.nx = 25, so.ny = 17, so.holes = 1, so.seed = 4;
  for (UpdateMode mode : {UpdateMode::kGaussSeidel, UpdateMode::kJacobi})
    for (int threads : {1, 2, 3, 7}) {
      Mesh m = BuildMesh(MakeSyntheticMesh(so));
      CountingSink c;
      SmoothOptions o = OneSweep(threads);
      o.mode = mode;
      Smooth(m, o, c);
      const std::vector<uint64_t> want = AccessesPerSweep(m, threads, mode);
      ASSERT_EQ(c.per_thread.size(), want.size());
      for (int t = 0; t < threads; ++t)
        EXPECT_EQ(c.per_thread[t].kind[0] + c.per_thread[t].kind[1] + c.per_thread[t].kind[2],
                  want[t])
            << UpdateModeName(mode) << ", thread " << t << " of " << threads;
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
      for (int64_t k = 0; k < n; ++k) {
        ASSERT_EQ(StaticOwner(k, n, threads), owner[k])
            << "k " << k << " n " << n << " threads " << threads;
        int64_t b, e;  // the range form the sweep loops use
        StaticRange(n, threads, owner[k], &b, &e);
        ASSERT_TRUE(b <= k && k < e) << "k " << k << " n " << n << " threads " << threads;
      }
    }
}

class TraceFile : public ::testing::Test {
 protected:
  std::string Path(const std::string& n) const { return (dir_ / n).string(); }
  // Traces `sweeps` sweeps of the tiny mesh with 2 threads into PATH; returns the recording.
  RecordingSink Write(const std::string& path, int sweeps) {
    Mesh m = testing::TwoInterior();
    TraceHeader h;
    h.mesh = "two_interior";
    h.ordering = "ori";
    TraceWriter w(path, h, sweeps);
    SmoothOptions o;
    o.max_iters = sweeps;
    o.tol = -1;
    o.threads = 2;
    StreamMesh(m, o, "two_interior", "ori", w);  // threads and vertices from the stream
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
  EXPECT_EQ(r.header().records, 3u * 166);
  EXPECT_EQ(r.header().iteration_starts, (std::vector<uint64_t>{0, 166, 332}));
  EXPECT_EQ(r.header().vertices, 8u);
  // Each of the 3 sweeps: thread 0 visits vertex 6, thread 1 vertex 7, 83 accesses each, 22 of
  // them element touches.
  EXPECT_EQ(r.header().sweep_records, (std::vector<std::vector<uint64_t>>(3, {83, 83})));
  EXPECT_EQ(r.header().sweep_elements, (std::vector<std::vector<uint64_t>>(3, {22, 22})));
  EXPECT_EQ(r.header().mesh, "two_interior");
  EXPECT_EQ(r.header().ordering, "ori");
  std::vector<TraceRecord> batch, all;
  while (r.Next(&batch, 10)) all.insert(all.end(), batch.begin(), batch.end());
  ASSERT_EQ(all.size(), rec.refs.size());
  for (size_t i = 0; i < all.size(); ++i) {
    const MemRef& e = rec.refs[i].ref;
    EXPECT_EQ(all[i].kind, static_cast<uint8_t>(e.element));
    if (e.element != K::kNone) {
      EXPECT_EQ(all[i].vertex, static_cast<uint32_t>(e.vertex));
    }
    EXPECT_EQ(all[i].thread, rec.refs[i].thread);
    EXPECT_EQ(all[i].size, e.size);
    EXPECT_EQ(all[i].array & 0x7f, static_cast<uint8_t>(e.array));
    EXPECT_EQ((all[i].array & kStoreBit) != 0, e.write);
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
  ExpectRejected(write("version", bad),
                 "unknown trace version 7 (this reader knows versions 1 and 2)");
  ExpectRejected(
      write("cut", bytes.substr(0, bytes.size() - 5)),
      "truncated trace: the header says 332 records (byte offset 40), the file holds 5307 bytes of "
      "records (331 records and a partial one)");
  ExpectRejected(write("header", bytes.substr(0, 20)), "truncated trace header");
  ExpectRejected(write("empty", ""), "not a meshreuse trace");
  ExpectRejected(Path("missing"), "cannot open");
}

TEST_F(TraceFile, AnalysisFromFileEqualsStreaming) {
  Write(Path("t"), 2);
  ReuseAnalysis from_file({}), streamed({});
  StreamTraceFile(Path("t"), from_file);
  Mesh m = testing::TwoInterior();
  SmoothOptions so;
  so.max_iters = 2;
  so.tol = -1;
  so.threads = 2;
  StreamMesh(m, so, "two_interior", "ori", streamed);
  testing::RecordingConsumer rec;
  StreamTraceFile(Path("t"), rec);  // the stream the file delivers, record for record
  Mesh m2 = testing::TwoInterior();
  testing::RecordingConsumer live;
  StreamMesh(m2, so, "two_interior", "ori", live);
  ASSERT_EQ(rec.all.size(), live.all.size());
  for (size_t i = 0; i < rec.all.size(); ++i) {
    const Access &a = rec.all[i], &b = live.all[i];
    EXPECT_TRUE(a.address == b.address && a.element == b.element && a.size == b.size &&
                a.thread == b.thread && a.kind == b.kind && a.array == b.array &&
                a.write == b.write)
        << "access " << i;
  }
  EXPECT_EQ(rec.sweep_starts, live.sweep_starts);
  EXPECT_EQ(rec.info.sweep_records, live.info.sweep_records);
  EXPECT_EQ(rec.info.sweep_elements, live.info.sweep_elements);
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(from_file.element(t)->hist.Pairs(), streamed.element(t)->hist.Pairs());
    EXPECT_EQ(from_file.line(t)->hist.Pairs(), streamed.line(t)->hist.Pairs());
    EXPECT_EQ(from_file.element(t)->hist.accesses(), 44u);
    EXPECT_EQ(from_file.line(t)->hist.accesses(), 166u);
  }
}

// A version-1 file (element touches only, written by earlier releases) still reads: its records
// are the element stream and their addresses the line stream.
TEST_F(TraceFile, VersionOneStillReads) {
  TraceHeader h;
  h.version = 1;
  h.threads = 1;
  h.vertices = 4;
  h.records = 3;
  h.iteration_starts = {0};
  h.sweep_records = {{3}};
  h.mesh = "old";
  h.ordering = "ori";
  std::vector<char> b = EncodeTraceHeader(h, 1);
  const TraceRecord recs[3] = {{64, 1, 0, 0, 0, 0}, {128, 2, 1, 0, 0, 0}, {64, 1, 2, 0, 0, 0}};
  const char* p = reinterpret_cast<const char*>(recs);
  b.insert(b.end(), p, p + sizeof recs);
  std::ofstream(Path("v1"), std::ios::binary)
      .write(b.data(), static_cast<std::streamsize>(b.size()));
  TraceReader r(Path("v1"));
  EXPECT_EQ(r.header().version, 1u);
  EXPECT_EQ(r.header().sweep_records, (std::vector<std::vector<uint64_t>>{{3}}));
  EXPECT_EQ(r.header().sweep_elements, (std::vector<std::vector<uint64_t>>{{3}}));
  EXPECT_EQ(r.header().mesh, "old");
  std::vector<TraceRecord> got;
  ASSERT_TRUE(r.Next(&got));
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[1].vertex, 2u);
  EXPECT_EQ(got[1].address, 128u);
  EXPECT_EQ(got[2].kind, 2);
  EXPECT_EQ(got[2].size, 0);
}

// A rejected file gives its descriptor back: thousands of rejections leave the open-file count as
// it was (issue 8, reproducer 11).
TEST_F(TraceFile, RejectedFilesLeakNoDescriptor) {
  std::ofstream(Path("not_a_trace"), std::ios::binary) << "MRTRACEX and then some bytes";
  auto open_fds = [] {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator("/proc/self/fd")) n += !e.path().empty();
    return n;
  };
  const size_t before = open_fds();
  for (int i = 0; i < 3000; ++i) EXPECT_THROW(TraceReader r(Path("not_a_trace")), InputError);
  EXPECT_EQ(open_fds(), before);
}

// A header that announces 50,000 sweeps over a sparse body: the reader accepts it (it is
// consistent), and the profile holds no more steps than there are accesses (reproducer 8).
TEST_F(TraceFile, ManySweepsCostNoMoreThanTheirRecords) {
  TraceHeader h;
  h.threads = 1;
  h.vertices = 8;
  h.records = 1000;
  const int n = 50000;
  h.iteration_starts.assign(n, 1000);
  h.iteration_starts[0] = 0;
  h.sweep_records.assign(n, {0});
  h.sweep_records[0] = {1000};
  h.sweep_elements.assign(n, {0});
  const std::vector<char> b = EncodeTraceHeader(h, n);
  {
    std::ofstream out(Path("many"), std::ios::binary);
    out.write(b.data(), static_cast<std::streamsize>(b.size()));
  }
  fs::resize_file(Path("many"), b.size() + 1000 * sizeof(TraceRecord));  // a hole of zeros
  TraceReader r(Path("many"));
  ASSERT_EQ(r.header().sweep_records.size(), static_cast<size_t>(n));
  std::vector<uint64_t> lengths;
  for (const auto& sweep : r.header().sweep_records) lengths.push_back(sweep[0]);
  const ReuseProfile p(lengths, 100);
  EXPECT_EQ(p.steps().size(), 100u);  // the one sweep with records
  // Counts that do not add up are refused.
  h.sweep_records[0] = {999};
  const std::vector<char> bad = EncodeTraceHeader(h, n);
  {
    std::ofstream out(Path("bad"), std::ios::binary);
    out.write(bad.data(), static_cast<std::streamsize>(bad.size()));
  }
  fs::resize_file(Path("bad"), bad.size() + 1000 * sizeof(TraceRecord));
  ExpectRejected(Path("bad"), "corrupt trace header: sweep 2 starts at record 1000");
}

TEST(ExternalTrace, TextAndBinary) {
  testing::TempDir dir;
  const std::string text = dir / "ext";
  auto read = [](const std::string& path, const char* fmt) {
    std::vector<uint64_t> got;
    ReadForeignTrace(path, ParseTraceFormat(fmt),
                     [&](uint64_t v, uint32_t, bool, bool) { got.push_back(v); });
    return got;
  };
  std::ofstream(text) << "# a comment\n1\n0x10\n  2  \n\n0X1f # trailing\n";
  EXPECT_EQ(read(text, "text"), (std::vector<uint64_t>{1, 16, 2, 31}));
  std::ofstream(text) << "1\n2\nzz\n";
  try {
    read(text, "text");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.problem().find("'zz'"), std::string::npos);
  }
  const uint32_t u32[3] = {5, 0, 4000000000u};
  std::ofstream(text, std::ios::binary).write(reinterpret_cast<const char*>(u32), sizeof u32);
  EXPECT_EQ(read(text, "u32"), (std::vector<uint64_t>{5, 0, 4000000000u}));
  EXPECT_EQ(ForeignTraceLength(text, ParseTraceFormat("u32")), 3u);
  EXPECT_THROW(read(text, "u64"), InputError);  // 12 bytes
}

}  // namespace
}  // namespace meshreuse
