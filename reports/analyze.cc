// The analyze runner; see analyze.h.
#include "reports/analyze.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/schedule.h"
#include "reports/chunk_summary.h"
#include "reports/chunk_threads.h"
#include "reports/inputs.h"
#include "reports/rank_locality.h"
#include "reports/run_info.h"
#include "tracer/access_stream.h"
#include "tracer/trace_formats.h"

namespace meshreuse {

namespace {

// %.17g: the double exactly (a mean of exact integers, to within an ulp of the quotient).
std::string Full(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string Cap(uint64_t c) { return c == kInfiniteCapacity ? "inf" : std::to_string(c); }

std::string QuantileName(double q) {
  return "q" + Fixed(100 * q, q * 100 == std::floor(q * 100) ? 0 : 1);
}

ReuseOptions Options(const AnalyzeConfig& cfg, Granularity g) {
  ReuseOptions o;
  o.granularity = g;
  o.line_bytes = cfg.line_bytes;
  o.exact = !cfg.sample || cfg.sample_error;
  o.sample = cfg.sample;
  o.shards = cfg.shards;
  o.profile = cfg.profile;
  return o;
}

// Per vertex, the reuse distances of its element touches (for --vtk).
class VertexReuse : public AccessConsumer {
 public:
  explicit VertexReuse(int32_t vertices)
      : sd_(static_cast<uint64_t>(vertices)),
        sum_(vertices, 0),
        max_(vertices, 0),
        finite_(vertices, 0),
        cold_(vertices, 0) {}
  void Begin(const StreamInfo&) override {}
  void Consume(const Access* a, size_t n) override {
    for (size_t i = 0; i < n; ++i) {
      if (a[i].element == Access::kNoElement) continue;
      const uint64_t v = a[i].element, d = sd_.Access(v);
      if (d == StackDistance::kCold) {
        ++cold_[v];
      } else {
        sum_[v] += static_cast<double>(d), max_[v] = std::max<double>(max_[v], d), ++finite_[v];
      }
    }
  }
  std::vector<VtkField> Fields() const {
    VtkField mean{"reuse_distance_mean", sum_}, mx{"reuse_distance_max", max_},
        cold{"cold_touches", cold_};
    for (size_t v = 0; v < sum_.size(); ++v) mean.values[v] = finite_[v] ? sum_[v] / finite_[v] : 0;
    return {mean, mx, cold};
  }

 private:
  StackDistance sd_;
  std::vector<double> sum_, max_, finite_, cold_;
};

}  // namespace

// Progress of a file as "analysing: 42% ..." at most every 2 s.
ProgressFn FileProgress(const Log& log) {
  auto last = std::make_shared<double>(-1);
  auto t0 =
      std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  return [&log, last, t0](double done) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - *t0).count();
    if (s - *last < 2.0) return;
    *last = s;
    char b[120];
    if (done > 0)
      std::snprintf(b, sizeof b, "analysing: %.0f%% (%.1f s, about %.1f s left)", 100 * done, s,
                    s * (1 - done) / done);
    else
      std::snprintf(b, sizeof b, "analysing: %.1f s so far", s);
    log.Say(b);
  };
}

SmoothOptions AnalyzeSweeps(const AnalyzeConfig& cfg) {
  return ExactSweeps(cfg.iterations, cfg.threads, cfg.mode);
}

std::vector<double> ParseQuantiles(const std::string& list) {
  std::vector<double> qs;
  size_t i = 0;
  while (i <= list.size()) {
    const size_t j = std::min(list.find(',', i), list.size());
    const std::string q = list.substr(i, j - i);
    i = j + 1;
    if (q.empty()) continue;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(q.c_str(), &end);
    if (!end || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      throw UsageError("--quantiles: '" + q + "' is not a number");
    if (!(v >= 0 && v <= 100))
      throw UsageError("--quantiles: " + q +
                       " is not a percentage in 0..100 (100 is the largest "
                       "distance, 50 the median)");
    qs.push_back(v / 100);
  }
  if (qs.empty()) throw UsageError("--quantiles is empty");
  return qs;
}

void CheckAnalyzeConfig(const AnalyzeConfig& cfg) {
  if (cfg.inputs.empty()) throw UsageError("no input given");
  if (cfg.chunk && cfg.merge) throw UsageError("--chunk and --merge exclude each other");
  if (cfg.transport && (cfg.chunk || cfg.merge))
    throw UsageError("a distributed run cuts the trace by rank: no --chunk or --merge");
  if (cfg.chunk && cfg.summary_out.empty()) throw UsageError("--chunk needs --summary-out FILE");
  if (!cfg.chunk && !cfg.summary_out.empty()) throw UsageError("--summary-out needs --chunk r/P");
  if (cfg.merge && !cfg.format.empty())
    throw UsageError("--merge reads summaries: the format was given to the chunk runs");
  if (cfg.merge && (cfg.sample || !cfg.vtk.empty() || cfg.granularity))
    throw UsageError(
        "--merge: the analysis was chosen by the chunk runs (no --sample-*, --vtk "
        "or --granularity here)");
  if (!cfg.format.empty()) ParseTraceFormat(cfg.format);
  if (cfg.ranks > 0 && (cfg.chunk || cfg.merge || cfg.transport || !cfg.format.empty() ||
                        !cfg.vtk.empty() || cfg.threads != 1))
    throw UsageError(
        "--ranks analyses each rank's part of a mesh (one stream per rank): no --chunk, "
        "--merge, --format, --vtk or --threads with it");
  CheckRankParts(cfg.ranks, cfg.partition, cfg.inputs);
  if (cfg.orderings.empty()) throw UsageError("no ordering given");
  for (const std::string& o : cfg.orderings) CheckOrderingSpec(o);
  if (cfg.iterations < 1 || cfg.iterations > kMaxStreamSweeps)
    throw UsageError("--iterations must be 1..65536");
  if (cfg.threads < 1 || cfg.threads > kMaxThreads)
    throw UsageError("--threads must be 1.." + std::to_string(kMaxThreads));
  CheckStreamSweeps(cfg.iterations, cfg.threads);
  if (cfg.line_bytes == 0 || (cfg.line_bytes & (cfg.line_bytes - 1)))
    throw UsageError("--line-bytes must be a power of two");
  if (cfg.element_bytes == 0) throw UsageError("--element-bytes must be positive");
  if (cfg.instructions &&
      (cfg.format.empty() || ParseTraceFormat(cfg.format).syntax != TraceSyntax::kLackey))
    throw UsageError("--instructions applies to --format lackey");
  for (const CacheLevel& l : cfg.cache.levels)
    if (l.name == "I1")
      throw UsageError(
          "--cache: I1 is simulate's instruction cache; the miss model's levels are "
          "unified (with --instructions the I lines are accesses like any other)");
}

AnalyzeResult RunAnalyze(const AnalyzeConfig& cfg, const Log& log) {
  CheckAnalyzeConfig(cfg);
  if (cfg.merge) return MergeSummaries(cfg, log);
  if (cfg.transport) return RunDistributed(cfg, *cfg.transport, log);
  if (cfg.chunk) throw std::logic_error("RunAnalyze: a chunk run is RunChunk");
  AnalyzeResult r;
  const TraceFormat* fmt = cfg.format.empty() ? nullptr : &ParseTraceFormat(cfg.format);
  if (cfg.granularity) {
    r.granularity = *cfg.granularity;
  } else if (fmt) {
    // An element model of 66-byte nodes over raw addresses means nothing: lines by default.
    r.granularity = fmt->addresses ? Granularity::kLine : Granularity::kElement;
    r.granularity_note =
        std::string("granularity ") + GranularityName(r.granularity) + " for --format " +
        cfg.format + " (" +
        (fmt->addresses ? "values are addresses; --granularity element treats them as ids"
                        : "values are ids; --granularity line treats them as addresses") +
        ")";
  }
  const ReuseOptions opt = Options(cfg, r.granularity);
  for (const std::string& in : cfg.inputs) {
    const InputKind kind = fmt ? InputKind::kText : ClassifyInput(in);
    if (kind == InputKind::kMesh && cfg.ranks > 0) {
      for (const std::string& ord : cfg.orderings) {
        RankLocalityConfig rc;
        rc.mesh = in, rc.ranks = cfg.ranks, rc.partition = cfg.partition, rc.ordering = ord;
        rc.placement = cfg.cut_placement;
        rc.seed = cfg.seed, rc.sweeps = AnalyzeSweeps(cfg);
        for (auto& a : AnalyzeRankParts(rc, opt, log)) r.runs.push_back(std::move(a));
      }
      continue;
    }
    if (kind == InputKind::kMesh) {
      for (const std::string& ord : cfg.orderings) {
        Mesh m = LayOut(in, ord, cfg.seed, cfg.triangle_order, log);
        auto a = std::make_unique<ReuseAnalysis>(opt);
        log.Say("analysing " + std::to_string(cfg.iterations) + " sweep(s) of " + in + " in " +
                ord + " order");
        const auto t0 = std::chrono::steady_clock::now();
        if (!cfg.vtk.empty()) {  // the layout before the sweeps move it, and where each came from
          const Mesh laid = m.Clone();
          const Permutation p = ComputeOrdering(ord, LoadMesh(in, Log()), cfg.seed);
          VertexReuse vr(m.NumVertices());
          FanOut both({a.get(), &vr});
          StreamMesh(m, AnalyzeSweeps(cfg), in, ParseOrderingSpec(ord).label, both);
          VtkField rank{"rank", std::vector<double>(laid.NumVertices())},
              orig{"original_id", rank.values};
          for (int32_t v = 0; v < laid.NumVertices(); ++v)
            rank.values[v] = v, orig.values[v] = p.OldOf(v);
          std::vector<VtkField> fields = {rank, orig};
          for (VtkField& f : vr.Fields()) fields.push_back(std::move(f));
          WriteVtk(laid, cfg.vtk, fields);
          log.Say("wrote " + cfg.vtk);
        } else {
          StreamMesh(m, AnalyzeSweeps(cfg), in, ParseOrderingSpec(ord).label, *a);
        }
        log.Say(
            "done in " +
            Fixed(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2) +
            " s");
        r.runs.push_back(std::move(a));
      }
      continue;
    }
    if (cfg.threads > 1 && CanAnalyzeInChunks(cfg, in)) {
      AnalyzeConfig one = cfg;
      one.inputs = {in};
      log.Say("analysing " + in + " in " + std::to_string(cfg.threads) + " chunks on " +
              std::to_string(cfg.threads) + " threads, each reading its own");
      AnalyzeResult part = AnalyzeChunksOnThreads(one, cfg.threads, log);
      r.runs.push_back(std::move(part.runs.at(0)));
      r.ranks.insert(r.ranks.end(), part.ranks.begin(), part.ranks.end());
      continue;
    }
    ReuseOptions o = opt;
    o.workers = cfg.threads;
    auto a = std::make_unique<ReuseAnalysis>(o);
    if (kind == InputKind::kTrace) {
      log.Say("analysing trace " + in +
              (cfg.threads > 1 ? " (" + std::to_string(cfg.threads) + " threads)" : ""));
      StreamTraceFile(in, *a, FileProgress(log));
    } else {
      const TraceFormat& f = fmt ? *fmt : ParseTraceFormat("text");
      const uint64_t len = ForeignTraceLength(in, f);
      log.Say("analysing " + in + " as " + f.name +
              (len ? " (" + Grouped(static_cast<long long>(len)) + " accesses)" : ""));
      StreamForeignTrace(in, f, cfg.instructions, *a, FileProgress(log));
    }
    r.runs.push_back(std::move(a));
  }
  return r;
}

Table AnalyzeTable(const AnalyzeResult& r, const AnalyzeConfig& cfg, bool human) {
  const std::vector<double>& qs = cfg.quantiles;
  const std::vector<CacheLevel>& levels = cfg.cache.levels;
  const bool cost = cfg.cache.has_latencies();
  std::vector<std::string> head;
  if (cfg.sample) {
    head = {"input", "ordering", "thread",  "granularity", "sampling",     "rate",
            "seed",  "accesses", "samples", "cold_est",    "distinct_est", "mean_est"};
    for (double q : qs) head.push_back(QuantileName(q) + "_est");
    for (const CacheLevel& l : levels) head.push_back(l.name + "_misses_est");
    head.push_back("mrc_mae");
    // The error where it matters: at each modelled level's capacity (a mean over every capacity
    // hides a large one at the small capacities, where sampled distances are coarsest).
    for (const CacheLevel& l : levels) head.push_back(l.name + "_miss_ratio_error");
  } else {
    head = {"input", "ordering", "thread", "granularity", "accesses", "per_vertex_sweep",
            "cold",  "distinct", "sum",    "mean"};
    for (double q : qs) head.push_back(QuantileName(q));
    for (const CacheLevel& l : levels) head.push_back(l.name + "_misses");
    if (cost) head.insert(head.end(), {"cost_cycles_low", "cost_cycles_high"});
    for (const CacheLevel& l : cfg.inverse)
      head.push_back(l.name + "_capacity_for_" + std::to_string(l.bytes));
  }
  Table t(head);
  auto num = [human](double v, int d) { return human ? Fixed(v, d) : Full(v); };
  for (const auto& a : r.runs)
    for (int th = 0; th < a->threads(); ++th)
      for (Granularity g : {Granularity::kElement, Granularity::kLine}) {
        const StreamAnalysis* s = a->stream(th, g);
        if (!s) continue;
        const uint32_t bytes = g == Granularity::kElement ? cfg.element_bytes : cfg.line_bytes;
        std::vector<std::string> row = {a->info().input, a->info().ordering, std::to_string(th),
                                        GranularityName(g)};
        if (cfg.sample) {
          const Shards& e = *s->shards;
          const bool finite = !e.weights().empty();
          row.insert(row.end(), {e.options().s_max ? "fixed-size" : "fixed-rate", num(e.rate(), 6),
                                 std::to_string(e.options().seed), std::to_string(e.accesses()),
                                 std::to_string(e.samples()), num(e.cold_weight(), 0),
                                 num(e.distinct_estimate(), 0), finite ? num(e.Mean(), 1) : ""});
          for (double q : qs) row.push_back(finite ? std::to_string(e.Quantile(q)) : "");
          for (const CacheLevel& l : levels)
            row.push_back(num(e.MissRatio(l.bytes / bytes) * static_cast<double>(e.accesses()), 0));
          row.push_back(s->exact ? num(MrcMeanAbsoluteError(s->hist, e), 6) : "");
          for (const CacheLevel& l : levels) {
            if (!s->exact || !s->hist.accesses()) {
              row.push_back("");
              continue;
            }
            // Estimated minus exact miss ratio at the level's capacity, signed.
            const uint64_t c = l.bytes / bytes;
            const double exact = static_cast<double>(s->hist.cold() + s->hist.CountAtLeast(c)) /
                                 static_cast<double>(s->hist.accesses());
            row.push_back(num(e.MissRatio(c) - exact, 6));
          }
          t.AddRow(row);
          continue;
        }
        const ReuseHistogram& h = s->hist;
        const uint64_t moves = a->moves(th);
        row.insert(row.end(),
                   {std::to_string(h.accesses()),
                    !moves  ? ""
                    : human ? Fixed(static_cast<double>(h.accesses()) / moves, 2)
                            : ExactNumber(static_cast<double>(h.accesses()) / moves),
                    std::to_string(h.cold()), std::to_string(s->distinct()),
                    h.finite() ? ToDecimal(h.sum()) : "", h.finite() ? num(h.mean(), 1) : ""});
        for (double q : qs) row.push_back(h.finite() ? std::to_string(h.Quantile(q)) : "");
        const std::vector<LevelMisses> miss = ModelMisses(h, levels, bytes);
        std::vector<uint64_t> counts;
        for (const LevelMisses& m : miss) {
          row.push_back(std::to_string(m.misses));
          counts.push_back(m.misses);
        }
        if (cost) {
          const std::optional<CostRange> c = AdditionalCycles(counts, cfg.cache);
          row.push_back(Fixed(c->low, 0));
          row.push_back(Fixed(c->high, 0));
        }
        for (const CacheLevel& l : cfg.inverse) row.push_back(Cap(CapacityForMisses(h, l.bytes)));
        t.AddRow(row);
      }
  return t;
}

Table HistogramTable(const AnalyzeResult& r) {
  Table t(ReuseAnalysis::HistogramColumns());
  for (const auto& a : r.runs) a->AppendHistogramRows(&t);
  return t;
}

Table ProfileTable(const AnalyzeResult& r) {
  Table t(ReuseAnalysis::ProfileColumns());
  for (const auto& a : r.runs) a->AppendProfileRows(&t);
  return t;
}

Table MrcTable(const AnalyzeResult& r) {
  Table t(ReuseAnalysis::MrcColumns());
  for (const auto& a : r.runs) a->AppendMrcRows(&t);
  return t;
}

std::vector<std::string> AnalyzeNotes(const AnalyzeResult& r, const AnalyzeConfig& cfg) {
  std::vector<std::string> n;
  if (cfg.sample)
    n.push_back(
        "(SHARDS estimates, seed " + std::to_string(cfg.shards.seed) +
        ": distances scaled by 1/rate; misses = accesses x the estimated miss ratio at "
        "each capacity; mrc_mae = mean |exact - estimated| miss ratio over every "
        "capacity, LEVEL_miss_ratio_error = estimated - exact at the level's capacity, "
        "with --sample-error" +
        (cfg.shards.exact_below
             ? "; distances below " + std::to_string(cfg.shards.exact_below) + " counted exactly"
             : std::string()) +
        ")");
  else
    n.push_back(
        "(distances in distinct elements or lines; sum exact; misses: fully associative "
        "LRU, " +
        cfg.cache.text + ", elements of " + std::to_string(cfg.element_bytes) + " B, lines of " +
        std::to_string(cfg.line_bytes) + " B" +
        (cfg.cache.has_latencies()
             ? ""
             : "; no cost columns: the cache spec gives no latencies (NAME=SIZE@CYCLES, "
               "mem@CYCLES)") +
        ")");
  if (!r.granularity_note.empty()) n.push_back("(" + r.granularity_note + ")");
  return n;
}

Json RankStatsJson(const std::vector<RankStats>& ranks) {
  Json a = Json::array();
  for (const RankStats& r : ranks)
    a.push_back({{"rank", r.rank},
                 {"analyse_cpu_s", r.analyse_cpu},
                 {"stream_cpu_s", r.stream_cpu},
                 {"resolve_cpu_s", r.resolve_cpu},
                 {"reduce_cpu_s", r.reduce_cpu},
                 {"wall_s", r.wall},
                 {"records", r.records},
                 {"accesses", r.accesses},
                 {"distinct", r.distinct},
                 {"stack_ids_in", r.stack_ids_in},
                 {"stack_ids_sent", r.stack_ids_sent},
                 {"bytes_sent", r.bytes_sent},
                 {"peak_rss_bytes", r.peak_rss_bytes},
                 {"histogram_bytes", r.histogram_bytes},
                 {"dense_histogram_bytes", r.dense_histogram_bytes},
                 {"pairs", r.pairs},
                 {"pairs_added", r.pairs_added},
                 {"merge_cpu_s", r.merge_cpu}});
  return a;
}

Json AnalyzeConfigJson(const AnalyzeConfig& cfg, const AnalyzeResult& r) {
  Json j;
  j["inputs"] = cfg.inputs;
  j["format"] = cfg.format;
  j["orderings"] = cfg.orderings;
  j["seed"] = cfg.seed;
  j["ordering_seeds"] = OrderingSeedsJson(cfg.orderings, cfg.seed);
  j["iterations"] = cfg.iterations;
  j["threads"] = cfg.threads;
  j["mode"] = UpdateModeName(cfg.mode);
  j["triangle_order"] = TriangleOrderName(cfg.triangle_order);
  j["granularity"] = cfg.granularity ? GranularityName(*cfg.granularity) : "";
  j["granularity_used"] = GranularityName(r.granularity);
  j["quantiles"] = cfg.quantiles;
  j["cache"] = cfg.cache.text;
  j["element_bytes"] = cfg.element_bytes;
  j["line_bytes"] = cfg.line_bytes;
  j["sample_rate"] = cfg.sample && !cfg.shards.s_max ? Json(cfg.shards.rate) : Json(nullptr);
  j["sample_size"] = cfg.shards.s_max;
  j["sample_seed"] = cfg.shards.seed;
  j["sample_exact_below"] = cfg.shards.exact_below;
  return j;
}

}  // namespace meshreuse
