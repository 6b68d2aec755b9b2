// ReuseAnalysis and its outputs; see reuse_analysis.h.
#include "analysis/reuse_analysis.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "analysis/parallel_stack_distance.h"
#include "analysis/streamed_chain.h"
#include "core/access.h"
#include "core/error.h"
#include "core/schedule.h"

namespace meshreuse {

Granularity ParseGranularity(const std::string& s) {
  if (s == "element") return Granularity::kElement;
  if (s == "line") return Granularity::kLine;
  if (s == "both") return Granularity::kBoth;
  throw UsageError("unknown granularity '" + s + "' (element, line or both)");
}

const char* GranularityName(Granularity g) {
  return g == Granularity::kElement ? "element" : g == Granularity::kLine ? "line" : "both";
}

ReuseAnalysis::ReuseAnalysis(const ReuseOptions& o) : opt_(o) {
  if (o.line_bytes == 0 || (o.line_bytes & (o.line_bytes - 1)))
    throw std::invalid_argument("the line size must be a power of two");
  if (o.workers < 1 || o.workers > kMaxThreads)
    throw std::invalid_argument("workers must be 1.." + std::to_string(kMaxThreads));
  if (o.chunk && (o.workers > 1 || (o.sample && o.shards.s_max)))
    throw std::invalid_argument("a chunk is analysed on one thread, sampled at a fixed rate");
  line_shift_ = __builtin_ctz(o.line_bytes);
  do_elements_ = static_cast<int>(o.granularity) & static_cast<int>(Granularity::kElement);
  do_lines_ = static_cast<int>(o.granularity) & static_cast<int>(Granularity::kLine);
}

void ReuseAnalysis::Begin(const StreamInfo& info) {
  if (info.threads < 1 || info.threads > kMaxThreads)
    throw std::invalid_argument("streams must be 1.." + std::to_string(kMaxThreads));
  Wait();  // a batch of an earlier input still in flight
  info_ = info;
  // Line ids are (address >> log2 line) - base: the canonical arrays start at kCanonicalBase, and
  // starting their lines near id 0 lets the analyzer's direct array cover them (above, every line
  // id would be hashed or the array would span 2^26 empty ids). A bijection: distances unchanged.
  line_base_ = info.canonical ? AddressCanonicalizer::kCanonicalBase >> line_shift_ : 0;
  element_.clear(), line_.clear(), ebuf_.clear(), lbuf_.clear();
  element_.resize(info.threads), line_.resize(info.threads);
  ebuf_.resize(info.threads), lbuf_.resize(info.threads);
  moves_.assign(info.threads, 0);
  ended_ = false;
}

std::unique_ptr<StreamAnalysis> ReuseAnalysis::NewStream(int t, Granularity g) {
  const bool element = g == Granularity::kElement;
  // This stream's accesses, when the input says: bounds its distinct ids, so the histogram's one
  // exact allocation never exceeds what the stream can fill.
  uint64_t records = 0;
  const auto& per_sweep = element ? info_.sweep_elements : info_.sweep_records;
  std::vector<uint64_t> lengths;
  for (const std::vector<uint64_t>& sweep : per_sweep)
    if (static_cast<size_t>(t) < sweep.size()) {
      lengths.push_back(sweep[t]);
      records += sweep[t];
    }
  const uint64_t dense = element ? static_cast<uint64_t>(std::max<int64_t>(info_.vertices, 0)) : 0;
  ShardsOptions shards = opt_.shards;
  shards.watch = element ? opt_.watch_element : opt_.watch_line;
  auto s = std::make_unique<StreamAnalysis>(dense, opt_.exact, opt_.sample ? &shards : nullptr);
  if (opt_.exact && dense && opt_.reserve)
    s->hist.Reserve(per_sweep.empty() ? dense : std::min(dense, records));
  bool any = false;
  for (uint64_t n : lengths) any = any || n > 0;
  // Steps per sweep: the configured count, fewer (at least 1) so that one granularity's profiles
  // hold at most kMaxProfileSteps steps over the (sweep, stream) pairs that have accesses.
  int64_t pairs = 1;
  for (const std::vector<uint64_t>& sweep : per_sweep)
    for (uint64_t n : sweep) pairs += n > 0;
  const int steps = static_cast<int>(
      std::clamp<int64_t>(kMaxProfileSteps / pairs, 1, std::max(opt_.profile_steps, 1)));
  if (any && opt_.profile) s->profile = ReuseProfile(lengths, steps);
  const std::vector<uint64_t>& offsets = element ? element_offset_ : line_offset_;
  s->chunk = opt_.chunk;
  s->keep_positions = opt_.chunk_positions || s->profile.enabled();
  if (opt_.chunk && opt_.sample) {
    s->sampled_chunk = std::make_unique<StreamAnalysis>(0);
    s->sampled_chunk->chunk = true;
    s->sampled_chunk->keep_positions = opt_.chunk_positions;
  }
  s->batch_limit = opt_.batch_per_worker * opt_.workers;
  s->offset = static_cast<size_t>(t) < offsets.size() ? offsets[t] : 0;
  s->profile.SetNext(s->offset);
  return s;
}

void ReuseAnalysis::Consume(const Access* a, size_t n) {
  if (opt_.workers > 1) {  // buffered for the chunk-and-merge analyzer
    for (size_t i = 0; i < n; ++i) {
      const Access& x = a[i];
      if (x.element != Access::kNoElement) AddElement(x.thread, x.element);
      if (x.kind == static_cast<uint8_t>(AccessKind::kAdjacency)) ++moves_[x.thread];
      AddAccess(x.thread, x.address, x.size);
    }
    return;
  }
  // Serial: runs of one thread (a traced run delivers each thread's share in one piece), with the
  // thread's streams looked up once per run rather than per access.
  for (size_t i = 0; i < n;) {
    const int t = a[i].thread;
    StreamAnalysis* e = element_[t].get();
    StreamAnalysis* l = do_lines_ ? &LineStream(t) : nullptr;
    uint64_t moves = 0;
    for (; i < n && a[i].thread == t; ++i) {
      const Access& x = a[i];
      if (do_elements_ && x.element != Access::kNoElement) {
        if (!e) e = &ElementStream(t);
        e->Add(x.element);
      }
      moves += x.kind == static_cast<uint8_t>(AccessKind::kAdjacency);
      if (l) {
        const uint64_t first = LineId(x.address >> line_shift_);
        const uint64_t last = LineId((x.address + (x.size ? x.size - 1 : 0)) >> line_shift_);
        l->Add(first);
        if (last != first) l->Add(last);
      }
    }
    moves_[t] += moves;
  }
}

ReuseAnalysis::~ReuseAnalysis() {
  if (batch_thread_.joinable()) batch_thread_.join();
}

void ReuseAnalysis::Wait() {
  if (!batch_thread_.joinable()) return;
  batch_thread_.join();
  // The next batch of this stream: enough accesses per distinct id to pay for the chunks.
  StreamAnalysis& s = *batch_stream_;
  const size_t per_worker = std::min<size_t>(
      opt_.max_batch_per_worker,
      std::max<size_t>(opt_.batch_per_worker, opt_.batch_per_distinct * s.distinct()));
  s.batch_limit = std::max(s.batch_limit, per_worker * opt_.workers);
  spare_ = std::move(batch_);
  batch_ = std::vector<uint64_t>();
  if (batch_error_) std::rethrow_exception(std::exchange(batch_error_, nullptr));
}

void ReuseAnalysis::Flush(StreamAnalysis& s, std::vector<uint64_t>& buf, bool last) {
  Wait();
  if (!last && buf.size() < s.batch_limit) return;  // the batch in flight raised the limit
  batch_.swap(buf);
  batch_stream_ = &s;
  buf.swap(spare_);  // the other buffer, emptied, with its capacity
  buf.clear();
  batch_thread_ = std::thread([this, &s] {
    try {
      s.AddBatch(batch_.data(), batch_.size(), opt_.workers);
    } catch (...) {
      batch_error_ = std::current_exception();
    }
  });
}

void ReuseAnalysis::End() {
  for (int t = 0; t < threads(); ++t) {
    if (element_[t] && !ebuf_[t].empty()) Flush(*element_[t], ebuf_[t], true);
    if (line_[t] && !lbuf_[t].empty()) Flush(*line_[t], lbuf_[t], true);
  }
  Wait();
  for (int t = 0; t < threads(); ++t)
    for (StreamAnalysis* s : {element_[t].get(), line_[t].get()})
      if (s && s->shards) s->shards->Finish();
  ended_ = true;
}

const StreamAnalysis* ReuseAnalysis::Done(const StreamAnalysis* s) const {
  if (!ended_) throw std::logic_error("ReuseAnalysis: End() must come before the results");
  return s;
}

template <class Row>
void ReuseAnalysis::ForEachStream(const Row& row) const {
  for (int t = 0; t < threads(); ++t)
    for (Granularity g : {Granularity::kElement, Granularity::kLine})
      if (const StreamAnalysis* s = stream(t, g))
        row(std::vector<std::string>{info_.input, info_.ordering, std::to_string(t),
                                     GranularityName(g)},
            *s);
}

namespace {
std::vector<std::string> Key(std::vector<std::string> rest) {
  std::vector<std::string> k = {"input", "ordering", "thread", "granularity"};
  k.insert(k.end(), rest.begin(), rest.end());
  return k;
}
std::vector<std::string> With(std::vector<std::string> key, std::vector<std::string> rest) {
  key.insert(key.end(), rest.begin(), rest.end());
  return key;
}
// %.17g: the double exactly (a mean of exact integers, to within an ulp of the quotient).
std::string Full(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
}  // namespace

std::vector<std::string> ReuseAnalysis::HistogramColumns() { return Key({"lo", "hi", "count"}); }

void ReuseAnalysis::AppendHistogramRows(Table* t, uint64_t exact_below) const {
  ForEachStream([&](const std::vector<std::string>& key, const StreamAnalysis& s) {
    s.hist.AppendRows(t, key, exact_below);
  });
}

std::vector<std::string> ReuseAnalysis::ProfileColumns() {
  return Key({"iteration", "step", "accesses", "cold", "mean"});
}

void ReuseAnalysis::AppendProfileRows(Table* t) const {
  ForEachStream([&](const std::vector<std::string>& key, const StreamAnalysis& s) {
    s.profile.AppendRows(t, key);
  });
}

std::vector<std::string> ReuseAnalysis::MrcColumns() {
  return Key({"capacity", "misses", "accesses", "miss_ratio", "estimated"});
}

void ReuseAnalysis::AppendMrcRows(Table* t) const {
  ForEachStream([&](const std::vector<std::string>& key, const StreamAnalysis& s) {
    if (s.shards) {
      const Shards& e = *s.shards;
      const std::string n = std::to_string(e.accesses());
      t->AddRow(
          With(key, {"0", Full(e.MissRatio(0) * e.accesses()), n, Full(e.MissRatio(0)), "1"}));
      for (const auto& kv : e.weights()) {
        const double r = e.MissRatio(kv.first + 1);
        t->AddRow(
            With(key, {std::to_string(kv.first + 1), Full(r * e.accesses()), n, Full(r), "1"}));
      }
      return;
    }
    const ReuseHistogram& h = s.hist;
    for (const MrcPoint& p : MissRatioCurve(h))
      t->AddRow(With(
          key,
          {std::to_string(p.capacity), std::to_string(p.misses), std::to_string(h.accesses()),
           h.accesses() ? Full(static_cast<double>(p.misses) / static_cast<double>(h.accesses()))
                        : "",
           "0"}));
  });
}

void StreamAnalysis::AddBatch(const uint64_t* ids, size_t n, int threads) {
  if (shards)
    for (size_t i = 0; i < n; ++i) shards->Access(ids[i]);
  if (!exact) return;
  if (!batched) {
    if (threads <= 1) {  // sampled above already
      for (size_t i = 0; i < n; ++i) AddExact(ids[i]);
      return;
    }
    stack = sd.StackBottomUp();  // from here on the stack travels as a list
    sd = StackDistance();
    batched = true;
  }
  // Chunks below a few thousand accesses are not worth a thread.
  const int p = static_cast<int>(std::min<size_t>(std::max(threads, 1), n / 4096 + 1));
  const uint64_t base = hist.accesses();
  auto begin = [&](int c) { return n * c / p; };
  std::vector<ReuseHistogram> hists(p);
  std::vector<ReuseProfile> profs(p);
  const bool prof = profile.enabled();
  StreamedChain(
      p, &stack,
      [&](int c) {
        // The partial histogram and profile are filled on this thread's stack, then moved:
        // neighbouring elements of one vector would share cache lines between the threads (false
        // sharing halved each thread's speed).
        ReuseHistogram h;
        ReuseProfile pr;
        if (prof) pr = profile.EmptyCopy();
        const uint64_t at = base + begin(c);
        ChunkSummary s = AnalyzeChunk(ids + begin(c), begin(c + 1) - begin(c), dense_limit,
                                      [&h, &pr, prof, at](size_t i, uint64_t d) {
                                        h.Add(d);
                                        if (prof) pr.AddAt(at + i, d);
                                      });
        hists[c] = std::move(h);
        profs[c] = std::move(pr);
        return s;
      },
      [&](int c, const ChunkSummary& s, const std::vector<uint64_t>& first) {
        ReuseHistogram h = std::move(hists[c]);
        ReuseProfile pr = std::move(profs[c]);
        const uint64_t at = base + begin(c);
        for (size_t k = 0; k < first.size(); ++k) {
          h.Add(first[k]);
          if (prof) pr.AddAt(at + s.first_positions[k], first[k]);
        }
        hists[c] = std::move(h);
        profs[c] = std::move(pr);
      });
  for (int c = 0; c < p; ++c) {
    hist.Merge(hists[c]);
    if (prof) profile.Merge(profs[c]);
  }
  profile.SetNext(base + n);
}

}  // namespace meshreuse
