// Benchmarks (Google Benchmark; not unit tests, never run by ctest). Run:
//   build/release/tests/bench/meshreuse_bench --mesh=out/meshes/paper/carabiner.node
// They measure, in one run so the ratios are side by side:
//   Analyzer/<trace>         StackDistance + histogram over a trace: <ordering> is the mesh's
//                            first-sweep element trace, <ordering>-8 eight sweeps; scan, uniform
//                            and meshlike are synthetic (analysis/synthetic_trace.h)
//   TextbookFenwick/<trace>  the textbook analyzer (Fenwick tree over every time position, hash
//                            map of last accesses) on the same trace, for the ratio
//   ParallelSpeedup/<trace>  serial and 2-thread exact analysis alternated: the speedup
//   FileRatio/<trace>        in-memory analysis and the u64-file pipeline alternated: the ratio
//   Read/raw, Read/mesh      reading --mesh's file(s): into a RawMesh, and built; MB/s of input
//   ApplyRatio               ORI sweep, apply into a reused working copy, apply into a new mesh and
//                            the rebuild, alternated: medians, and each apply in ORI sweeps
//   Sweep/plain, Sweep/null  a hand-written Gauss-Seidel sweep with no sink at all, and
//                            Smooth<NullSink>'s sweep: NullSink must cost nothing
//   Sweep/analyze            one sweep streamed into the element analyzer (streaming cost)
//   StreamingRatio           untraced and streamed sweeps alternated: their ratio
//   Memory/<sweeps>          analyzer bytes per distinct element after 1 and 100 sweeps
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>

#include "analysis/reference.h"
#include "analysis/reuse_histogram.h"
#include "analysis/stack_distance.h"
#include "analysis/synthetic_trace.h"
#include "analysis/trace_analysis.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/quality.h"
#include "core/smoother.h"
#include "core/synthetic.h"

namespace meshreuse {
namespace {

std::string g_mesh = "out/meshes/paper/carabiner.node";

const Mesh& BaseMesh() {
  static const Mesh m = [] {
    if (std::filesystem::exists(g_mesh)) return ReadMesh(g_mesh);
    SyntheticOptions o;  // about 330k vertices when no mesh file is there
    o.nx = 640, o.ny = 510, o.holes = 3, o.seed = 1;
    return BuildMesh(MakeSyntheticMesh(o));
  }();
  return m;
}

const Mesh& Ordered(const std::string& ordering) {
  static std::map<std::string, Mesh> cache;
  auto it = cache.find(ordering);
  if (it == cache.end())
    it = cache
             .emplace(ordering,
                      ApplyPermutation(BaseMesh(), ComputeOrdering(ordering, BaseMesh(), 1)))
             .first;
  return it->second;
}

struct ElementTrace {
  static constexpr bool kEnabled = true;
  std::vector<uint64_t> ids;
  void BeginSweep(int) {}
  void Bind(const ArrayLayout&) {}
  void Access(int, const MemRef& r) {
    if (r.element != AccessKind::kNone) ids.push_back(static_cast<uint64_t>(r.vertex));
  }
};

// The traces by name: <ordering> (the mesh's first-sweep element trace), <ordering>-8 (8 sweeps),
// scan (1M ids x 20), uniform (20M accesses over 1M ids), meshlike (15M accesses over 330k ids,
// 10% far reuses).
const std::vector<uint64_t>& Trace(const std::string& name) {
  static std::map<std::string, std::vector<uint64_t>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  std::vector<uint64_t> t;
  if (name == "scan") {
    t = CyclicScanTrace(1000000, 20);
  } else if (name == "uniform") {
    t = UniformTrace(1000000, 20000000, 1);
  } else if (name == "meshlike") {
    t = MeshLikeTrace(330000, 15000000, 0.1, 1);
  } else {
    const size_t dash = name.find('-');
    Mesh m = Ordered(name.substr(0, dash)).Clone();
    SmoothOptions o;
    o.max_iters = dash == std::string::npos ? 1 : std::stoi(name.substr(dash + 1));
    o.tol = -1;
    ElementTrace e;
    Smooth(m, o, e);
    t = std::move(e.ids);
  }
  return cache.emplace(name, std::move(t)).first->second;
}

uint64_t DenseLimit(const std::string& name) {
  if (name == "scan" || name == "uniform") return 1000000;
  if (name == "meshlike") return 330000;
  return static_cast<uint64_t>(BaseMesh().NumVertices());
}

void Analyzer(benchmark::State& state, std::string name) {
  const std::vector<uint64_t>& trace = Trace(name);
  for (auto _ : state) {
    StackDistance sd(DenseLimit(name));
    ReuseHistogram h;
    h.Reserve(DenseLimit(name));
    for (uint64_t id : trace) h.Add(sd.Access(id));
    benchmark::DoNotOptimize(h.finite());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(trace.size()));
}

// The textbook method (analysis/reference.h), distances then the same histogram.
void TextbookFenwick(benchmark::State& state, std::string name) {
  const std::vector<uint64_t>& trace = Trace(name);
  for (auto _ : state) {
    ReuseHistogram h;
    for (uint64_t d : TextbookStackDistances(trace)) h.Add(d);
    benchmark::DoNotOptimize(h.finite());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(trace.size()));
}

// The exact parallel analyzer (chunk-and-merge) against the serial one, interleaved: each
// iteration analyses the trace serially and on `threads` threads (StreamAnalysis, histogram
// included, one batch), and the ratio of the summed times is the speedup.
void ParallelSpeedup(benchmark::State& state, std::string name) {
  const std::vector<uint64_t>& trace = Trace(name);
  const int threads = static_cast<int>(state.range(0));
  using Clock = std::chrono::steady_clock;
  double serial = 0, parallel = 0;
  for (auto _ : state) {
    for (int k = 0; k < 2; ++k) {
      StreamAnalysis s(DenseLimit(name));
      const auto t0 = Clock::now();
      s.AddBatch(trace.data(), trace.size(), k == 0 ? 1 : threads);
      const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
      (k == 0 ? serial : parallel) += secs;
      benchmark::DoNotOptimize(s.hist.finite());
    }
  }
  const double it = static_cast<double>(state.iterations());
  state.counters["serial_Macc_s"] = static_cast<double>(trace.size()) * it / serial / 1e6;
  state.counters["parallel_Macc_s"] = static_cast<double>(trace.size()) * it / parallel / 1e6;
  state.counters["speedup"] = serial / parallel;
}

// Reading a trace file against analysing it in memory, interleaved: each iteration writes nothing
// new, but times (a) StackDistance + histogram over the in-memory trace (the Analyzer figure) and
// (b) what `analyze FILE --format u64 --granularity element` does after start-up: read the u64
// file through InputStream, feed TraceAnalysis (histogram and profile). The ratio of the sums is
// the whole-process overhead.
void FileRatio(benchmark::State& state, std::string name) {
  const std::vector<uint64_t>& trace = Trace(name);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("meshreuse-bench-" + name + ".u64")).string();
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(trace.data(), 8, trace.size(), f) != trace.size()) {
      state.SkipWithError("cannot write the u64 file");
      return;
    }
    std::fclose(f);
  }
  using Clock = std::chrono::steady_clock;
  double mem = 0, file = 0;
  for (auto _ : state) {
    auto t0 = Clock::now();
    {
      StackDistance sd(DenseLimit(name));
      ReuseHistogram h;
      h.Reserve(DenseLimit(name));
      for (uint64_t id : trace) h.Add(sd.Access(id));
      benchmark::DoNotOptimize(h.finite());
    }
    auto t1 = Clock::now();
    {
      TraceAnalysisOptions o;
      o.granularity = Granularity::kElement;
      o.iteration_lengths = {{ExternalTraceLength(path, ExternalFormat::kU64)}};
      TraceAnalysis a(o);
      ReadExternalTrace(path, ExternalFormat::kU64,
                        [&a](uint64_t v, uint32_t) { a.AddElement(0, v); });
      a.Finish();
      benchmark::DoNotOptimize(a.element(0)->hist.finite());
    }
    auto t2 = Clock::now();
    mem += std::chrono::duration<double>(t1 - t0).count();
    file += std::chrono::duration<double>(t2 - t1).count();
  }
  std::remove(path.c_str());
  const double it = static_cast<double>(state.iterations());
  state.counters["memory_Macc_s"] = static_cast<double>(trace.size()) * it / mem / 1e6;
  state.counters["file_Macc_s"] = static_cast<double>(trace.size()) * it / file / 1e6;
  state.counters["ratio"] = file / mem;
}

// The lean sweep (--quality per-sweep): the moves, then one quality pass over the triangles; ns per
// interior vertex for each part and in all (the issue-10 goal: <= 15 ns on carabiner, 1 thread),
// beside the default per-move sweep in the same iterations.
void LeanSweep(benchmark::State& state, std::string ordering) {
  Mesh m = Ordered(ordering).Clone();
  const std::vector<double> tq = TriangleQualities(m), w = GlobalQualityWeights(m);
  AlignedVector<double> wq(2 * tq.size());
  for (size_t t = 0; t < tq.size(); ++t) wq[2 * t] = w[t], wq[2 * t + 1] = tq[t];
  using Clock = std::chrono::steady_clock;
  NullSink sink;
  double lean = 0, pass = 0, per_move = 0;
  for (auto _ : state) {
    auto t0 = Clock::now();
    benchmark::DoNotOptimize(smoother_detail::LeanGaussSeidelSweep(m, wq.data(), 1, sink, nullptr));
    auto t1 = Clock::now();
    benchmark::DoNotOptimize(smoother_detail::QualityPass(m, wq.data(), 1, sink, nullptr));
    auto t2 = Clock::now();
    benchmark::DoNotOptimize(smoother_detail::GaussSeidelSweep(
        smoother_detail::ArraysOf(m), m.interior, wq.data(), 1, sink, nullptr));
    auto t3 = Clock::now();
    lean += std::chrono::duration<double>(t1 - t0).count();
    pass += std::chrono::duration<double>(t2 - t1).count();
    per_move += std::chrono::duration<double>(t3 - t2).count();
  }
  const double k =
      1e9 / static_cast<double>(state.iterations()) / static_cast<double>(m.interior.size());
  state.counters["lean_ns"] = lean * k;
  state.counters["quality_pass_ns"] = pass * k;  // measured apart, for the split
  state.counters["per_move_ns"] = per_move * k;
}

// Applying an ordering against one ORI sweep, interleaved: each iteration times one untraced ORI
// sweep (the smoother's own timer), ApplyPermutation (direct) and ApplyPermutationByRebuild with
// the BFS permutation; the counters are the two applies in ORI sweeps (issue 12: <= 1).
void ApplyRatio(benchmark::State& state) {
  const Mesh& base = BaseMesh();
  const Permutation p = ComputeOrdering("bfs", base, 1);
  Mesh m = base.Clone();
  Mesh work = ApplyPermutation(base, p);
  SmoothOptions o;
  o.max_iters = 1;
  o.tol = -1;
  using Clock = std::chrono::steady_clock;
  std::vector<double> sweep, into, fresh, rebuild;
  auto ms = [](Clock::time_point a, Clock::time_point b) {
    return 1e3 * std::chrono::duration<double>(b - a).count();
  };
  for (auto _ : state) {
    sweep.push_back(1e3 * Smooth(m, o).sweeps[0].seconds);
    auto t0 = Clock::now();
    ApplyPermutationInto(base, p, TriangleOrder::kSorted, &work);
    auto t1 = Clock::now();
    benchmark::DoNotOptimize(ApplyPermutation(base, p).NumVertices());
    auto t2 = Clock::now();
    benchmark::DoNotOptimize(ApplyPermutationByRebuild(base, p).NumVertices());
    auto t3 = Clock::now();
    into.push_back(ms(t0, t1)), fresh.push_back(ms(t1, t2)), rebuild.push_back(ms(t2, t3));
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  const double s = median(sweep);
  state.counters["sweep_ms"] = s;
  state.counters["into_ms"] = median(into);
  state.counters["fresh_ms"] = median(fresh);
  state.counters["rebuild_ms"] = median(rebuild);
  state.counters["into_sweeps"] = median(into) / s;
  state.counters["fresh_sweeps"] = median(fresh) / s;
  state.counters["rebuild_sweeps"] = median(rebuild) / s;
}

// A Gauss-Seidel sweep written without any sink: what Smooth<NullSink> must match.
// Weight and quality of triangle t at wq[2t], wq[2t+1], as the smoother keeps them.
double PlainSweep(Mesh& m, std::vector<double>& wq) {
  double* xy = m.xy.data();
  double dq = 0;
  for (int32_t v : m.interior) {
    double sx = 0, sy = 0;
    for (const int32_t* p = m.v2v.RowBegin(v); p != m.v2v.RowEnd(v); ++p)
      sx += xy[2 * int64_t{*p}], sy += xy[2 * int64_t{*p} + 1];
    const double inv = 1.0 / static_cast<double>(m.v2v.RowSize(v));
    xy[2 * int64_t{v}] = sx * inv;
    xy[2 * int64_t{v} + 1] = sy * inv;
    for (const int32_t* p = m.v2t.RowBegin(v); p != m.v2t.RowEnd(v); ++p) {
      const double q = TriangleQuality(xy, &m.tri[3 * int64_t{*p}]);
      dq += wq[2 * int64_t{*p}] * (q - wq[2 * int64_t{*p} + 1]);
      wq[2 * int64_t{*p} + 1] = q;
    }
  }
  return dq;
}

void SweepPlain(benchmark::State& state) {
  Mesh m = BaseMesh().Clone();
  const std::vector<double> tq = TriangleQualities(m), w = GlobalQualityWeights(m);
  std::vector<double> wq(2 * tq.size());
  for (size_t t = 0; t < tq.size(); ++t) wq[2 * t] = w[t], wq[2 * t + 1] = tq[t];
  for (auto _ : state) benchmark::DoNotOptimize(PlainSweep(m, wq));
}

void SweepNull(benchmark::State& state) {
  Mesh m = BaseMesh().Clone();
  SmoothOptions o;
  o.max_iters = 1;
  o.tol = -1;
  double secs = 0;
  for (auto _ : state) {
    const SmoothResult r = Smooth(m, o);  // one sweep; its own timer excludes the set-up
    secs = r.sweeps[0].seconds;
    state.SetIterationTime(secs);
  }
}

void SweepAnalyze(benchmark::State& state) {
  Mesh m = BaseMesh().Clone();
  SmoothOptions o;
  o.max_iters = 1;
  o.tol = -1;
  for (auto _ : state) {
    TraceAnalysisOptions ao;
    ao.granularity = Granularity::kElement;
    ao.dense_elements = static_cast<uint64_t>(m.NumVertices());
    ao.line_base = AddressCanonicalizer::kCanonicalBase / ao.line_bytes;
    TraceAnalysis a(ao);
    AnalysisSink sink{&a};
    const SmoothResult r = Smooth(m, o, sink);
    state.SetIterationTime(r.sweeps[0].seconds);
  }
}

// The streaming cost as a ratio measured side by side: each iteration times one untraced sweep
// and one sweep streamed into the element analyzer, on the same mesh state.
void StreamingRatio(benchmark::State& state) {
  SmoothOptions o;
  o.max_iters = 1;
  o.tol = -1;
  double plain = 0, traced = 0;
  for (auto _ : state) {
    Mesh a = BaseMesh().Clone(), b = BaseMesh().Clone();
    plain += Smooth(a, o).sweeps[0].seconds;
    TraceAnalysisOptions ao;
    ao.granularity = Granularity::kElement;
    ao.dense_elements = static_cast<uint64_t>(b.NumVertices());
    ao.line_base = AddressCanonicalizer::kCanonicalBase / ao.line_bytes;
    TraceAnalysis an(ao);
    AnalysisSink sink{&an};
    traced += Smooth(b, o, sink).sweeps[0].seconds;
  }
  state.counters["plain_ms"] = 1e3 * plain / static_cast<double>(state.iterations());
  state.counters["streamed_ms"] = 1e3 * traced / static_cast<double>(state.iterations());
  state.counters["ratio"] = traced / plain;
}

void Memory(benchmark::State& state) {
  const int sweeps = static_cast<int>(state.range(0));
  for (auto _ : state) {
    Mesh m = BaseMesh().Clone();
    SmoothOptions o;
    o.max_iters = sweeps;
    o.tol = -1;
    TraceAnalysisOptions ao;
    ao.granularity = Granularity::kElement;
    ao.dense_elements = static_cast<uint64_t>(m.NumVertices());
    ao.line_base = AddressCanonicalizer::kCanonicalBase / ao.line_bytes;
    TraceAnalysis a(ao);
    AnalysisSink sink{&a};
    Smooth(m, o, sink);
    const StreamAnalysis* s = a.element(0);
    state.counters["accesses"] = static_cast<double>(s->sd.accesses());
    state.counters["bytes_per_distinct"] =
        static_cast<double>(s->sd.MemoryBytes()) / static_cast<double>(s->sd.distinct());
    state.counters["with_histogram"] =
        static_cast<double>(s->sd.MemoryBytes() + s->hist.counts().capacity() * 8) /
        static_cast<double>(s->sd.distinct());
  }
}

// Reading the mesh file(s) --mesh names (Triangle .node + .ele, or .msh) into a RawMesh, and into a
// built Mesh: bytes per second of input (the issue-12 goal: >= 200 MB/s).
void ReadSpeed(benchmark::State& state, bool build) {
  namespace fs = std::filesystem;
  if (!fs::exists(g_mesh)) return state.SkipWithError("no mesh file (--mesh=PATH)");
  int64_t bytes = static_cast<int64_t>(fs::file_size(g_mesh));
  const fs::path p(g_mesh);
  if (p.extension() == ".node")
    bytes += static_cast<int64_t>(fs::file_size(fs::path(p).replace_extension(".ele")));
  for (auto _ : state) {
    if (build)
      benchmark::DoNotOptimize(ReadMesh(g_mesh).NumVertices());
    else
      benchmark::DoNotOptimize(ReadRawMesh(g_mesh).xy.size());
  }
  state.SetBytesProcessed(bytes * state.iterations());
  state.counters["MB_per_s"] = benchmark::Counter(
      static_cast<double>(bytes) * 1e-6 * state.iterations(), benchmark::Counter::kIsRate);
}

}  // namespace
}  // namespace meshreuse

int main(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--mesh=", 7) == 0)
      meshreuse::g_mesh = argv[i] + 7;
    else
      rest.push_back(argv[i]);
  }
  int n = static_cast<int>(rest.size());
  using namespace meshreuse;
  // Each trace's analyzer and textbook runs side by side, so their ratio is from one moment.
  for (const char* o : {"ori", "bfs", "rdr", "random", "ori-8", "bfs-8", "rdr-8", "random-8",
                        "scan", "uniform", "meshlike"}) {
    benchmark::RegisterBenchmark(("Analyzer/" + std::string(o)).c_str(), Analyzer, std::string(o))
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("TextbookFenwick/" + std::string(o)).c_str(), TextbookFenwick,
                                 std::string(o))
        ->Unit(benchmark::kMillisecond);
  }
  for (const char* o : {"ori-8", "bfs-8", "rdr-8", "random-8", "scan", "uniform", "meshlike"})
    benchmark::RegisterBenchmark(("ParallelSpeedup/" + std::string(o)).c_str(), ParallelSpeedup,
                                 std::string(o))
        ->Arg(2)
        ->Iterations(5)
        ->Unit(benchmark::kMillisecond);
  for (const char* o : {"ori", "ori-8", "rdr-8", "uniform"})
    benchmark::RegisterBenchmark(("FileRatio/" + std::string(o)).c_str(), FileRatio, std::string(o))
        ->Iterations(5)
        ->Unit(benchmark::kMillisecond);
  for (const char* o : {"ori", "bfs", "rdr-wave"})
    benchmark::RegisterBenchmark(("LeanSweep/" + std::string(o)).c_str(), LeanSweep, std::string(o))
        ->Iterations(50)
        ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Read/raw", ReadSpeed, false)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("Read/mesh", ReadSpeed, true)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("ApplyRatio", ApplyRatio)
      ->Iterations(9)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Sweep/plain", SweepPlain)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Sweep/null", SweepNull)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Sweep/analyze", SweepAnalyze)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("StreamingRatio", StreamingRatio)
      ->Iterations(5)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Memory", Memory)
      ->Arg(1)
      ->Arg(100)
      ->Iterations(1)
      ->Unit(benchmark::kSecond);
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
