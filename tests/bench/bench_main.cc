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
//   Multicore/P              the many-core simulator (westmere-ex, P threads compact, a visit
//                            per turn) and the per-stream one (one thread's streams), each beside
//                            its code before issue 40 (tests/bench/before/) on the same streams,
//                            in turn: ns per access, the speedups pair by pair (median, min, max;
//                            the goal >= 3) and many-core over per-stream (the goal: <= 1.5);
//                            hot_*: the same, each batch of 512 copied into a small buffer
//                            before its Consume (as the tracer hands a report's simulators their
//                            batches), only Consume timed: no stream read from memory
//   OneRank                  the distributed smoother at one rank (ordered, ori, on a thread
//                            communicator) and the serial smoother with --quality per-sweep, the
//                            same sweeps in turn: ms per sweep (sweeps 2-6, median) and their
//                            ratio pair by pair (issue 40's goal: <= 1.15), the quality equal;
//                            the same ratio in thread CPU time (cpu_ratio); each quality pass
//                            alone, and the exact sum alone over the pass's terms, AddAll against
//                            Add term by term (the code before it)
//   Kernel/NAME              every kernel but the Laplacian (kernel_bench.cc): the registry's
//                            timed kernel (its template on NullSink) and a hand-written loop of
//                            the same arithmetic with no sink, alternated: ms per sweep (sweeps
//                            2.., median) and their ratio pair by pair (issue 41's goal: within 2%)
//   Build/fan/N, Build/grid/N  BuildMesh and RDR on a fan (one vertex in N triangles) and on a
//                            grid of N triangles, alternated: ns per triangle, and fan/grid
//                            (linear in any degree: the fan within 3x of the grid at 10^5 and
//                            10^6)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include "analysis/cache_sim.h"
#include "analysis/machine.h"
#include "analysis/multicore_sim.h"
#include "analysis/reference.h"
#include "analysis/reuse_analysis.h"
#include "analysis/reuse_histogram.h"
#include "analysis/stack_distance.h"
#include "analysis/synthetic_trace.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/quality.h"
#include "core/ranks/halo_smoother.h"
#include "core/ranks/partition.h"
#include "core/ranks/rank_part.h"
#include "core/ranks/thread_communicator.h"
#include "core/smoother.h"
#include "core/synthetic.h"
#include "tests/bench/before/multicore_sim.h"
#include "tests/bench/bench_util.h"
#include "tracer/access_stream.h"
#include "tracer/foreign_trace.h"

namespace meshreuse {

namespace {
std::string g_mesh = "out/meshes/paper/carabiner.node";
}  // namespace

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void PutRatios(benchmark::State& state, const std::string& name, std::vector<double> r) {
  std::sort(r.begin(), r.end());
  state.counters[name] = r[r.size() / 2];
  state.counters[name + "_min"] = r.front();
  state.counters[name + "_max"] = r.back();
}

const Mesh& BaseMesh() {
  static const Mesh m = [] {
    if (std::filesystem::exists(g_mesh)) return ReadMesh(g_mesh);
    SyntheticOptions o;  // about 330k vertices when no mesh file is there
    o.nx = 640, o.ny = 510, o.holes = 3, o.seed = 1;
    return BuildMesh(MakeSyntheticMesh(o));
  }();
  return m;
}

namespace {

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

// The exact parallel analyzer (chunks and the streamed merge) against the serial one, interleaved:
// each iteration analyses the trace serially and on `threads` threads (StreamAnalysis, histogram
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
// file through InputStream, feed ReuseAnalysis (histogram and profile). The ratio of the sums is
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
      ReuseOptions o;
      o.granularity = Granularity::kElement;
      ReuseAnalysis a(o);
      StreamForeignTrace(path, ParseTraceFormat("u64"), false, a);
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
  const double s = Median(sweep);
  state.counters["sweep_ms"] = s;
  state.counters["into_ms"] = Median(into);
  state.counters["fresh_ms"] = Median(fresh);
  state.counters["rebuild_ms"] = Median(rebuild);
  state.counters["into_sweeps"] = Median(into) / s;
  state.counters["fresh_sweeps"] = Median(fresh) / s;
  state.counters["rebuild_sweeps"] = Median(rebuild) / s;
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
    ReuseOptions ao;
    ao.granularity = Granularity::kElement;
    ao.profile = false;
    ReuseAnalysis a(ao);
    const SmoothResult r = StreamMesh(m, o, "mesh", "ori", a);
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
    ReuseOptions ao;
    ao.granularity = Granularity::kElement;
    ao.profile = false;
    ReuseAnalysis an(ao);
    traced += StreamMesh(b, o, "mesh", "ori", an).sweeps[0].seconds;
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
    ReuseOptions ao;
    ao.granularity = Granularity::kElement;
    ao.profile = false;
    ReuseAnalysis a(ao);
    StreamMesh(m, o, "mesh", "ori", a);
    const StreamAnalysis* s = a.element(0);
    state.counters["accesses"] = static_cast<double>(s->sd.accesses());
    state.counters["bytes_per_distinct"] =
        static_cast<double>(s->sd.MemoryBytes()) / static_cast<double>(s->sd.distinct());
    state.counters["with_histogram"] =
        static_cast<double>(s->sd.MemoryBytes() + s->hist.counter_bytes()) /
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

// The streams of two sweeps of the --mesh at P threads, in memory; then both simulators over them.
void Multicore(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  SmoothOptions o;
  o.max_iters = 2, o.tol = -1, o.threads = p, o.interleave = 1;
  struct Keep : AccessConsumer {
    std::vector<Access> all;
    StreamInfo info;
    void Begin(const StreamInfo& i) override { info = i; }
    void Consume(const Access* a, size_t n) override { all.insert(all.end(), a, a + n); }
  } keep, one;
  Mesh m = BaseMesh().Clone();
  StreamMesh(m, o, "m", "ori", keep);
  o.threads = 1;
  Mesh m1 = BaseMesh().Clone();
  StreamMesh(m1, o, "m", "ori", one);  // today's case: one stream, private caches
  const Machine w = ParseMachine("westmere-ex");
  const CacheSpec spec = ParseCacheSpec("westmere-ex");
  // Each iteration times the old code (tests/bench/before/, as at 6436f89) and today's on the same
  // streams, in turn; their counts must agree exactly.
  std::vector<double> multi, single, multi_before, single_before;
  auto ns = [](auto t0, auto t1, size_t n) {
    return 1e9 * std::chrono::duration<double>(t1 - t0).count() / static_cast<double>(n);
  };
  auto feed = [](auto& sim, const std::vector<Access>& all) {
    for (size_t i = 0; i < all.size(); i += 512)
      sim.Consume(all.data() + i, std::min<size_t>(512, all.size() - i));
  };
  std::vector<double> scan;  // reading the stored stream alone: a floor under both
  // The same streams as the report hands them over: each batch of 512 copied into a small buffer
  // first (as the tracer writes its batch, tracer/access_stream.cc), only Consume timed. The stored
  // stream (1.5 GB for carabiner) is read from memory, which no report does; `hot_clock_ns` is what
  // the two clock reads add (timed around an empty Consume), left in: it lowers the ratios.
  std::vector<Access> buf(512);
  auto feed_hot = [&buf](auto& sim, const std::vector<Access>& all) {
    std::chrono::steady_clock::duration d{};
    for (size_t i = 0; i < all.size(); i += 512) {
      const size_t k = std::min<size_t>(512, all.size() - i);
      std::copy_n(all.data() + i, k, buf.data());
      const auto t0 = std::chrono::steady_clock::now();
      sim.Consume(buf.data(), k);
      d += std::chrono::steady_clock::now() - t0;
    }
    return 1e9 * std::chrono::duration<double>(d).count() / static_cast<double>(all.size());
  };
  struct NoSim {
    void Consume(const Access* a, size_t) { benchmark::DoNotOptimize(a); }
  } none;
  std::vector<double> hot_multi, hot_single, hot_multi_before, hot_single_before, hot_clock;
  for (auto _ : state) {
    auto s0 = std::chrono::steady_clock::now();
    uint64_t sum = 0;
    for (const Access& x : keep.all) sum += x.address + x.size + x.thread + x.write;
    benchmark::DoNotOptimize(sum);
    scan.push_back(ns(s0, std::chrono::steady_clock::now(), keep.all.size()));
    auto t0 = std::chrono::steady_clock::now();
    before::MulticoreSimulation a0(w, Placement::kCompact);
    a0.Begin(keep.info);
    feed(a0, keep.all);
    auto t1 = std::chrono::steady_clock::now();
    MulticoreSimulation a(w, Placement::kCompact);
    a.Begin(keep.info);
    feed(a, keep.all);
    auto t2 = std::chrono::steady_clock::now();
    before::CacheSimulation b0(spec, 64);
    b0.Begin(one.info);
    feed(b0, one.all);
    auto t3 = std::chrono::steady_clock::now();
    CacheSimulation b(spec, 64);
    b.Begin(one.info);
    feed(b, one.all);
    auto t4 = std::chrono::steady_clock::now();
    for (int t = 0; t < p; ++t)
      for (size_t l = 0; l < w.levels.size(); ++l) {
        const auto& x = a.Stats(t).levels[l];
        const auto& y = a0.Stats(t).levels[l];
        if (x.misses != y.misses || x.cold != y.cold || x.coherence != y.coherence ||
            x.prefetch_hits != y.prefetch_hits || x.inclusion_victims != y.inclusion_victims)
          return state.SkipWithError("the many-core simulator's counts changed");
      }
    for (size_t l = 0; l < spec.levels.size(); ++l)
      if (b.Stats(0)[l].misses != b0.Stats(0)[l].misses ||
          b.Stats(0)[l].cold != b0.Stats(0)[l].cold)
        return state.SkipWithError("the per-stream simulator's counts changed");
    hot_clock.push_back(feed_hot(none, keep.all));
    {
      before::MulticoreSimulation h0(w, Placement::kCompact);
      h0.Begin(keep.info);
      hot_multi_before.push_back(feed_hot(h0, keep.all));
      MulticoreSimulation h(w, Placement::kCompact);
      h.Begin(keep.info);
      hot_multi.push_back(feed_hot(h, keep.all));
      before::CacheSimulation c0(spec, 64);
      c0.Begin(one.info);
      hot_single_before.push_back(feed_hot(c0, one.all));
      CacheSimulation c(spec, 64);
      c.Begin(one.info);
      hot_single.push_back(feed_hot(c, one.all));
      for (size_t l = 0; l < spec.levels.size(); ++l)
        if (c.Stats(0)[l].misses != b.Stats(0)[l].misses ||
            c.Stats(0)[l].cold != b.Stats(0)[l].cold)
          return state.SkipWithError("the per-stream simulator fed in batches counted otherwise");
      for (int t = 0; t < p; ++t)
        for (size_t l = 0; l < w.levels.size(); ++l)
          if (h.Stats(t).levels[l].misses != a.Stats(t).levels[l].misses ||
              h.Stats(t).levels[l].coherence != a.Stats(t).levels[l].coherence)
            return state.SkipWithError("the many-core simulator fed in batches counted otherwise");
    }
    multi_before.push_back(ns(t0, t1, keep.all.size()));
    multi.push_back(ns(t1, t2, keep.all.size()));
    single_before.push_back(ns(t2, t3, one.all.size()));
    single.push_back(ns(t3, t4, one.all.size()));
  }
  auto ratios = [](const std::vector<double>& x, const std::vector<double>& y) {
    std::vector<double> r;
    for (size_t i = 0; i < x.size(); ++i) r.push_back(x[i] / y[i]);
    return r;
  };
  // A simulator's ns an access today and before, and the speedups pair by pair.
  auto put = [&](const std::string& now_name, const std::string& before_name,
                 const std::string& speedup_name, const std::vector<double>& now,
                 const std::vector<double>& before) {
    state.counters[now_name] = Median(now);
    state.counters[before_name] = Median(before);
    PutRatios(state, speedup_name, ratios(before, now));
  };
  put("multicore_ns_per_access", "multicore_before_ns", "multicore_speedup", multi, multi_before);
  put("per_stream_ns_per_access", "per_stream_before_ns", "per_stream_speedup", single,
      single_before);
  put("hot_multicore_ns", "hot_multicore_before_ns", "hot_multicore_speedup", hot_multi,
      hot_multi_before);
  put("hot_per_stream_ns", "hot_per_stream_before_ns", "hot_per_stream_speedup", hot_single,
      hot_single_before);
  state.counters["ratio"] = Median(multi) / Median(single);
  state.counters["read_stream_ns"] = Median(scan);
  state.counters["hot_clock_ns"] = Median(hot_clock);
  CacheSimulation b(spec, 64);  // the levels' miss rates of the one-thread stream
  b.Begin(one.info);
  feed(b, one.all);
  for (size_t l = 0; l < spec.levels.size(); ++l)
    state.counters[spec.levels[l].name + "_miss_rate"] = b.Stats(0)[l].MissRate();
}

// One rank of the distributed smoother against the serial lean sweep, alternated.
void OneRank(benchmark::State& state) {
  const Mesh& base = BaseMesh();
  const std::vector<int32_t> part(static_cast<size_t>(base.NumVertices()), 0);
  const PartitionStats ps = MeasurePartition(base, part, 1);
  constexpr int kSweeps = 6;
  HaloOptions ho;
  ho.max_iters = kSweeps, ho.tol = -1;
  SmoothOptions so = ExactSweeps(kSweeps);
  so.quality = QualityMode::kPerSweep;
  std::vector<double> serial_ms, rank_ms, ratio, cpu_ratio, rank_q_ms, serial_q_ms, all_ms, each_ms;
  std::vector<double> wq;  // the serial smoother's interleaved weights (smoother.h)
  for (const double w : GlobalQualityWeights(base)) wq.push_back(w), wq.push_back(0.0);
  NullSink null;
  for (auto _ : state) {
    Mesh m = base.Clone();
    const SmoothResult sr = Smooth(m, so);
    RankPart p = BuildRankPart(base, part, 1, ps.colour, 0);
    HaloResult hr;
    ThreadCommunicator::Run(1, [&](Communicator& tx) { hr = SmoothRankPart(p, ho, tx); });
    std::vector<double> a, b, ac, bc;  // sweeps 2.. (the first pays for cold caches)
    for (int k = 1; k < kSweeps; ++k) a.push_back(1e3 * sr.sweeps[k].seconds);
    for (int k = 1; k < kSweeps; ++k) b.push_back(1e3 * hr.sweeps[k].seconds);
    for (int k = 1; k < kSweeps; ++k) ac.push_back(sr.sweeps[k].cpu_seconds);
    for (int k = 1; k < kSweeps; ++k) bc.push_back(hr.sweeps[k].cpu_seconds);
    if (std::abs(hr.sweeps.back().quality - sr.sweeps.back().quality) > 1e-12)
      return state.SkipWithError("one rank's quality differs from the serial smoother's");
    serial_ms.push_back(Median(a));
    rank_ms.push_back(Median(b));
    // Where the difference is: each quality pass alone, on the same coordinates (the rank's
    // exact fixed-point sum of its triangles; the serial smoother's vectorised double sum).
    const auto c0 = std::chrono::steady_clock::now();
    const FixedSum exact = PartQuality(p);
    const auto c1 = std::chrono::steady_clock::now();
    const double plain = smoother_detail::QualityPass(m, wq.data(), 1, null, nullptr);
    const auto c2 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(exact.ToDouble() + plain);
    rank_q_ms.push_back(1e3 * std::chrono::duration<double>(c1 - c0).count());
    serial_q_ms.push_back(1e3 * std::chrono::duration<double>(c2 - c1).count());
    // The exact sum alone, over the same terms: AddAll, then the per-term Add it replaced.
    std::vector<double> terms(p.weight.size());
    for (size_t t = 0; t < terms.size(); ++t)
      terms[t] = p.weight[t] * TriangleQuality(p.xy.data(), &p.tri[3 * t]);
    FixedSum all, each;
    const auto s0 = std::chrono::steady_clock::now();
    all.AddAll(terms.data(), static_cast<int64_t>(terms.size()));
    const auto s1 = std::chrono::steady_clock::now();
    for (const double x : terms) each.Add(x);
    const auto s2 = std::chrono::steady_clock::now();
    if (all != each || all != exact)
      return state.SkipWithError("AddAll differs from Add term by term");
    all_ms.push_back(1e3 * std::chrono::duration<double>(s1 - s0).count());
    each_ms.push_back(1e3 * std::chrono::duration<double>(s2 - s1).count());
    ratio.push_back(rank_ms.back() / serial_ms.back());
    cpu_ratio.push_back(Median(bc) / Median(ac));
  }
  state.counters["serial_ms_per_sweep"] = Median(serial_ms);
  state.counters["one_rank_ms_per_sweep"] = Median(rank_ms);
  PutRatios(state, "ratio", ratio);
  PutRatios(state, "cpu_ratio", cpu_ratio);  // thread CPU time: steadier on a shared host
  state.counters["rank_quality_pass_ms"] = Median(rank_q_ms);
  state.counters["serial_quality_pass_ms"] = Median(serial_q_ms);
  state.counters["exact_sum_ms"] = Median(all_ms);
  state.counters["term_by_term_sum_ms"] = Median(each_ms);
}

// A fan: vertex 0 at the centre of n rim vertices, n triangles around it (its degree is n); or a
// grid of about n triangles (degree 6). The same triangle count, the one difference the degree.
RawMesh FanOrGrid(bool fan, int64_t n) {
  RawMesh r;
  if (fan) {
    r.xy = {0.0, 0.0};
    for (int64_t i = 0; i < n; ++i) {
      const double a = 2 * M_PI * static_cast<double>(i) / static_cast<double>(n);
      r.xy.push_back(std::cos(a)), r.xy.push_back(std::sin(a));
    }
    for (int64_t i = 0; i < n; ++i)
      for (int64_t c : {int64_t{0}, i + 1, (i + 1) % n + 1})
        r.tri.push_back(static_cast<int32_t>(c));
    return r;
  }
  const int64_t k = static_cast<int64_t>(std::sqrt(static_cast<double>(n) / 2)) + 1;
  for (int64_t y = 0; y <= k; ++y)
    for (int64_t x = 0; x <= k; ++x) r.xy.push_back(x), r.xy.push_back(y);
  for (int64_t y = 0; y < k; ++y)
    for (int64_t x = 0; x < k; ++x) {
      const int32_t a = static_cast<int32_t>(y * (k + 1) + x), b = a + 1;
      const int32_t c = static_cast<int32_t>(a + k + 1), d = c + 1;
      for (int32_t v : {a, b, d, a, d, c}) r.tri.push_back(v);
    }
  return r;
}

void Build(benchmark::State& state) {
  const int64_t n = state.range(0);
  const RawMesh fan = FanOrGrid(true, n), grid = FanOrGrid(false, n);
  std::vector<double> bf, bg, of, og;  // build, order; fan, grid
  for (auto _ : state) {
    for (const RawMesh* r : {&fan, &grid}) {
      RawMesh copy;
      copy.xy = r->xy, copy.tri = r->tri;
      const double per = 1e9 / static_cast<double>(r->tri.size() / 3);
      const auto t0 = std::chrono::steady_clock::now();
      const Mesh m = BuildMesh(std::move(copy));
      const auto t1 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(ComputeOrdering("rdr", m).size());
      const auto t2 = std::chrono::steady_clock::now();
      (r == &fan ? bf : bg).push_back(per * std::chrono::duration<double>(t1 - t0).count());
      (r == &fan ? of : og).push_back(per * std::chrono::duration<double>(t2 - t1).count());
    }
  }
  state.counters["build_fan_ns_tri"] = Median(bf);
  state.counters["build_grid_ns_tri"] = Median(bg);
  state.counters["build_fan/grid"] = Median(bf) / Median(bg);
  state.counters["rdr_fan/grid"] = Median(of) / Median(og);
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
  benchmark::RegisterBenchmark("Multicore", Multicore)
      ->Arg(1)
      ->Arg(8)
      ->Arg(32)
      ->Iterations(5)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("OneRank", OneRank)->Iterations(11)->Unit(benchmark::kMillisecond);
  RegisterKernelBenchmarks();
  benchmark::RegisterBenchmark("Build", Build)
      ->Arg(100000)
      ->Arg(1000000)
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
