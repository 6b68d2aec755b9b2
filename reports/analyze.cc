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
#include "reports/chunks/chunk_threads.h"
#include "reports/chunks/distributed_analysis.h"
#include "reports/chunks/merge_summaries.h"
#include "reports/inputs.h"
#include "reports/run_info.h"
#include "reports/stream_source.h"
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

std::string QuantileName(double q) {
  return "q" + Fixed(100 * q, q * 100 == std::floor(q * 100) ? 0 : 1);
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
  if (cfg.ranks > 0 && (cfg.chunk || cfg.merge || cfg.transport || !cfg.format.empty() ||
                        !cfg.vtk.empty() || cfg.threads != 1))
    throw UsageError(
        "--ranks analyses each rank's part of a mesh (one stream per rank): no --chunk, "
        "--merge, --format, --vtk or --threads with it");
  cfg.Check();
  if (cfg.line_bytes == 0 || (cfg.line_bytes & (cfg.line_bytes - 1)))
    throw UsageError("--line-bytes must be a power of two");
  if (cfg.element_bytes == 0) throw UsageError("--element-bytes must be positive");
  for (const CacheLevel& l : cfg.cache.levels)
    if (l.name == "I1")
      throw UsageError(
          "--cache: I1 is simulate's instruction cache; the miss model's levels are "
          "unified (with --instructions the I lines are accesses like any other)");
}

namespace {

// The analyzer on every stream of the source: a ReuseAnalysis per stream (per rank's part), a
// trace file that can be cut analysed as chunks on threads, and --vtk's per-vertex distances.
class AnalyzeStreams : public StreamConsumer {
 public:
  AnalyzeStreams(const AnalyzeConfig& cfg, AnalyzeResult* r)
      : cfg_(cfg), r_(*r), opt_(cfg.Options(r->granularity)) {}
  std::string Verb() const override { return "analysing"; }
  AccessConsumer& Start(const StreamJob& job) override {
    ReuseOptions o = opt_;
    if (job.kind != InputKind::kMesh) o.workers = cfg_.threads;  // a trace read in batches
    r_.runs.push_back(std::make_unique<ReuseAnalysis>(o));
    ReuseAnalysis& a = *r_.runs.back();
    if (!job.mesh || cfg_.vtk.empty()) return a;
    // The layout before the sweeps move it, and where each vertex came from.
    laid_ = std::make_unique<Mesh>(job.mesh->Clone());
    reuse_ = std::make_unique<VertexReuse>(laid_->NumVertices());
    both_ = std::make_unique<FanOut>(std::vector<AccessConsumer*>{&a, reuse_.get()});
    return *both_;
  }
  void Finish(const StreamJob& job) override {
    if (!reuse_) return;
    const Permutation p = ComputeOrdering(*job.ordering, LoadMesh(job.input, Log()), cfg_.seed);
    VtkField rank{"rank", std::vector<double>(laid_->NumVertices())},
        orig{"original_id", rank.values};
    for (int32_t v = 0; v < laid_->NumVertices(); ++v)
      rank.values[v] = v, orig.values[v] = p.OldOf(v);
    std::vector<VtkField> fields = {rank, orig};
    for (VtkField& f : reuse_->Fields()) fields.push_back(std::move(f));
    if (cfg_.vtk.size() > 4 && cfg_.vtk.compare(cfg_.vtk.size() - 4, 4, ".vtu") == 0)
      WriteVtu(*laid_, cfg_.vtk, fields);
    else
      WriteVtk(*laid_, cfg_.vtk, fields);
    vtk_written_ = true;
    reuse_.reset(), both_.reset(), laid_.reset();
  }
  bool TakeTrace(const std::string& in, const Log& log) override {
    if (cfg_.threads <= 1 || !CanAnalyzeInChunks(cfg_, in)) return false;
    ReuseJob one = cfg_;
    one.inputs = {in};
    log.Say("analysing " + in + " in " + std::to_string(cfg_.threads) + " chunks on " +
            std::to_string(cfg_.threads) + " threads, each reading its own");
    AnalyzeResult part = AnalyzeChunksOnThreads(one, cfg_.threads, log);
    r_.runs.push_back(std::move(part.runs.at(0)));
    r_.ranks.insert(r_.ranks.end(), part.ranks.begin(), part.ranks.end());
    return true;
  }
  std::string Where() const override {
    return cfg_.threads > 1 ? " (" + std::to_string(cfg_.threads) + " threads)" : "";
  }
  bool vtk_written() const { return vtk_written_; }

 private:
  const AnalyzeConfig& cfg_;
  AnalyzeResult& r_;
  const ReuseOptions opt_;
  std::unique_ptr<Mesh> laid_;
  std::unique_ptr<VertexReuse> reuse_;
  std::unique_ptr<FanOut> both_;
  bool vtk_written_ = false;
};

}  // namespace

AnalyzeResult RunAnalyze(const AnalyzeConfig& cfg, const Log& log) {
  CheckAnalyzeConfig(cfg);
  if (cfg.merge) return MergeSummaries(cfg.inputs, cfg.profile, log);
  if (cfg.transport) return RunDistributed(cfg, *cfg.transport, log);
  if (cfg.chunk) throw std::logic_error("RunAnalyze: a chunk run is RunChunk");
  AnalyzeResult r;
  if (const TraceFormat* fmt = cfg.Format(); cfg.granularity) {
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
  AnalyzeStreams streams(cfg, &r);
  ForEachStream(cfg, streams, log);
  if (streams.vtk_written()) log.Say("wrote " + cfg.vtk);
  return r;
}

Table AnalyzeTable(const AnalyzeResult& r, const AnalyzeConfig& cfg, bool human) {
  const std::vector<double>& qs = cfg.quantiles;
  const std::vector<CacheLevel>& levels = cfg.cache.levels;
  const bool cost = cfg.cache.has_latencies();
  std::vector<std::string> head;
  if (cfg.sample) {
    head = {"input",    "ordering", "thread",      "granularity", "sampling",     "rate",    "seed",
            "accesses", "samples",  "ids_sampled", "cold_est",    "distinct_est", "mean_est"};
    for (double q : qs) head.push_back(QuantileName(q) + "_est");
    for (const CacheLevel& l : levels) head.push_back(l.name + "_misses_est");
    for (const CacheLevel& l : levels) head.push_back(l.name + "_misses_ci95");
    head.push_back("mrc_mae");
    // The error where it matters: at each modelled level's capacity (a mean over every capacity
    // hides a large one at the small capacities, where sampled distances are coarsest).
    for (const CacheLevel& l : levels) head.push_back(l.name + "_miss_ratio_error");
  } else {
    head = {"input", "ordering", "thread", "granularity", "accesses", "per_vertex_sweep",
            "cold",  "distinct", "sum",    "mean"};
    for (double q : qs) head.push_back(QuantileName(q));
    for (const CacheLevel& l : levels) head.push_back(l.name + "_misses");
    if (cost)
      head.insert(head.end(), {"cost_cycles_at_low_latency", "cost_cycles_at_high_latency"});
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
                                 std::to_string(e.samples()), std::to_string(e.sampled_ids()),
                                 num(e.cold_weight(), 0), num(e.distinct_estimate(), 0),
                                 finite ? num(e.Mean(), 1) : ""});
          for (double q : qs) row.push_back(finite ? std::to_string(e.Quantile(q)) : "");
          for (const CacheLevel& l : levels)
            row.push_back(num(e.MissRatio(l.bytes / bytes) * static_cast<double>(e.accesses()), 0));
          for (size_t i = 0; i < levels.size(); ++i) {
            const double b = e.MissBound(i);
            row.push_back(std::isfinite(b) ? num(b, 0) : "");
          }
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
        for (const CacheLevel& l : cfg.inverse)
          row.push_back(CapacityCell(CapacityForMisses(h, l.bytes)));
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

std::vector<std::string> SampleWarnings(const AnalyzeResult& r, const AnalyzeConfig& cfg) {
  std::vector<std::string> w;
  if (!cfg.sample) return w;
  for (const auto& a : r.runs)
    for (int th = 0; th < a->threads(); ++th)
      for (Granularity g : {Granularity::kElement, Granularity::kLine}) {
        const StreamAnalysis* s = a->stream(th, g);
        if (!s || !s->shards || s->shards->accesses() == 0) continue;
        const Shards& e = *s->shards;
        // FromSampled (merged chunks) keeps no first touches apart: judge by the samples.
        const uint64_t ids = e.sampled_ids() ? e.sampled_ids() : e.samples();
        if (ids >= kTrustedSampleIds) continue;
        w.push_back(
            a->info().input + " " + a->info().ordering + " thread " + std::to_string(th) + " " +
            GranularityName(g) + ": the sample holds " + std::to_string(ids) + " ids (fewer than " +
            std::to_string(kTrustedSampleIds) + "): its estimates" +
            (cfg.shards.exact_below
                 ? " at distances of " + std::to_string(cfg.shards.exact_below) + " and beyond"
                 : "") +
            " are not to be trusted; raise --sample-rate, or --sample-size " +
            std::to_string(8 * kTrustedSampleIds));
      }
  return w;
}

std::vector<std::string> AnalyzeNotes(const AnalyzeResult& r, const AnalyzeConfig& cfg) {
  std::vector<std::string> n;
  if (cfg.sample)
    n.push_back("(SHARDS estimates, seed " + std::to_string(cfg.shards.seed) +
                ": distances scaled by 1/rate; misses = accesses x the estimated miss ratio at "
                "each capacity; mrc_mae = mean |exact - estimated| miss ratio over every "
                "capacity, LEVEL_miss_ratio_error = estimated - exact at the level's capacity, "
                "with --sample-error; LEVEL_misses_ci95 = the 95% bound of the sampling of ids "
                "(+-; 0: exact; empty: a merged or distributed run, which keeps no per-id counts), "
                "which leaves out the scaling of distances that --sample-error measures" +
                (cfg.shards.exact_below
                     ? "; distances below " + std::to_string(cfg.shards.exact_below) +
                           " counted exactly: the misses at every capacity up to it are exact, "
                           "and the quantiles below it all but exact (the finite accesses they "
                           "share out are estimated)"
                     : "; no distance counted exactly (--sample-exact-below 0, or a chunked run)") +
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

Json AnalyzeConfigJson(const AnalyzeConfig& cfg, const AnalyzeResult& r) {
  Json j = cfg.ToJson();
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

RunOutput AnalyzeOutput(const AnalyzeResult& r, const AnalyzeConfig& cfg) {
  RunOutput o;
  o.tool = "meshreuse analyze";
  o.text.emplace_back(RunOutput::Share(AnalyzeTable(r, cfg, true)));
  for (const std::string& n : AnalyzeNotes(r, cfg)) o.text.emplace_back(n);
  o.csv = RunOutput::Share(AnalyzeTable(r, cfg, false));
  o.json = o.csv;
  o.tables.push_back({"analyze", o.csv, {"csv", "json"}});
  o.tables.push_back({"histogram", RunOutput::Share(HistogramTable(r)), {"csv"}});
  Table prof = ProfileTable(r);
  if (prof.Rows() > 0) o.tables.push_back({"profile", RunOutput::Share(std::move(prof)), {"csv"}});
  o.configuration = AnalyzeConfigJson(cfg, r);
  if (cfg.sample) o.extra = {{"sample_warnings", SampleWarnings(r, cfg)}};
  return o;
}

}  // namespace meshreuse
