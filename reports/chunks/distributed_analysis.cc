// The distributed analysis in phases; see distributed_analysis.h.
#include "reports/chunks/distributed_analysis.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "analysis/streamed_chain.h"
#include "core/error.h"
#include "reports/chunks/merge_summaries.h"
#include "reports/chunks/summarize_chunk.h"

namespace meshreuse {

namespace {

// Sorted (key, value) lists added into one sorted list, values of equal keys added.
template <class T, class Key, class Add>
std::vector<T> AddSorted(std::vector<T>&& a, std::vector<T>&& b, Key key, Add add) {
  auto less = [&](const T& x, const T& y) { return key(x) < key(y); };
  if (!std::is_sorted(a.begin(), a.end(), less)) std::sort(a.begin(), a.end(), less);
  if (!std::is_sorted(b.begin(), b.end(), less)) std::sort(b.begin(), b.end(), less);
  std::vector<T> out;
  out.reserve(a.size() + b.size());
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && key(a[i]) < key(b[j]))) {
      out.push_back(a[i++]);
    } else if (i == a.size() || key(b[j]) < key(a[i])) {
      out.push_back(b[j++]);
    } else {
      out.push_back(a[i++]);
      add(&out.back(), b[j++]);
    }
  }
  return out;
}

// Adds the resolved chunks `b` (those right after `a`'s, from the rank named `name`) into `a`.
void AddResolved(SummaryFile* a, SummaryFile&& b, const std::string& name) {
  if (!(b.id == a->id) || b.info.threads != a->info.threads || b.moves.size() != a->moves.size())
    throw InputError(name, 0, "corrupt: a resolved message of another analysis");
  if (b.first != a->end)
    throw InputError(name, 0, "corrupt: its records do not follow the previous chunk's");
  a->end = b.end;
  for (size_t t = 0; t < a->moves.size(); ++t) a->moves[t] += b.moves[t];
  for (StreamSummary& y : b.streams) {
    if (!y.resolved) throw InputError(name, 0, "corrupt: a stream not resolved");
    auto x = std::find_if(a->streams.begin(), a->streams.end(), [&](const StreamSummary& z) {
      return z.thread == y.thread && z.granularity == y.granularity && z.sampled == y.sampled;
    });
    if (x == a->streams.end()) {  // the stream's first accesses are in b's chunks
      a->streams.push_back(std::move(y));
      continue;
    }
    x->accesses += y.accesses;
    x->stream_accesses += y.stream_accesses;
    using Pair = std::pair<uint64_t, uint64_t>;
    x->hist = AddSorted(
        std::move(x->hist), std::move(y.hist), [](const Pair& p) { return p.first; },
        [](Pair* p, const Pair& q) { p->second += q.second; });
    using Step = StreamSummary::Step;
    x->profile = AddSorted(
        std::move(x->profile), std::move(y.profile), [](const Step& p) { return p.index; },
        [](Step* p, const Step& q) {
          p->accesses += q.accesses, p->cold += q.cold, p->sum += q.sum;
        });
  }
}

// What a rank's resolved histograms take (16 bytes a distance it counts).
uint64_t ResolvedBytes(const SummaryFile& s) {
  uint64_t n = 0;
  for (const StreamSummary& x : s.streams) n += x.hist.capacity() * 16;
  return n;
}

using Pair = std::pair<uint64_t, uint64_t>;

// A stream's key in a distributed run: (thread * 2 + granularity - 1) * 2 + sampled.
size_t StreamKey(const StreamSummary& x) {
  return (x.thread * 2 + static_cast<size_t>(x.granularity) - 1) * 2 + x.sampled;
}

// One stream's (distance, count) pairs as bytes, after its key and their number.
void PutPairs(std::string* out, uint64_t key, const Pair* p, size_t n) {
  const size_t at = out->size();
  out->resize(at + 16 * (n + 1));
  char* w = &(*out)[at];
  auto put = [&w](uint64_t v) {
    std::memcpy(w, &v, 8);
    w += 8;
  };
  put(key), put(n);
  for (size_t i = 0; i < n; ++i) put(p[i].first), put(p[i].second);
}

Pair PairAt(const char* p, size_t i) {
  uint64_t v[2];
  std::memcpy(v, p + 16 * i, 16);
  return {v[0], v[1]};
}

// Each stream's pairs in bytes PutPairs wrote, from the rank named `name`: f(key, bytes of its
// n pairs, n) (PairAt reads them), keys below `keys`, each stream once, every count positive and
// the distances increasing.
template <class F>
void ForEachPairs(const std::string& b, const std::string& name, size_t keys, F f) {
  std::vector<bool> seen(keys, false);
  for (size_t at = 0; at < b.size();) {
    if (b.size() - at < 16) throw InputError(name, 0, "corrupt: a histogram slice cut");
    const Pair head = PairAt(b.data() + at, 0);
    at += 16;
    if (head.first >= keys || seen[head.first] || head.second > (b.size() - at) / 16)
      throw InputError(name, 0, "corrupt: a histogram slice's stream or length");
    seen[head.first] = true;
    const char* p = b.data() + at;
    for (size_t i = 0; i < head.second; ++i) {
      const Pair q = PairAt(p, i);
      if (q.second == 0 || (i && q.first <= PairAt(p, i - 1).first))
        throw InputError(name, 0, "corrupt: a histogram slice's pairs");
    }
    f(static_cast<size_t>(head.first), p, static_cast<size_t>(head.second));
    at += 16 * head.second;
  }
}

}  // namespace

void SendIds(Communicator& c, const uint64_t* ids, size_t n) {
  c.Send(c.rank() + 1, PackValues(ids, n));
}

size_t RecvIds(Communicator& c, std::vector<uint64_t>* ids) {
  *ids = UnpackValues<uint64_t>(c.Recv(c.rank() - 1));
  return ids->size();
}

uint64_t SendSummary(Communicator& c, int32_t to, SummaryFile&& s) {
  if (c.SharesMemory()) {  // no bytes: the object changes hands
    c.SendObject(to, std::make_shared<SummaryFile>(std::move(s)));
    return 0;
  }
  std::string b = EncodeSummary(s);
  const uint64_t n = b.size();
  c.Send(to, std::move(b));
  return n;
}

SummaryFile RecvSummary(Communicator& c, int32_t from, const std::string& name) {
  if (c.SharesMemory())
    return std::move(*std::static_pointer_cast<SummaryFile>(c.RecvObject(from)));
  return DecodeSummary(name, c.Recv(from), true);
}

namespace {

// One rank's run, phase by phase: Summarise, RelayStacks (and each stream's first touches
// resolved), ScatterHistograms (from scatter_from_ranks ranks on), ReduceTree, then SendToRoot on
// ranks 1.. and MergeAtRoot on rank 0.
class DistributedRun {
 public:
  DistributedRun(const ReuseJob& job, Communicator& tx, const Log& log)
      : job_(job), tx_(tx), log_(log), rank_(tx.rank()), ranks_(tx.size()) {
    stats_.rank = rank_;
  }

  AnalyzeResult Run() {
    Summarise();
    RelayStacks();
    Lap();
    stats_.bytes_sent = stats_.stack_ids_sent * 8 + 16 * keys_;  // blocks, and two collectives
    if (rank_ == 0) log_.Say("adding up " + std::to_string(ranks_) + " resolved chunks");
    for (const StreamSummary& x : s_.streams) stats_.pairs += x.hist.size();
    stats_.histogram_bytes = std::max(stats_.histogram_bytes, ResolvedBytes(s_));
    scatter_ = ranks_ >= std::max(job_.scatter_from_ranks, 2);
    slice_.resize(keys_);
    if (scatter_) ScatterHistograms();
    ReduceTree();
    if (rank_ != 0) {
      SendToRoot();
      return AnalyzeResult();
    }
    return MergeAtRoot();
  }

 private:
  using U = unsigned __int128;
  static constexpr size_t kBlock = size_t{1} << 16;  // ids a block of the relay

  double Lap() {
    const double now = ThreadCpuSeconds(), d = now - cpu_;
    cpu_ = now;
    return d;
  }
  void Finish() {
    stats_.reduce_cpu = Lap();
    stats_.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
    stats_.peak_rss_bytes = PeakRssBytes();
  }

  // This rank's chunk, and every stream's presence and offset across the ranks.
  void Summarise() {
    s_ = SummarizeChunk(job_, static_cast<uint32_t>(rank_), static_cast<uint32_t>(ranks_), true,
                        rank_ == 0 ? log_ : quiet_);
    stats_.analyse_cpu = Lap();
    stats_.records = s_.end - s_.first;
    for (const StreamSummary& x : s_.streams)
      stats_.accesses += x.accesses, stats_.distinct += x.chunk.first_ids.size();
    // Every rank relays every stream some chunk has, in one order: stream key = (thread * 2 + g -
    // 1) * 2 + sampled.
    keys_ = static_cast<size_t>(s_.info.threads) * 4;
    present_.assign(keys_, 0);
    std::vector<uint64_t> accesses(keys_, 0);
    mine_.assign(keys_, nullptr);
    for (StreamSummary& x : s_.streams) {
      const size_t k = StreamKey(x);
      present_[k] = 1, accesses[k] = x.accesses, mine_[k] = &x;
    }
    present_ = tx_.AllReduceMax(present_);
    offsets_ = tx_.ExclusiveScanSum(accesses);
  }

  // Each stream's LRU stack through the ranks in order, each rank filtering what it receives
  // through its chunk's first touches; then this rank's first touches resolved.
  void RelayStacks() {
    if (rank_ == 0)
      log_.Say("streaming the LRU stacks through " + std::to_string(ranks_) + " ranks");
    // A profile for placing first touches at their true positions in each stream.
    ReuseOptions po;
    po.granularity = static_cast<Granularity>(s_.id.granularity);
    po.line_bytes = s_.id.line_bytes;
    po.profile = job_.profile;
    ReuseAnalysis places(po);
    places.Begin(s_.info);
    for (size_t k = 0; k < keys_; ++k) {
      if (!present_[k]) continue;
      StreamSummary* x = mine_[k];
      const ChunkSummary empty;
      ChunkResolver res(x ? x->chunk : empty);
      RelayStack(x, res);
      if (x) Resolve(k, x, res, places);
    }
  }

  void RelayStack(const StreamSummary* x, ChunkResolver& res) {
    const bool last = rank_ + 1 == ranks_;
    auto forward = [&](bool flush) {
      if (last) {
        out_.clear();
        return;
      }
      if (!out_.empty() && (flush || out_.size() >= kBlock)) {
        SendIds(tx_, out_.data(), out_.size());
        stats_.stack_ids_sent += out_.size();
        out_.clear();
      }
    };
    const double stream0 = ThreadCpuSeconds();
    if (rank_ > 0)
      while (RecvIds(tx_, &in_) > 0) {
        stats_.stack_ids_in += in_.size();
        res.Filter(in_.data(), in_.size(), &out_);
        forward(false);
      }
    if (x)
      for (size_t at = 0; at < x->chunk.stack.size(); at += kBlock) {
        out_.insert(out_.end(), x->chunk.stack.begin() + at,
                    x->chunk.stack.begin() + std::min(x->chunk.stack.size(), at + kBlock));
        forward(false);
      }
    forward(true);
    if (!last) SendIds(tx_, nullptr, 0);  // end of this stream
    stats_.stream_cpu += ThreadCpuSeconds() - stream0;
  }

  // Off the critical path: this chunk's first touches of stream k, folded into its histogram and
  // profile; the stream is then resolved (no first touches or stack left).
  void Resolve(size_t k, StreamSummary* x, ChunkResolver& res, ReuseAnalysis& places) {
    const double resolve0 = ThreadCpuSeconds();
    StreamAnalysis& st = places.MakeStream(static_cast<int>(x->thread), x->granularity);
    const bool prof = !x->sampled && st.profile.enabled();
    if (prof && x->offset != offsets_[k])
      throw InputError(s_.input, 0,
                       "the profile cannot be computed: chunk " + std::to_string(rank_) +
                           " counted its stream " + std::to_string(x->thread) +
                           " to start at access " + std::to_string(x->offset) +
                           ", the chunks before it hold " + std::to_string(offsets_[k]) +
                           " (accesses straddling two lines)");
    // The first touches' distances reach the whole stream's distinct ids: counted in pages.
    ReuseHistogram h;
    h.UsePages();
    for (const auto& [dist, n] : x->hist) h.AddCount(dist, n);
    const std::vector<uint64_t>& places_in_chunk = x->chunk.first_positions;
    if (prof && places_in_chunk.size() != x->chunk.first_ids.size())
      throw std::logic_error("RunDistributed: a chunk with a profile kept no first-touch places");
    res.ForEachFirstTouchDistance([&](size_t i, uint64_t d) {
      h.Add(d);
      if (prof) st.profile.AddAt(offsets_[k] + places_in_chunk[i], d);
    });
    stats_.histogram_bytes = std::max(stats_.histogram_bytes, h.counter_bytes());
    stats_.dense_histogram_bytes =
        std::max(stats_.dense_histogram_bytes,
                 h.finite() ? ReuseHistogram::kDenseCounterBytes * (h.max() + 1) : 0);
    size_t pairs = 1;  // and the cold count's
    h.ForEach([&pairs](uint64_t, uint64_t) { ++pairs; });
    x->hist.clear();
    x->hist.reserve(pairs);
    h.ForEach([&](uint64_t dist, uint64_t n) { x->hist.emplace_back(dist, n); });
    if (h.cold()) x->hist.emplace_back(StackDistance::kCold, h.cold());
    if (prof) {
      const auto& steps = st.profile.steps();
      for (size_t i = 0; i < steps.size(); ++i)
        if (steps[i].accesses)
          x->profile.push_back({i, steps[i].accesses, steps[i].cold, steps[i].sum});
    }
    x->chunk = ChunkSummary();
    x->resolved = true;
    x->offset = offsets_[k];  // the true start, now known
    stats_.resolve_cpu += ThreadCpuSeconds() - resolve0;
  }

  // The histograms added up by distance, not by chunk (a reduce-scatter): rank j adds slice j of
  // every stream's distances, d with floor(d P / top) = j (top: one past the stream's largest
  // finite distance on any rank; the cold count with the last slice), from every rank, and rank 0
  // gathers the disjoint slices in order. Each rank adds at most the distinct distances M and rank
  // 0 receives at most M, whatever P, where the tree (ReduceTree), adding whole lists, takes
  // log2(P) merges of up to M pairs on the way to rank 0. With few ranks the tree is cheaper: the
  // slices are cut, sent, parsed and added twice over (threads on 20 M uniform accesses over 10^6
  // ids, rank 0's reduce CPU by distance and by tree: 0.047 / 0.020 s at 2, 0.052 / 0.035 at 4,
  // 0.051 / 0.047 at 8: the default, 16, where the tree's levels cost more). Integers: exact in
  // any grouping.
  uint64_t Lo(size_t k, int j) const {  // the least distance of slice j (j < ranks)
    return static_cast<uint64_t>((U{top_[k]} * static_cast<unsigned>(j) + ranks_ - 1) / ranks_);
  }
  bool InSlice(size_t k, int j, uint64_t d) const {
    if (d == StackDistance::kCold) return j + 1 == ranks_;
    return d < top_[k] && d >= Lo(k, j) && (j + 1 == ranks_ || d < Lo(k, j + 1));
  }
  void ScatterHistograms() {
    top_.assign(keys_, 0);
    for (const StreamSummary& x : s_.streams)
      for (auto p = x.hist.rbegin(); p != x.hist.rend(); ++p)
        if (p->first != StackDistance::kCold) {
          top_[StreamKey(x)] = p->first + 1;
          break;
        }
    top_ = tx_.AllReduceMax(top_);
    std::vector<std::pair<const Pair*, size_t>> own(keys_, {nullptr, 0});
    std::vector<std::string> in = tx_.AllToAll(CutSlices(&own));
    const double merge0 = ThreadCpuSeconds();
    AddSlices(own, in);
    stats_.merge_cpu += ThreadCpuSeconds() - merge0;
    for (StreamSummary& x : s_.streams) {
      x.hist = std::vector<Pair>();
      x.hist_apart = true;
    }
  }

  // Each rank's slices of every stream (this rank's own left in place: `own`).
  std::vector<std::string> CutSlices(std::vector<std::pair<const Pair*, size_t>>* own) {
    std::vector<std::string> out(static_cast<size_t>(ranks_));
    for (const StreamSummary& x : s_.streams) {
      const size_t k = StreamKey(x);
      const Pair* b = x.hist.data();
      const Pair* e = b + x.hist.size();
      for (int j = 0; j < ranks_; ++j) {  // pairs are sorted: each slice a run of them
        const Pair* end = j + 1 == ranks_
                              ? e
                              : std::lower_bound(b, e, Lo(k, j + 1), [](const Pair& q, uint64_t d) {
                                  return q.first < d;
                                });
        if (end == b) continue;
        if (j == rank_)
          (*own)[k] = {b, static_cast<size_t>(end - b)};
        else
          PutPairs(&out[static_cast<size_t>(j)], k, b, static_cast<size_t>(end - b));
        b = end;
      }
    }
    for (const std::string& o : out) stats_.bytes_sent += o.size();
    return out;
  }

  // Slice `rank` of every stream, this rank's own and every other's, added up in pages of
  // distances, each allocated when first touched: memory follows the distances the slice holds (a
  // scan's: one page), not its width.
  void AddSlices(const std::vector<std::pair<const Pair*, size_t>>& own,
                 const std::vector<std::string>& in) {
    std::vector<ReuseHistogram> counts(keys_);
    for (ReuseHistogram& h : counts) h.UsePages();
    // This slice's bounds, once per stream (InSlice divides for each call): [from, to).
    std::vector<uint64_t> from(keys_), to(keys_);
    for (size_t k = 0; k < keys_; ++k)
      from[k] = Lo(k, rank_), to[k] = rank_ + 1 == ranks_ ? top_[k] : Lo(k, rank_ + 1);
    const bool last = rank_ + 1 == ranks_;
    auto add = [&](size_t k, uint64_t d, uint64_t n, const std::string& name) {
      if (d == StackDistance::kCold ? !last : d < from[k] || d >= to[k])
        throw InputError(name, 0, "corrupt: a distance outside the slice it was sent for");
      counts[k].AddCount(d, n);
    };
    const std::string me = "rank " + std::to_string(rank_);
    for (size_t k = 0; k < keys_; ++k) {
      for (size_t i = 0; i < own[k].second; ++i)
        add(k, own[k].first[i].first, own[k].first[i].second, me);
      stats_.pairs_added += own[k].second;
    }
    for (int j = 0; j < ranks_; ++j)
      if (j != rank_) {
        const std::string name = "rank " + std::to_string(j);
        ForEachPairs(in[static_cast<size_t>(j)], name, keys_,
                     [&](size_t k, const char* p, size_t n) {
                       if (!present_[k]) throw InputError(name, 0, "corrupt: a stream no rank has");
                       for (size_t i = 0; i < n; ++i) {
                         const Pair q = PairAt(p, i);
                         add(k, q.first, q.second, name);
                       }
                       stats_.pairs_added += n;
                     });
      }
    for (size_t k = 0; k < keys_; ++k) {
      counts[k].ForEach([&](uint64_t d, uint64_t n) { slice_[k].emplace_back(d, n); });
      if (counts[k].cold()) slice_[k].emplace_back(StackDistance::kCold, counts[k].cold());
      stats_.histogram_bytes = std::max<uint64_t>(
          stats_.histogram_bytes, counts[k].counter_bytes() + slice_[k].capacity() * 16);
      counts[k] = ReuseHistogram();
    }
  }

  // The resolved chunks (their histograms too, unless scattered; accesses, profiles, moves) up a
  // binary tree of ranks: at the level of `step`, a rank r with r % 2 step == step sends what it
  // holds (chunks [r, r + step)) to r - step, which adds it to its own.
  void ReduceTree() {
    for (int step = 1; step < ranks_; step *= 2) {
      if (rank_ % (2 * step) == step) {
        stats_.bytes_sent += SendSummary(tx_, rank_ - step, std::move(s_));
        s_ = SummaryFile();
        break;
      }
      if (rank_ + step < ranks_) {
        const std::string name = "rank " + std::to_string(rank_ + step);
        SummaryFile o = RecvSummary(tx_, rank_ + step, name);
        for (const StreamSummary& x : o.streams) stats_.pairs_added += x.hist.size();
        const double merge0 = ThreadCpuSeconds();
        AddResolved(&s_, std::move(o), name);
        if (!scatter_) {  // the histograms came whole, and were added here
          stats_.merge_cpu += ThreadCpuSeconds() - merge0;
          stats_.histogram_bytes = std::max(stats_.histogram_bytes, ResolvedBytes(s_));
        }
      }
    }
  }

  // Ranks 1..: this rank's slices (when scattered) and its statistics to rank 0.
  void SendToRoot() {
    if (scatter_) {
      std::string b;
      for (size_t k = 0; k < keys_; ++k)
        if (!slice_[k].empty()) PutPairs(&b, k, slice_[k].data(), slice_[k].size());
      stats_.bytes_sent += b.size();
      tx_.Send(0, std::move(b));
    }
    Finish();
    tx_.Send(0, std::string(reinterpret_cast<const char*>(&stats_), sizeof stats_));
  }

  // Rank 0 holds every chunk, resolved: its histograms (when scattered) the slices of the ranks in
  // order, each rank's distances above those of the ranks before.
  void GatherSlices() {
    for (int j = 1; j < ranks_; ++j) {
      const std::string name = "rank " + std::to_string(j);
      ForEachPairs(tx_.Recv(j), name, keys_, [&](size_t k, const char* p, size_t n) {
        for (size_t i = 0; i < n; ++i) {
          const Pair q = PairAt(p, i);
          if (!InSlice(k, j, q.first))
            throw InputError(name, 0, "corrupt: a distance outside its slice");
          slice_[k].push_back(q);
        }
      });
    }
    for (StreamSummary& x : s_.streams) {
      const size_t k = StreamKey(x);
      uint64_t n = 0;
      for (const Pair& q : slice_[k])
        if (__builtin_add_overflow(n, q.second, &n)) n = ~uint64_t{0};
      if (n != x.accesses)
        throw InputError("the ranks", 0,
                         "corrupt: a stream's histogram slices do not add up to its accesses");
      x.hist = std::move(slice_[k]);
      x.hist_apart = false;
      stats_.histogram_bytes = std::max(stats_.histogram_bytes, ResolvedBytes(s_));
    }
    for (const std::vector<Pair>& left : slice_)
      if (!left.empty())
        throw InputError("the ranks", 0, "corrupt: histogram slices of a stream none holds");
  }

  // One summary of one chunk for the merger, and every rank's statistics.
  AnalyzeResult MergeAtRoot() {
    if (scatter_) GatherSlices();
    s_.chunk = 0, s_.id.chunks = 1;
    SummaryMerger m(job_.profile, true);
    m.Add(std::move(s_), "rank 0", 1);
    std::vector<RankStats> all(1);
    for (int r = 1; r < ranks_; ++r) {
      const std::string b = tx_.Recv(r);
      if (b.size() != sizeof(RankStats))
        throw InputError("rank " + std::to_string(r), 0, "corrupt statistics message");
      all.emplace_back();
      std::memcpy(&all.back(), b.data(), sizeof(RankStats));
    }
    AnalyzeResult res = m.Finish();
    uint64_t merged = 0, merged_dense = 0;  // every merged stream's, held together
    for (const auto& run : res.runs)
      for (int t = 0; t < run->threads(); ++t)
        for (Granularity g : {Granularity::kElement, Granularity::kLine})
          if (const StreamAnalysis* x = run->stream(t, g)) {
            merged += x->hist.counter_bytes();
            merged_dense +=
                x->hist.finite() ? ReuseHistogram::kDenseCounterBytes * (x->hist.max() + 1) : 0;
          }
    stats_.histogram_bytes = std::max(stats_.histogram_bytes, merged);
    stats_.dense_histogram_bytes = std::max(stats_.dense_histogram_bytes, merged_dense);
    Finish();
    all[0] = stats_;
    res.ranks = std::move(all);
    return res;
  }

  const ReuseJob& job_;
  Communicator& tx_;
  const Log& log_;
  const Log quiet_;
  const int rank_, ranks_;
  RankStats stats_;
  const std::chrono::steady_clock::time_point wall0_ = std::chrono::steady_clock::now();
  double cpu_ = ThreadCpuSeconds();
  SummaryFile s_;
  size_t keys_ = 0;
  std::vector<uint64_t> present_, offsets_, top_;
  std::vector<StreamSummary*> mine_;
  std::vector<uint64_t> in_, out_;  // the relay's blocks
  bool scatter_ = false;
  std::vector<std::vector<Pair>> slice_;  // this rank's slice of each stream, added up
};

}  // namespace

AnalyzeResult RunDistributed(const ReuseJob& job, Communicator& tx, const Log& log) {
  return DistributedRun(job, tx, log).Run();
}

}  // namespace meshreuse
