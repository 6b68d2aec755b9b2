// The merge of chunk summaries; see merge_summaries.h.
#include "reports/chunks/merge_summaries.h"

#include <map>
#include <stdexcept>

#include "analysis/streamed_chain.h"
#include "core/error.h"
#include "tracer/foreign_trace.h"
#include "tracer/trace_formats.h"

namespace meshreuse {

SummaryMerger::SummaryMerger(bool profile, bool reread) : profile_(profile), reread_(reread) {}
SummaryMerger::~SummaryMerger() = default;

void SummaryMerger::Add(SummaryFile s, const std::string& name, size_t given) {
  if (!a_) {
    id_ = s.id;
    first_name_ = name;
    input_ = s.input;
    granularity_ = static_cast<Granularity>(id_.granularity);
    ReuseOptions o;
    o.granularity = granularity_;
    o.line_bytes = id_.line_bytes;
    o.profile = profile_;
    o.exact = id_.exact;
    o.sample = id_.sample;
    o.shards.rate = id_.sample ? id_.rate : 1;
    o.shards.seed = id_.seed;
    o.reserve = false;  // the summary's vertex and sweep counts are claims, not yet data
    shards_ = o.shards;
    a_ = std::make_unique<ReuseAnalysis>(o);
    StreamInfo info = s.info;
    info.input = s.input;
    a_->Begin(info);
    if (given != id_.chunks)
      throw InputError(name, 0,
                       "a run of " + std::to_string(id_.chunks) + " chunks, and " +
                           std::to_string(given) +
                           " summaries given: give every chunk's summary once, in order 0.." +
                           std::to_string(id_.chunks - 1));
  } else if (!(s.id == id_)) {
    throw InputError(name, 0,
                     "a summary of another analysis: its trace, options or chunk count differ "
                     "from those of " +
                         first_name_);
  }
  if (s.chunk != expect_)
    throw InputError(name, 0,
                     "chunk " + ChunkName(s.chunk, id_.chunks) + " where chunk " +
                         ChunkName(expect_, id_.chunks) +
                         " was expected: give every summary once, in order 0.." +
                         std::to_string(id_.chunks - 1));
  if (s.first != next_record_)
    throw InputError(name, 0, "corrupt: its records do not follow the previous chunk's");
  if (s.info.threads != a_->threads())
    throw InputError(name, 0, "corrupt: a thread count unlike the first summary's");
  ++expect_;
  next_record_ = s.end;
  for (int t = 0; t < a_->threads(); ++t) a_->AddMoves(t, s.moves[t]);
  for (StreamSummary& x : s.streams) {
    any_access_ = any_access_ || x.accesses > 0 || x.stream_accesses > 0;
    StreamAnalysis& st = a_->MakeStream(static_cast<int>(x.thread), x.granularity);
    // The merged distances reach the stream's distinct ids: counted in pages, not in an array as
    // long as the largest (no rank of an MPI run, nor a file merge, holds one of M entries).
    if (!st.hist.paged() && st.hist.accesses() == 0) st.hist.UsePages();
    if (x.sampled) {  // the sampled ids, a stream of their own (no profile)
      Sampled& z = sampled_[{static_cast<int>(x.thread), static_cast<int>(x.granularity)}];
      if (!x.resolved)
        for (uint64_t d : ResolveChunk(x.chunk, &z.stack)) z.hist.Add(d);
      for (const auto& [dist, n] : x.hist) z.hist.AddCount(dist, n);
      z.accesses += x.stream_accesses;
      continue;
    }
    st.batched = true;                       // the stack travels as a list
    const uint64_t at = st.hist.accesses();  // the stream's accesses before this chunk
    const bool prof = st.profile.enabled();
    if (prof && x.offset != at)
      throw InputError(name, 0,
                       "the profile cannot be merged: the chunk counted its stream " +
                           std::to_string(x.thread) + " to start at access " +
                           std::to_string(x.offset) + ", the chunks before it hold " +
                           std::to_string(at) +
                           " (accesses straddling two lines before the chunk); merge without "
                           "profile output");
    if (!x.resolved) {
      const std::vector<uint64_t> d = ResolveChunk(x.chunk, &st.stack);
      for (size_t k = 0; k < d.size(); ++k) {
        st.hist.Add(d[k]);
        if (prof) st.profile.AddAt(at + x.chunk.first_positions[k], d[k]);
      }
    }
    for (const auto& [dist, n] : x.hist) st.hist.AddCount(dist, n);
    if (prof)
      for (const StreamSummary::Step& p : x.profile)
        if (!st.profile.AddToStep(p.index, p.accesses, p.cold, p.sum))
          throw InputError(name, 0, "corrupt: a profile step beyond the sweeps");
  }
}

AnalyzeResult SummaryMerger::Finish() {
  if (!a_) throw std::logic_error("SummaryMerger: nothing added");
  // A whole read refuses a lackey file without records (data, or instructions counted); a chunk
  // cannot tell, so the chunks together do (no access in any chunk is exactly that condition).
  if (id_.format == "lackey" && !any_access_) {
    if (reread_)
      ReadForeignTrace(
          input_, ParseTraceFormat("lackey"), [](uint64_t, uint32_t, bool, bool) {},
          id_.instructions != 0);
    throw InputError(input_, 0,
                     "no lackey records (L, S, M or I lines) in any chunk: run valgrind "
                     "--tool=lackey --trace-mem=yes --log-file=FILE PROGRAM and read FILE");
  }
  // Each sampled stream's estimate, as the serial sampler would have built it (End() then applies
  // SHARDS_adj as it does serially).
  for (const auto& [key, z] : sampled_) {
    StreamAnalysis& st = a_->MakeStream(key.first, static_cast<Granularity>(key.second));
    st.shards = std::make_unique<Shards>(Shards::FromSampled(shards_, z.accesses, z.hist));
  }
  a_->End();
  AnalyzeResult res;
  res.granularity = granularity_;
  if (id_.sample) {
    res.sampling = shards_;
    res.sampling_with_exact = id_.exact;
  }
  res.runs.push_back(std::move(a_));
  return res;
}

namespace {

// Why `paths` are not a run's summaries (chunks 0..P-1 once each, P from the first): the chunks
// missing and those given twice, by name. The error path alone reads every summary for this.
std::string ChunkCountProblem(const std::vector<std::string>& paths, uint32_t chunks) {
  std::map<uint32_t, std::vector<std::string>> given;
  for (const std::string& path : paths) given[ReadSummary(path).chunk].push_back(path);
  std::string missing, twice;
  for (uint32_t r = 0; r < chunks; ++r) {
    const auto it = given.find(r);
    if (it == given.end())
      missing += (missing.empty() ? "" : ", ") + ChunkName(r, chunks);
    else if (it->second.size() > 1)
      twice += (twice.empty() ? "" : "; ") + ChunkName(r, chunks) + " (" + it->second[0] + ", " +
               it->second[1] + ")";
  }
  std::string why = "a run of " + std::to_string(chunks) + " chunks, and " +
                    std::to_string(paths.size()) +
                    (paths.size() == 1 ? " summary given" : " summaries given");
  if (!missing.empty()) why += ": chunk " + missing + " missing";
  if (!twice.empty()) why += (missing.empty() ? ": chunk " : "; chunk ") + twice + " given twice";
  return why + " (give every chunk's summary once, in order 0.." + std::to_string(chunks - 1) + ")";
}

}  // namespace

AnalyzeResult MergeSummaries(const std::vector<std::string>& paths, bool profile, const Log& log) {
  if (paths.empty()) throw UsageError("--merge: no summary given");
  SummaryMerger m(profile);
  for (const std::string& path : paths) {
    SummaryFile s = ReadSummary(path);
    if (&path == &paths[0] && s.id.chunks != paths.size())
      throw InputError(path, 0, ChunkCountProblem(paths, s.id.chunks));
    log.Say("merging chunk " + ChunkName(s.chunk, s.id.chunks) + " (" + path + ")");
    m.Add(std::move(s), path, paths.size());
  }
  return m.Finish();
}

}  // namespace meshreuse
