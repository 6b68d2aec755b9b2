// Reuse analysis of an access stream (any source of tracer/access_stream.h): one exact LRU stack
// with its histogram and profile (StreamAnalysis) per thread stream and per granularity.
// Element granularity: the element stream (touches of vertex records by vertex id, the paper's
// model; a foreign trace's values). Line granularity: the address stream (every load and store,
// by byte address / line size); an access that straddles two lines touches both. Each thread's
// stream is analysed on its own (private caches, as the paper's per-core L1/L2).
// Memory follows what arrives: a stream's state is made at its first access, whatever thread
// count the input announced.
// Outputs, one schema each whatever the command (AppendHistogramRows, AppendProfileRows,
// AppendMrcRows; key columns input, ordering, thread, granularity first).
#pragma once

#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "analysis/reuse_histogram.h"
#include "analysis/shards.h"
#include "analysis/stack_distance.h"
#include "core/table.h"
#include "tracer/access_stream.h"

namespace meshreuse {

enum class Granularity { kElement = 1, kLine = 2, kBoth = 3 };
Granularity ParseGranularity(const std::string& s);  // element | line | both; UsageError
const char* GranularityName(Granularity g);

struct StreamAnalysis {
  // exact: the exact analyzer runs; sample: SHARDS runs too (both: its error can be measured).
  explicit StreamAnalysis(uint64_t dense_limit, bool exact = true,
                          const ShardsOptions* sample = nullptr)
      : sd(exact ? dense_limit : 0), dense_limit(dense_limit), exact(exact) {
    if (sample) shards = std::make_unique<Shards>(*sample);
  }
  StackDistance sd;  // the stream's LRU stack (its distinct() is the stream's distinct ids)
  ReuseHistogram hist;
  ReuseProfile profile;
  uint64_t dense_limit;
  bool exact;
  std::unique_ptr<Shards> shards;
  void Add(uint64_t id) {
    if (exact) AddExact(id);
    if (sampled_chunk) {  // a chunk: the sampled ids' own exact chunk analysis
      ++added;
      if (shards->Keeps(id)) sampled_chunk->AddExact(id);
    } else if (shards) {
      shards->Access(id);
    }
  }
  uint64_t AddExact(uint64_t id) {  // the access's distance (StackDistance::kCold if cold)
    const uint64_t d = sd.Access(id);
    if (d == StackDistance::kCold && chunk) {  // decided later, by the merge
      first_ids.push_back(id);
      if (keep_positions) first_positions.push_back(sd.accesses() - 1);
      if (profile.enabled()) profile.Skip();
      return d;
    }
    hist.Add(d);
    if (profile.enabled()) profile.Add(d);
    return d;
  }
  // The next n accesses at once, on `threads` threads (the streamed merge, streamed_chain.h): the
  // same histogram and profile as n calls of Add. From the first batch on, the stream's LRU stack
  // is kept as a list (`stack`, bottom-up) instead of in `sd`.
  void AddBatch(const uint64_t* ids, size_t n, int threads);
  std::vector<uint64_t> stack;
  bool batched = false;
  size_t batch_limit = 0;  // ids buffered before a batch is analysed (ReuseAnalysis, workers > 1)
  // A chunk of a longer trace (ReuseOptions::chunk): its cold accesses are its first touches,
  // kept here (the id, and the access's place in the chunk's part of the stream) for the merge,
  // not counted; `offset` is where the chunk starts in the stream (profile positions).
  bool chunk = false;
  uint64_t offset = 0;
  std::vector<uint64_t> first_ids, first_positions;
  bool keep_positions = true;  // first_positions kept (ReuseOptions::chunk_positions)
  // A chunk sampled at a fixed rate: the sampled ids' exact distances among themselves, as a
  // chunk of their own (merged, they give exactly the serial SHARDS estimate:
  // Shards::FromSampled); `added` counts the stream's accesses in the chunk.
  std::unique_ptr<StreamAnalysis> sampled_chunk;
  uint64_t added = 0;
  // The stream's distinct ids (exact analysis): each id's first access is its one cold access,
  // however the analysis was done (serial, batched, merged from chunks or ranks).
  uint64_t distinct() const { return hist.cold(); }
};

// The most profile steps of one granularity over all streams (rows of the profile table).
inline constexpr int64_t kMaxProfileSteps = int64_t{1} << 18;

struct ReuseOptions {
  Granularity granularity = Granularity::kBoth;
  uint32_t line_bytes = 64;  // a power of two
  bool profile = true;       // a profile per stream, when the input's sweep lengths are known
  int profile_steps = 100;   // per sweep, fewer when the sweeps x streams are many:
  // at most kMaxProfileSteps steps a stream (each step is a row of the profile)
  // Threads per stream for the analysis itself (chunks and the streamed merge, exact). Above 1,
  // accesses are buffered (batch_per_worker ids per thread and stream, or more: see
  // batch_per_distinct) and analysed a batch at a time.
  int workers = 1;
  size_t batch_per_worker = size_t{1} << 22;
  // A chunk pays for each distinct id it meets (its first touch, its place in the stack that
  // flows, its index), so a chunk of far more accesses than the stream has distinct ids gains:
  // a batch holds at least batch_per_distinct x the stream's distinct ids per worker, up to
  // max_batch_per_worker (memory: two batches of 8 bytes an id).
  size_t batch_per_distinct = 8;
  size_t max_batch_per_worker = size_t{1} << 26;
  // One chunk of a trace, for a summary (reports/chunks/summarize_chunk.h): first touches kept, not
  // counted (StreamAnalysis::chunk); serial; sampling at a fixed rate only.
  bool chunk = false;
  // A chunk keeps where each first touch stands in its stream: a summary file holds them, a
  // distributed run needs them only for its profile (kept anyway when the chunk has one). Without
  // them a chunk of 10^6 distinct ids writes 8 MB less, most of it fresh pages.
  bool chunk_positions = true;
  // Sampling (SHARDS) beside or instead of the exact analysis.
  bool exact = true;
  bool sample = false;
  ShardsOptions shards;
  // The capacities (element and line ids) whose sampled miss estimates get a bound
  // (ShardsOptions::watch): the cache levels', set by the caller.
  std::vector<uint64_t> watch_element, watch_line;
  // Histograms of vertex ids reserved up front from the input's vertex and sweep counts; off
  // where those counts are a file's claims that no data backs yet (a summary merge).
  bool reserve = true;
};

class ReuseAnalysis : public AccessConsumer {
 public:
  explicit ReuseAnalysis(const ReuseOptions& o);
  ~ReuseAnalysis() override;
  // From the stream: its thread count, the dense range of element ids (the vertices), whether line
  // ids start at the canonical base (so the direct array covers them), the profile's sweep lengths.
  void Begin(const StreamInfo& info) override;
  void Consume(const Access* a, size_t n) override;
  void End() override;  // analyses what is buffered, closes the samplers

  // Feeding by hand (tests, fuzzers), after Begin: one element touch; one access of `size` bytes
  // (0 counts as 1) at `address`, one line or two if it straddles.
  void AddElement(int thread, uint64_t element) {
    if (do_elements_) Feed(ElementStream(thread), ebuf_[thread], element);
  }
  void AddAccess(int thread, uint64_t address, uint32_t size) {
    if (!do_lines_) return;
    const uint64_t first = LineId(address >> line_shift_);
    const uint64_t last = LineId((address + (size ? size - 1 : 0)) >> line_shift_);
    StreamAnalysis& s = LineStream(thread);
    Feed(s, lbuf_[thread], first);
    if (last != first) Feed(s, lbuf_[thread], last);
  }

  // For a chunk: where it starts in each thread's element and line streams (profile positions).
  void SetStreamOffsets(std::vector<uint64_t> element, std::vector<uint64_t> line) {
    element_offset_ = std::move(element), line_offset_ = std::move(line);
  }
  // Assembling an analysis from parts (merged chunk summaries), between Begin and End: a stream's
  // state, made empty (its profile as Begin's info gives it) on first use; moves added.
  StreamAnalysis& MakeStream(int t, Granularity g) {
    return g == Granularity::kElement ? ElementStream(t) : LineStream(t);
  }
  void AddMoves(int t, uint64_t n) { moves_[t] += n; }

  const StreamInfo& info() const { return info_; }
  const ReuseOptions& options() const { return opt_; }
  int threads() const { return info_.threads; }
  bool has_elements() const { return do_elements_; }
  bool has_lines() const { return do_lines_; }
  // A stream's analysis; nullptr when the granularity is off or the stream had no access.
  const StreamAnalysis* element(int t) const { return Done(element_[t].get()); }
  const StreamAnalysis* line(int t) const { return Done(line_[t].get()); }
  const StreamAnalysis* stream(int t, Granularity g) const {
    return g == Granularity::kElement ? element(t) : line(t);
  }
  // vertices moved: their row-offset reads (one per move; a rank's unpacks write coordinates too)
  uint64_t moves(int t) const { return moves_[t]; }

  // One row per distance bin (exact below `exact_below`, powers of two beyond) and one "cold" row:
  // input, ordering, thread, granularity, lo, hi, count.
  static std::vector<std::string> HistogramColumns();
  void AppendHistogramRows(Table* t, uint64_t exact_below = 64) const;
  // input, ordering, thread, granularity, iteration, step, accesses, cold, mean.
  static std::vector<std::string> ProfileColumns();
  void AppendProfileRows(Table* t) const;
  // input, ordering, thread, granularity, capacity, misses, accesses, miss_ratio, estimated: the
  // exact curve, or SHARDS' estimate when sampling (estimated = 1).
  static std::vector<std::string> MrcColumns();
  void AppendMrcRows(Table* t) const;

 private:
  StreamAnalysis& ElementStream(int t) {
    if (!element_[t]) element_[t] = NewStream(t, Granularity::kElement);
    return *element_[t];
  }
  StreamAnalysis& LineStream(int t) {
    if (!line_[t]) line_[t] = NewStream(t, Granularity::kLine);
    return *line_[t];
  }
  std::unique_ptr<StreamAnalysis> NewStream(int t, Granularity g);
  void Feed(StreamAnalysis& s, std::vector<uint64_t>& buf, uint64_t id) {
    if (opt_.workers <= 1) return s.Add(id);
    // The buffer grows as ids come (a stream of a few accesses holds a few), up to one batch.
    buf.push_back(id);
    if (buf.size() >= s.batch_limit) Flush(s, buf);
  }
  // Hands a full buffer to a thread that analyses it (AddBatch) while the caller goes on reading
  // into the other buffer (double buffering: reading and decoding overlap the analysis).
  // Not yet when the batch in flight raised this stream's limit (unless `last`).
  void Flush(StreamAnalysis& s, std::vector<uint64_t>& buf, bool last = false);
  void Wait();  // the batch in flight analysed (its error rethrown), its buffer spare again
  const StreamAnalysis* Done(const StreamAnalysis* s) const;
  template <class Row>
  void ForEachStream(const Row& row) const;

  ReuseOptions opt_;
  StreamInfo info_;
  int line_shift_ = 6;
  uint64_t line_base_ = 0;
  // Line ids count from the base (the canonical arrays' lines near id 0); lines below it go to
  // the top of the range, so that no line maps to the reserved 2^64-1 (the last byte of the
  // address space, the only line that could, is refused by the readers).
  uint64_t LineId(uint64_t line) const {
    return line >= line_base_ ? line - line_base_ : line + (~uint64_t{0} - line_base_);
  }
  bool do_elements_ = false, do_lines_ = false, ended_ = false;
  std::vector<std::unique_ptr<StreamAnalysis>> element_, line_;
  std::vector<std::vector<uint64_t>> ebuf_, lbuf_;  // per thread stream (workers > 1)
  std::thread batch_thread_;                        // the batch in flight
  std::vector<uint64_t> batch_, spare_;
  StreamAnalysis* batch_stream_ = nullptr;
  std::exception_ptr batch_error_;
  std::vector<uint64_t> moves_;
  std::vector<uint64_t> element_offset_, line_offset_;
};

}  // namespace meshreuse
