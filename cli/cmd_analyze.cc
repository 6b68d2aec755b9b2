// meshreuse trace | analyze: write the smoother's access trace; reuse distances, quantiles,
// histograms, profiles and modelled misses of a mesh (streamed, no file), a trace file, or another
// tool's trace (--format text|u32|u64).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "analysis/trace_analysis.h"
#include "cli/common.h"
#include "cli/options.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/smoother.h"
#include "reports/run_info.h"
#include "reports/table.h"
#include "tracer/input_stream.h"
#include "tracer/trace_reader.h"
#include "tracer/trace_writer.h"

namespace meshreuse::cli {

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string Base(const std::string& p) { return std::filesystem::path(p).filename().string(); }

SmoothOptions TraceSweeps(int iterations, int threads, const std::string& mode) {
  SmoothOptions o;
  o.max_iters = iterations;
  o.tol = -std::numeric_limits<double>::infinity();  // exactly `iterations` sweeps
  o.threads = threads;
  try {
    o.mode = ParseUpdateMode(mode);
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
  return o;
}

struct Job {
  std::string input, ordering;
  int64_t vertices = 0;  // 0: unknown
  int iterations = 0;
  std::unique_ptr<TraceAnalysis> analysis;
  // Per thread stream: the vertices it moves, summed over its sweeps (its coordinate writes), so
  // per_vertex_sweep is per the thread's own vertices. Empty: unknown (foreign traces).
  std::vector<uint64_t> moves;
};

std::string Cap(uint64_t c) { return c == kInfiniteCapacity ? "inf" : std::to_string(c); }

}  // namespace

int TraceCommand(const Args& args) {
  po::options_description desc("options");
  std::string mesh, ordering = "ori", out, mode = "gauss-seidel", triangle_order;
  int iterations = 1, threads = 1;
  uint32_t element_bytes = 66;
  uint64_t seed = 1;
  desc.add_options()("mesh", po::value(&mesh)->required(), "input mesh")(
      "ordering", po::value(&ordering)->default_value("ori"),
      ("one of: " + OrderingNames()).c_str())("seed", po::value(&seed)->default_value(1),
                                              "seed of randomised orderings")(
      "iterations,k", po::value(&iterations)->default_value(1), "sweeps to trace")(
      "threads,t", po::value(&threads)->default_value(1), "streams: the static schedule's threads")(
      "mode", po::value(&mode)->default_value("gauss-seidel"), "gauss-seidel or jacobi")(
      "element-bytes", po::value(&element_bytes)->default_value(66),
      "element size recorded in the header")("output,o", po::value(&out)->required(), "trace file")(
      "compress", "zstd-compress the trace (read back transparently by analyze and simulate)")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(args, "trace MESH [--ordering NAME] [--iterations K] [--threads P] -o FILE",
                    "Writes every access of K smoothing sweeps (vertex id, byte address, kind, "
                    "thread) to a binary trace (format in tracer/trace_format.h, 16 bytes per "
                    "access). The access sequence of one vertex visit is documented in "
                    "core/smoother.h.",
                    desc, pos, vm))
    return 0;
  if (iterations < 1 || iterations > 100000) throw po::error("--iterations must be 1..100000");
  if (threads < 1 || threads > 255) throw po::error("--threads must be 1..255");
  CheckOrderings({ordering});
  CheckWritable(out);
  const bool compress = vm.count("compress") > 0;
  const SmoothOptions so = TraceSweeps(iterations, threads, mode);
  const TriangleOrder tri_order = TriangleOrderOption(triangle_order);
  const Progress progress(vm.count("quiet") > 0);
  Mesh m = LayOut(mesh, ordering, seed, tri_order, progress);
  TraceHeader h;
  h.threads = static_cast<uint32_t>(threads);
  h.vertices = static_cast<uint32_t>(m.NumVertices());
  h.element_bytes = element_bytes;
  h.mesh = Base(mesh);
  h.ordering = ordering;
  const auto t0 = Clock::now();
  // Compressed: the plain trace first (its header is final only at the end), then zstd.
  const std::string plain = compress ? out + ".plain.tmp." + std::to_string(::getpid()) : out;
  TraceWriter w(plain, h, iterations);
  uint64_t per_sweep = 0;
  for (uint64_t n : RefsPerSweep(m, threads, so.mode)) per_sweep += n;
  progress.Say("tracing " + std::to_string(iterations) + " sweep(s), about " +
               Grouped(static_cast<long long>(per_sweep * iterations)) + " accesses");
  Smooth(m, so, w);
  w.Close();
  if (compress) {
    try {
      progress.Say("compressing with zstd");
      CompressFile(plain, out);
    } catch (...) {
      std::remove(plain.c_str());
      throw;
    }
    std::remove(plain.c_str());
  }
  const uint64_t n = w.records();
  const uint64_t elements = w.elements();
  const double per = static_cast<double>(m.NumVertices()) * iterations;
  std::printf(
      "wrote %s: %s accesses (%s per vertex per sweep), %s element touches (%s), %d sweep(s), "
      "%d stream(s), %.1f MB%s, %.2f s\n",
      out.c_str(), Grouped(static_cast<long long>(n)).c_str(),
      Fixed(static_cast<double>(n) / per, 2).c_str(),
      Grouped(static_cast<long long>(elements)).c_str(),
      Fixed(static_cast<double>(elements) / per, 2).c_str(), iterations, threads,
      (static_cast<double>(n) * sizeof(TraceRecord)) / 1e6,
      compress ? (" (" + Fixed(static_cast<double>(std::filesystem::file_size(out)) / 1e6, 1) +
                  " MB compressed)")
                     .c_str()
               : "",
      Since(t0));
  return 0;
}

namespace {

// %.17g: the double exactly (a mean of exact integers, to within an ulp of the quotient).
std::string Full(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// One stream's row; `human` rounds the mean to one decimal (the aligned view), otherwise every
// number is exact or at full precision.
std::vector<std::string> StreamRow(const Job& j, int th, const char* gname, const StreamAnalysis& s,
                                   const std::vector<double>& qs,
                                   const std::vector<CacheLevel>& levels, uint32_t bytes,
                                   const std::vector<CacheLevel>& inverse, bool human) {
  const ReuseHistogram& h = s.hist;
  std::vector<std::string> row = {
      j.input,
      j.ordering,
      std::to_string(th),
      gname,
      std::to_string(h.accesses()),
      th < static_cast<int>(j.moves.size()) && j.moves[th]
          ? (human ? Fixed(static_cast<double>(h.accesses()) / j.moves[th], 2)
                   : JsonNumber(static_cast<double>(h.accesses()) / j.moves[th]))
          : "",
      std::to_string(h.cold()),
      std::to_string(s.sd.distinct()),
      h.finite() ? ToDecimal(h.sum()) : "",
      h.finite() ? (human ? Fixed(h.mean(), 1) : Full(h.mean())) : ""};
  for (double q : qs) row.push_back(h.finite() ? std::to_string(h.Quantile(q)) : "");
  const std::vector<LevelMisses> miss = ModelMisses(h, levels, bytes);
  for (const LevelMisses& m : miss) row.push_back(std::to_string(m.misses));
  if (levels.size() == 3) {
    const CostRange c = AdditionalCycles(miss);
    row.push_back(Fixed(c.low, 0));
    row.push_back(Fixed(c.high, 0));
  }
  for (const CacheLevel& l : inverse) row.push_back(Cap(CapacityForMisses(h, l.bytes)));
  return row;
}

// The sampled estimate's row (SHARDS): estimated counts, the rate and seed that made them, and
// the miss-ratio curve's error against the exact one when both ran.
std::vector<std::string> SampledRow(const Job& j, int th, const char* gname,
                                    const StreamAnalysis& s, const std::vector<double>& qs,
                                    const std::vector<CacheLevel>& levels, uint32_t bytes,
                                    bool human) {
  const Shards& e = *s.shards;
  auto num = [human](double v, int d) { return human ? Fixed(v, d) : Full(v); };
  const bool finite = !e.weights().empty();
  std::vector<std::string> row = {j.input,
                                  j.ordering,
                                  std::to_string(th),
                                  gname,
                                  e.options().s_max ? "fixed-size" : "fixed-rate",
                                  num(e.rate(), 6),
                                  std::to_string(e.options().seed),
                                  std::to_string(e.accesses()),
                                  std::to_string(e.samples()),
                                  num(e.cold_weight(), 0),
                                  num(e.distinct_estimate(), 0),
                                  finite ? num(e.Mean(), 1) : ""};
  for (double q : qs) row.push_back(finite ? std::to_string(e.Quantile(q)) : "");
  for (const CacheLevel& l : levels) {
    const uint64_t cap = bytes ? l.bytes / bytes : 0;
    row.push_back(num(e.MissRatio(cap) * static_cast<double>(e.accesses()), 0));
  }
  row.push_back(s.exact ? num(MrcMeanAbsoluteError(s.hist, e), 6) : "");
  return row;
}

}  // namespace

int AnalyzeCommand(const Args& args) {
  po::options_description desc("options");
  std::vector<std::string> inputs;
  std::string orderings = "ori", format, granularity, quantiles = "50,75,90,100",
              cache = "westmere-ex", mode = "gauss-seidel", hist_csv, prof_csv, mrc_csv, out_dir,
              measured, triangle_order;
  int iterations = 1, threads = 1;
  uint32_t element_bytes = 66, line_bytes = 64;
  uint64_t seed = 1, sample_size = 0;
  double sample_rate = 0;
  desc.add_options()(
      "input", po::value(&inputs)->required()->multitoken(),
      "mesh(es) (.node/.ele/.msh: the smoother streams into the analyzer), a trace "
      "file from `meshreuse trace` (plain or zstd), or another tool's trace with --format ('-': "
      "stdin)")("orderings", po::value(&orderings)->default_value("ori"),
                "for meshes: comma-separated orderings")(
      "seed", po::value(&seed)->default_value(1),
      "seed of randomised orderings and of the sampling hash")(
      "iterations,k", po::value(&iterations)->default_value(1), "for meshes: sweeps to analyse")(
      "threads,t", po::value(&threads)->default_value(1),
      "for meshes: the smoother's threads (one stream each); for trace files: the analyzer's "
      "threads per stream (exact chunk-and-merge)")("mode",
                                                    po::value(&mode)->default_value("gauss-seidel"),
                                                    "for meshes: gauss-seidel or jacobi")(
      "format", po::value(&format),
      "other tools' traces: text (decimal or 0x-hex per line), u32, u64 (little-endian), parda "
      "(PARDA's binary = u64), oracle (libCacheSim oracleGeneral), lackey (valgrind "
      "--trace-mem=yes); any of them may be zstd-compressed")(
      "instructions", "lackey: count instruction fetches (I lines) too, not only data")(
      "granularity", po::value(&granularity),
      "element, line or both (default: both for meshes and meshreuse traces; line for address "
      "traces: lackey, parda, u32, u64; element for id traces: text, oracle)")(
      "quantiles", po::value(&quantiles)->default_value("50,75,90,100"), "percentages to report")(
      "cache", po::value(&cache)->default_value("westmere-ex"),
      "westmere-ex or L1=32K,L2=256K,L3=24M")("element-bytes",
                                              po::value(&element_bytes)->default_value(66),
                                              "element size for the element miss model")(
      "line-bytes", po::value(&line_bytes)->default_value(64), "cache line size (a power of two)")(
      "measured-misses", po::value(&measured),
      "inverse model: L1=N,L2=N,... measured misses -> the capacity (elements or lines) that "
      "explains them")("sample-rate", po::value(&sample_rate),
                       "approximate instead: SHARDS at this fixed rate (e.g. 0.01)")(
      "sample-size", po::value(&sample_size),
      "approximate instead: SHARDS tracking at most this many ids (fixed size)")(
      "sample-error",
      "with --sample-*: run the exact analysis too and report the miss-ratio curve's mean "
      "absolute error")("json", "print JSON")("csv", "print CSV")(
      "histogram-csv", po::value(&hist_csv), "write the histograms (exact < 64, log2 bins beyond)")(
      "profile-csv", po::value(&prof_csv), "write the profiles (each sweep in 100 steps)")(
      "mrc-csv", po::value(&mrc_csv),
      "write the miss-ratio curves (capacity -> misses, miss ratio; exact, or the estimate when "
      "sampling)")("out", po::value(&out_dir),
                   "write analyze.{csv,json}, histogram.csv, profile.csv, run.json")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("input", -1);
  po::variables_map vm;
  if (!ParseOptions(args,
                    "analyze INPUT... [--orderings ori,bfs,rdr] [--iterations K] [--json|--csv]",
                    "Exact LRU reuse distances (element = vertex id, line = address / line size; "
                    "each thread's stream on its own): accesses, cold, distinct, the exact sum and "
                    "mean, quantiles, modelled misses per cache level (fully associative LRU) and "
                    "the paper's equation-2 cost. Several meshes x --orderings print the paper's "
                    "Table 2. With --sample-rate or --sample-size: a SHARDS estimate instead.",
                    desc, pos, vm))
    return 0;
  Granularity gran;
  std::string gran_note;  // the default chosen for a foreign trace, said under the table
  ExternalFormat fmt = ExternalFormat::kText;
  std::vector<CacheLevel> levels, inverse;
  std::vector<double> qs;
  try {
    if (!measured.empty()) inverse = ParseCacheSpec(measured);
    if (!format.empty()) fmt = ParseExternalFormat(format);
    if (!granularity.empty()) {
      gran = ParseGranularity(granularity);
    } else if (format.empty()) {
      gran = Granularity::kBoth;
    } else {
      // An element model of 66-byte nodes over raw addresses means nothing: lines by default.
      const bool addresses = fmt == ExternalFormat::kLackey || fmt == ExternalFormat::kParda ||
                             fmt == ExternalFormat::kU32 || fmt == ExternalFormat::kU64;
      gran = addresses ? Granularity::kLine : Granularity::kElement;
      gran_note = std::string("granularity ") + GranularityName(gran) + " for --format " + format +
                  " (" +
                  (addresses ? "values are addresses; --granularity element treats them as ids"
                             : "values are ids; --granularity line treats them as addresses") +
                  ")";
    }
    levels = ParseCacheSpec(cache);
    for (const std::string& q : SplitList(quantiles)) {
      size_t used = 0;
      const double v = std::stod(q, &used);
      if (used != q.size() || !(v >= 0 && v <= 100))
        throw std::invalid_argument("quantile '" + q + "'");
      qs.push_back(v / 100);
    }
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
  if (iterations < 1 || iterations > 100000) throw po::error("--iterations must be 1..100000");
  if (threads < 1 || threads > 255) throw po::error("--threads must be 1..255");
  if (line_bytes == 0 || (line_bytes & (line_bytes - 1)))
    throw po::error("--line-bytes must be a power of two");
  if (element_bytes == 0) throw po::error("--element-bytes must be positive");
  const bool sampling = vm.count("sample-rate") || vm.count("sample-size");
  if (vm.count("sample-rate") && vm.count("sample-size"))
    throw po::error("--sample-rate and --sample-size exclude each other");
  if (vm.count("sample-rate") && !(sample_rate > 0 && sample_rate <= 1))
    throw po::error("--sample-rate must be in (0, 1]");
  if (vm.count("sample-size") && sample_size == 0) throw po::error("--sample-size must be >= 1");
  if (vm.count("sample-error") && !sampling)
    throw po::error("--sample-error needs --sample-rate or --sample-size");
  if (vm.count("instructions") && fmt != ExternalFormat::kLackey)
    throw po::error("--instructions applies to --format lackey");
  CheckOneFormat(vm);
  for (const std::string* f : {&hist_csv, &prof_csv, &mrc_csv})
    if (!f->empty()) CheckWritable(*f);
  if (!out_dir.empty()) PrepareOutDir(out_dir);
  const std::vector<std::string> ords = SplitList(orderings);
  CheckOrderings(ords);
  const TriangleOrder tri_order = TriangleOrderOption(triangle_order);
  const Progress progress(vm.count("quiet") > 0);
  auto common = [&](TraceAnalysisOptions& o) {
    o.granularity = gran;
    o.line_bytes = line_bytes;
    o.exact = !sampling || vm.count("sample-error");
    o.sample = sampling;
    o.shards.rate = sampling && !sample_size ? sample_rate : 1;
    o.shards.s_max = sample_size;
    o.shards.seed = seed;
  };

  std::vector<Job> jobs;
  for (const std::string& in : inputs) {
    if (format.empty() && in != "-" && IsMesh(in)) {
      for (const std::string& ord : ords) {
        Mesh m = LayOut(in, ord, seed, tri_order, progress);
        const SmoothOptions so = TraceSweeps(iterations, threads, mode);
        TraceAnalysisOptions o;
        common(o);
        o.threads = threads;
        o.dense_elements = static_cast<uint64_t>(m.NumVertices());
        o.line_base = AddressCanonicalizer::kCanonicalBase / line_bytes;
        if (so.mode == UpdateMode::kGaussSeidel)
          for (uint64_t n : AccessesPerSweep(m, threads))
            o.iteration_lengths.push_back(std::vector<uint64_t>(iterations, n));
        for (uint64_t n : RefsPerSweep(m, threads, so.mode))
          o.line_iteration_lengths.push_back(std::vector<uint64_t>(iterations, n));
        Job j{in, ord, m.NumVertices(), iterations, std::make_unique<TraceAnalysis>(o), {}};
        // Each thread moves its static share of the interior list once a sweep.
        for (int t = 0; t < threads; ++t) {
          int64_t b = 0, e = 0;
          smoother_detail::StaticRange(static_cast<int64_t>(m.interior.size()), threads, t, &b, &e);
          j.moves.push_back(static_cast<uint64_t>(e - b) * static_cast<uint64_t>(iterations));
        }
        progress.Say("analysing " + std::to_string(iterations) + " sweep(s) of " + in + " in " +
                     ord + " order");
        const auto t0 = Clock::now();
        AnalysisSink sink{j.analysis.get()};
        Smooth(m, so, sink);
        j.analysis->Finish();
        progress.Say("done in " + Fixed(Since(t0), 2) + " s");
        jobs.push_back(std::move(j));
      }
    } else if (format.empty() && in != "-") {
      TraceReader r(in);
      const TraceHeader& h = r.header();
      TraceAnalysisOptions o;
      common(o);
      o.threads = static_cast<int>(h.threads);
      o.workers = threads;
      // Each thread's sweep lengths (for the profile) and the vertex count are in the header.
      o.iteration_lengths.assign(h.threads, {});
      o.line_iteration_lengths.assign(h.threads, {});
      for (const std::vector<uint64_t>& sweep : h.sweep_elements)
        for (uint32_t t = 0; t < h.threads; ++t) o.iteration_lengths[t].push_back(sweep[t]);
      for (const std::vector<uint64_t>& sweep : h.sweep_records)
        for (uint32_t t = 0; t < h.threads; ++t) o.line_iteration_lengths[t].push_back(sweep[t]);
      // Direct arrays for ids below the vertex count (0, unknown: the hash table); never more
      // than the records, so a header's count cannot make memory exceed what the file holds.
      o.dense_elements = std::min<uint64_t>(h.vertices, h.records);
      o.line_base = AddressCanonicalizer::kCanonicalBase / line_bytes;  // traces are canonical
      Job j{in,
            h.ordering,
            static_cast<int64_t>(h.vertices),
            static_cast<int>(h.iteration_starts.size()),
            std::make_unique<TraceAnalysis>(o),
            std::vector<uint64_t>(h.threads, 0)};
      progress.Say("analysing trace " + in + " (" + Grouped(static_cast<long long>(h.records)) +
                   " accesses" + (threads > 1 ? ", " + std::to_string(threads) + " threads" : "") +
                   ")");
      const auto t0 = Clock::now();
      uint64_t done = 0;
      std::vector<TraceRecord> batch;
      while (r.Next(&batch, 1 << 18)) {
        for (const TraceRecord& rec : batch) {
          if (rec.thread >= h.threads)
            throw InputError(in, 0,
                             "record " + std::to_string(done) + " has thread " +
                                 std::to_string(rec.thread) + " beyond the header's " +
                                 std::to_string(h.threads));
          if (rec.kind < kElementKinds) j.analysis->AddElement(rec.thread, rec.vertex);
          if (rec.kind == static_cast<uint8_t>(AccessKind::kCoordWrite)) ++j.moves[rec.thread];
          j.analysis->AddAccess(rec.thread, rec.address, rec.size);
          ++done;
        }
        progress.Fraction("analysing", static_cast<double>(done) / h.records, Since(t0));
      }
      j.analysis->Finish();
      jobs.push_back(std::move(j));
    } else {
      TraceAnalysisOptions o;
      common(o);
      o.workers = threads;
      const uint64_t len = ExternalTraceLength(in, fmt);
      if (len) o.iteration_lengths = o.line_iteration_lengths = {{len}};
      Job j{in, "", 0, len ? 1 : 0, std::make_unique<TraceAnalysis>(o), {}};
      progress.Say("analysing " + in + " as " + (format.empty() ? "text" : format) +
                   (len ? " (" + Grouped(static_cast<long long>(len)) + " accesses)" : ""));
      TraceAnalysis* a = j.analysis.get();
      const auto t0 = Clock::now();
      uint64_t seen = 0;
      ReadExternalTrace(
          in, fmt,
          [&](uint64_t v, uint32_t size) {
            a->AddElement(0, v);
            a->AddAccess(0, v, size);
            if ((++seen & 0xFFFFF) == 0) {
              if (len)
                progress.Fraction("analysing", static_cast<double>(seen) / len, Since(t0));
              else if ((seen & 0x3FFFFFF) == 0)
                progress.Say(Grouped(static_cast<long long>(seen)) + " accesses so far");
            }
          },
          vm.count("instructions") > 0);
      a->Finish();
      jobs.push_back(std::move(j));
    }
  }

  // One row per input x ordering x thread x granularity; `t` exact/full precision (CSV, JSON),
  // `th` for people.
  std::vector<std::string> head;
  if (sampling) {
    head = {"input", "ordering", "thread",  "granularity", "sampling",     "rate",
            "seed",  "accesses", "samples", "cold_est",    "distinct_est", "mean_est"};
    for (double q : qs)
      head.push_back("q" + Fixed(100 * q, q * 100 == std::floor(q * 100) ? 0 : 1) + "_est");
    for (const CacheLevel& l : levels) head.push_back(l.name + "_misses_est");
    head.push_back("mrc_mae");
  } else {
    head = {"input", "ordering", "thread", "granularity", "accesses", "per_vertex_sweep",
            "cold",  "distinct", "sum",    "mean"};
    for (double q : qs)
      head.push_back("q" + Fixed(100 * q, q * 100 == std::floor(q * 100) ? 0 : 1));
    for (const CacheLevel& l : levels) head.push_back(l.name + "_misses");
    if (levels.size() == 3) head.insert(head.end(), {"cost_cycles_low", "cost_cycles_high"});
    for (const CacheLevel& l : inverse)
      head.push_back(l.name + "_capacity_for_" + std::to_string(l.bytes));
  }
  Table t(head), th(head);
  Table hist({"input", "ordering", "thread", "granularity", "lo", "hi", "count"});
  Table prof({"input", "ordering", "thread", "granularity", "iteration", "step", "accesses", "cold",
              "mean"});
  Table mrc({"input", "ordering", "thread", "granularity", "capacity", "misses", "accesses",
             "miss_ratio", "estimated"});
  // The side tables only when written (the curve has a point per distinct distance).
  const bool want_hist = !hist_csv.empty() || !out_dir.empty();
  const bool want_prof = !prof_csv.empty() || !out_dir.empty();
  const bool want_mrc = !mrc_csv.empty();  // not in --out: a point per distinct distance
  for (const Job& j : jobs)
    for (int tr = 0; tr < j.analysis->threads(); ++tr)
      for (int g = 0; g < 2; ++g) {
        const StreamAnalysis* s = g == 0 ? j.analysis->element(tr) : j.analysis->line(tr);
        if (!s) continue;
        const char* gname = g == 0 ? "element" : "line";
        const uint32_t bytes = g == 0 ? element_bytes : line_bytes;
        const std::vector<std::string> id = {j.input, j.ordering, std::to_string(tr), gname};
        auto with = [&id](std::vector<std::string> rest) {
          std::vector<std::string> r = id;
          r.insert(r.end(), rest.begin(), rest.end());
          return r;
        };
        if (sampling) {
          t.AddRow(SampledRow(j, tr, gname, *s, qs, levels, bytes, false));
          th.AddRow(SampledRow(j, tr, gname, *s, qs, levels, bytes, true));
          const Shards& e = *s->shards;
          if (!want_mrc) continue;
          mrc.AddRow(with({"0", Full(e.MissRatio(0) * e.accesses()), std::to_string(e.accesses()),
                           Full(e.MissRatio(0)), "1"}));
          for (const auto& kv : e.weights()) {
            const double r = e.MissRatio(kv.first + 1);
            mrc.AddRow(with({std::to_string(kv.first + 1), Full(r * e.accesses()),
                             std::to_string(e.accesses()), Full(r), "1"}));
          }
          continue;
        }
        t.AddRow(StreamRow(j, tr, gname, *s, qs, levels, bytes, inverse, false));
        th.AddRow(StreamRow(j, tr, gname, *s, qs, levels, bytes, inverse, true));
        const ReuseHistogram& h = s->hist;
        if (want_hist)
          for (const auto& b : h.Binned(64))
            hist.AddRow(
                with({std::to_string(b.lo), std::to_string(b.hi), std::to_string(b.count)}));
        if (want_prof)
          for (const auto& st : s->profile.steps())
            prof.AddRow(with({std::to_string(st.iteration), std::to_string(st.step),
                              std::to_string(st.accesses), std::to_string(st.cold),
                              st.accesses > st.cold ? Full(st.mean()) : ""}));
        if (want_mrc)
          for (const MrcPoint& p : MissRatioCurve(h))
            mrc.AddRow(with(
                {std::to_string(p.capacity), std::to_string(p.misses), std::to_string(h.accesses()),
                 h.accesses()
                     ? Full(static_cast<double>(p.misses) / static_cast<double>(h.accesses()))
                     : "",
                 "0"}));
      }
  if (vm.count("json")) {
    std::printf("%s", t.Json().c_str());
  } else if (vm.count("csv")) {
    std::printf("%s", t.Csv().c_str());
  } else {
    std::printf("%s", th.Aligned().c_str());
    if (sampling)
      std::printf(
          "(SHARDS estimates, seed %llu: distances scaled by 1/rate; misses = accesses x the "
          "estimated miss ratio at each capacity; mrc_mae = mean |exact - estimated| miss ratio "
          "over every capacity, with --sample-error)\n",
          static_cast<unsigned long long>(seed));
    else
      std::printf(
          "(distances in %s; sum exact; misses: fully associative LRU, %s, elements of %u B, "
          "lines of %u B)\n",
          "distinct elements or lines", cache.c_str(), element_bytes, line_bytes);
    if (!gran_note.empty()) std::printf("(%s)\n", gran_note.c_str());
  }
  // A trace without sweeps (a foreign one of unknown length) has no profile: say so rather than
  // write an empty file.
  const bool no_profile = want_prof && prof.Rows() == 0;
  if (no_profile)
    std::fprintf(stderr,
                 "meshreuse: note: no profile written: the input has no sweeps (a foreign trace "
                 "read from a stream has no known length to cut into time steps)\n");
  if (!hist_csv.empty()) WriteText(hist_csv, hist.Csv());
  if (!prof_csv.empty() && !no_profile) WriteText(prof_csv, prof.Csv());
  if (!mrc_csv.empty()) WriteText(mrc_csv, mrc.Csv());
  if (!out_dir.empty()) {
    WriteText(out_dir + "/analyze.csv", t.Csv());
    WriteText(out_dir + "/analyze.json", t.Json());
    WriteText(out_dir + "/histogram.csv", hist.Csv());
    if (!no_profile) WriteText(out_dir + "/profile.csv", prof.Csv());
    WriteText(out_dir + "/run.json",
              "{\n" + RunJsonHeader("meshreuse analyze") + "  \"config\": {\"orderings\": " +
                  JsonString(orderings) + ", \"seed\": " + std::to_string(seed) +
                  ", \"iterations\": " + std::to_string(iterations) + ", \"threads\": " +
                  std::to_string(threads) + ", \"granularity\": " + JsonString(granularity) +
                  ", \"granularity_used\": " + JsonString(GranularityName(gran)) + ", \"cache\": " +
                  JsonString(cache) + ", \"element_bytes\": " + std::to_string(element_bytes) +
                  ", \"line_bytes\": " + std::to_string(line_bytes) +
                  ", \"format\": " + JsonString(format) +
                  ", \"sample_rate\": " + (vm.count("sample-rate") ? Full(sample_rate) : "null") +
                  ", \"sample_size\": " + std::to_string(sample_size) +
                  ", \"triangle_order\": " + JsonString(triangle_order) + "}\n}\n");
    progress.Say("wrote " + out_dir + "/{analyze.csv,analyze.json,histogram.csv," +
                 (no_profile ? "" : "profile.csv,") + "run.json}");
  }
  return 0;
}

}  // namespace meshreuse::cli
