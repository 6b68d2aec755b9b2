// TraceAnalysis and the small parsers; see trace_analysis.h.
#include "analysis/trace_analysis.h"

#include <stdexcept>

#include "analysis/parallel_stack_distance.h"

namespace meshreuse {

Granularity ParseGranularity(const std::string& s) {
  if (s == "element") return Granularity::kElement;
  if (s == "line") return Granularity::kLine;
  if (s == "both") return Granularity::kBoth;
  throw std::invalid_argument("unknown granularity '" + s + "' (element, line or both)");
}

const char* GranularityName(Granularity g) {
  return g == Granularity::kElement ? "element" : g == Granularity::kLine ? "line" : "both";
}

ExternalFormat ParseExternalFormat(const std::string& s) {
  if (s == "text") return ExternalFormat::kText;
  if (s == "u32") return ExternalFormat::kU32;
  if (s == "u64") return ExternalFormat::kU64;
  if (s == "parda") return ExternalFormat::kParda;
  if (s == "oracle" || s == "oracleGeneral") return ExternalFormat::kOracle;
  if (s == "lackey") return ExternalFormat::kLackey;
  throw std::invalid_argument("unknown trace format '" + s +
                              "' (text, u32, u64, parda, oracle or lackey)");
}

size_t ExternalRecordBytes(ExternalFormat fmt) {
  switch (fmt) {
    case ExternalFormat::kU32:
      return 4;
    case ExternalFormat::kU64:
    case ExternalFormat::kParda:
      return 8;
    case ExternalFormat::kOracle:
      return 24;
    default:
      return 0;
  }
}

uint64_t ExternalTraceLength(const std::string& path, ExternalFormat fmt) {
  const size_t w = ExternalRecordBytes(fmt);
  if (w == 0 || path == "-") return 0;
  try {
    InputStream in(path);
    return in.size() > 0 ? static_cast<uint64_t>(in.size()) / w : 0;
  } catch (const InputError&) {
    return 0;  // the reader reports it
  }
}

TraceAnalysis::TraceAnalysis(const TraceAnalysisOptions& o) : opt_(o) {
  if (o.threads < 1 || o.threads > 256) throw std::invalid_argument("threads must be 1..256");
  if (o.line_bytes == 0 || (o.line_bytes & (o.line_bytes - 1)))
    throw std::invalid_argument("the line size must be a power of two");
  line_shift_ = __builtin_ctz(o.line_bytes);
  for (int t = 0; t < o.threads; ++t) {
    const bool prof =
        static_cast<size_t>(t) < o.iteration_lengths.size() && !o.iteration_lengths[t].empty();
    const bool line_prof = static_cast<size_t>(t) < o.line_iteration_lengths.size() &&
                           !o.line_iteration_lengths[t].empty();
    std::unique_ptr<StreamAnalysis> e, l;
    if (static_cast<int>(o.granularity) & static_cast<int>(Granularity::kElement)) {
      e = std::make_unique<StreamAnalysis>(o.dense_elements, o.exact,
                                           o.sample ? &o.shards : nullptr);
      if (prof) e->profile = ReuseProfile(o.iteration_lengths[t], o.profile_steps);
    }
    if (static_cast<int>(o.granularity) & static_cast<int>(Granularity::kLine)) {
      l = std::make_unique<StreamAnalysis>(0, o.exact, o.sample ? &o.shards : nullptr);
      if (line_prof) l->profile = ReuseProfile(o.line_iteration_lengths[t], o.profile_steps);
    }
    element_.push_back(std::move(e));
    line_.push_back(std::move(l));
  }
  if (o.workers < 1 || o.workers > 1024) throw std::invalid_argument("workers must be 1..1024");
  ebuf_.resize(o.threads);
  lbuf_.resize(o.threads);
  if (o.workers > 1)
    for (int t = 0; t < o.threads; ++t) {
      if (element_[t]) ebuf_[t].reserve(o.batch_per_worker * o.workers);
      if (line_[t]) lbuf_[t].reserve(o.batch_per_worker * o.workers);
    }
}

void TraceAnalysis::Flush(StreamAnalysis& s, std::vector<uint64_t>& buf) {
  s.AddBatch(buf.data(), buf.size(), opt_.workers);
  buf.clear();
}

void TraceAnalysis::Finish() {
  for (int t = 0; t < threads(); ++t) {
    if (element_[t] && !ebuf_[t].empty()) Flush(*element_[t], ebuf_[t]);
    if (line_[t] && !lbuf_[t].empty()) Flush(*line_[t], lbuf_[t]);
    for (StreamAnalysis* s : {element_[t].get(), line_[t].get()})
      if (s && s->shards) s->shards->Finish();
  }
}

const StreamAnalysis* TraceAnalysis::Done(const StreamAnalysis* s) const {
  for (int t = 0; t < threads(); ++t)
    if (!ebuf_[t].empty() || !lbuf_[t].empty())
      throw std::logic_error("TraceAnalysis: Finish() must be called before reading results");
  return s;
}

void StreamAnalysis::AddBatch(const uint64_t* ids, size_t n, int threads) {
  if (shards)
    for (size_t i = 0; i < n; ++i) shards->Access(ids[i]);
  if (!exact) return;
  // Chunks below a few thousand accesses are not worth a thread.
  const int p = static_cast<int>(std::min<size_t>(std::max(threads, 1), n / 4096 + 1));
  if (p <= 1) {  // sampled above already
    for (size_t i = 0; i < n; ++i) AddExact(ids[i]);
    return;
  }
  const uint64_t base = hist.accesses();
  auto begin = [&](int c) { return n * c / p; };
  std::vector<ChunkSummary> chunks(p);
  std::vector<ReuseHistogram> hists(p);
  std::vector<ReuseProfile> profs(p);
  const bool prof = profile.enabled();
#pragma omp parallel for num_threads(p) schedule(static, 1)
  for (int c = 0; c < p; ++c) {
    // The partial histogram and profile live on this thread's stack while they are filled:
    // neighbouring elements of one vector would share cache lines between the threads (false
    // sharing halved each thread's speed).
    ReuseHistogram h;
    ReuseProfile pr;
    if (prof) pr = profile.EmptyCopy();
    const uint64_t at = base + begin(c);
    chunks[c] = AnalyzeChunk(ids + begin(c), begin(c + 1) - begin(c), dense_limit,
                             [&h, &pr, prof, at](size_t i, uint64_t d) {
                               h.Add(d);
                               if (prof) pr.AddAt(at + i, d);
                             });
    hists[c] = std::move(h);
    profs[c] = std::move(pr);
  }
  for (int c = 0; c < p; ++c) {
    const uint64_t at = base + begin(c);
    MergeChunk(&sd, chunks[c], [this, prof, at](size_t i, uint64_t d) {
      hist.Add(d);
      if (prof) profile.AddAt(at + i, d);
    });
    chunks[c] = ChunkSummary();
    hist.Merge(hists[c]);
    if (prof) profile.Merge(profs[c]);
  }
  profile.SetNext(base + n);
}

}  // namespace meshreuse
