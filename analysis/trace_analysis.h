// Reuse analysis of a whole trace: one StackDistance + ReuseHistogram (+ ReuseProfile) per thread
// stream and per granularity, fed in one pass. Element granularity: the element stream (touches
// of vertex records, by vertex id; the paper's model). Line granularity: the address stream (every
// load and store, by byte address / line size); an access that straddles two lines touches both.
// Each thread's stream is analysed on its own (private caches, as the paper's per-core L1/L2).
// AnalysisSink lets the smoother stream into it without a trace file.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "analysis/reuse_histogram.h"
#include "analysis/shards.h"
#include "analysis/stack_distance.h"
#include "tracer/sink.h"

namespace meshreuse {

enum class Granularity { kElement = 1, kLine = 2, kBoth = 3 };
Granularity ParseGranularity(const std::string& s);  // element | line | both
const char* GranularityName(Granularity g);

struct StreamAnalysis {
  // exact: the exact analyzer runs; sample: SHARDS runs too (both: its error can be measured).
  explicit StreamAnalysis(uint64_t dense_limit, bool exact = true,
                          const ShardsOptions* sample = nullptr)
      : sd(exact ? dense_limit : 0), dense_limit(dense_limit), exact(exact) {
    if (exact) hist.Reserve(dense_limit);
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
    if (shards) shards->Access(id);
  }
  uint64_t AddExact(uint64_t id) {  // the access's distance (StackDistance::kCold if cold)
    const uint64_t d = sd.Access(id);
    hist.Add(d);
    if (profile.enabled()) profile.Add(d);
    return d;
  }
  // The next n accesses at once, on `threads` OpenMP threads (parallel_stack_distance.h): the
  // same histogram and profile as n calls of Add.
  void AddBatch(const uint64_t* ids, size_t n, int threads);
};

struct TraceAnalysisOptions {
  int threads = 1;
  Granularity granularity = Granularity::kBoth;
  uint32_t line_bytes = 64;     // a power of two
  uint64_t dense_elements = 0;  // element ids below this use direct arrays (0: hash everything)
  // Line ids are (address >> log2 line_bytes) - line_base: the swept arrays' canonical addresses
  // start at AddressCanonicalizer::kCanonicalBase, and starting their lines near id 0 lets the
  // analyzer's direct array cover them (above, every line id would be hashed or the array would
  // span 2^26 empty ids: 270 MB). A bijection, so every distance is unchanged.
  uint64_t line_base = 0;
  // iteration_lengths[t] = element accesses of each iteration in thread t's stream, and
  // line_iteration_lengths[t] its line accesses (loads and stores); empty: no profile.
  std::vector<std::vector<uint64_t>> iteration_lengths;
  std::vector<std::vector<uint64_t>> line_iteration_lengths;
  int profile_steps = 100;
  // Threads per stream for the analysis itself (chunk-and-merge, exact). Above 1, accesses are
  // buffered (batch_per_worker ids per thread and stream) and analysed a batch at a time; call
  // Finish() before reading the results.
  int workers = 1;
  size_t batch_per_worker = size_t{1} << 22;
  // Sampling (SHARDS) beside or instead of the exact analysis.
  bool exact = true;
  bool sample = false;
  ShardsOptions shards;
};

class TraceAnalysis {
 public:
  explicit TraceAnalysis(const TraceAnalysisOptions& o);
  void AddElement(int thread, uint64_t element) {
    if (element_[thread]) Feed(*element_[thread], ebuf_[thread], element);
  }
  // An access of `size` bytes (0 counts as 1) at `address`: one line, or two if it straddles.
  void AddAccess(int thread, uint64_t address, uint32_t size) {
    if (!line_[thread]) return;
    const uint64_t first = (address >> line_shift_) - opt_.line_base;
    const uint64_t last = ((address + (size ? size - 1 : 0)) >> line_shift_) - opt_.line_base;
    Feed(*line_[thread], lbuf_[thread], first);
    if (last != first) Feed(*line_[thread], lbuf_[thread], last);
  }
  // Analyses what is buffered (workers > 1) and closes the samplers; call it once at the end.
  void Finish();
  int threads() const { return static_cast<int>(element_.size()); }
  bool has_lines() const {
    return static_cast<int>(opt_.granularity) & static_cast<int>(Granularity::kLine);
  }
  const StreamAnalysis* element(int t) const { return Done(element_[t].get()); }
  const StreamAnalysis* line(int t) const { return Done(line_[t].get()); }
  const TraceAnalysisOptions& options() const { return opt_; }

 private:
  void Feed(StreamAnalysis& s, std::vector<uint64_t>& buf, uint64_t id) {
    if (opt_.workers <= 1) return s.Add(id);
    buf.push_back(id);
    if (buf.size() == buf.capacity()) Flush(s, buf);
  }
  void Flush(StreamAnalysis& s, std::vector<uint64_t>& buf);
  const StreamAnalysis* Done(const StreamAnalysis* s) const;
  TraceAnalysisOptions opt_;
  int line_shift_;
  std::vector<std::unique_ptr<StreamAnalysis>> element_, line_;
  std::vector<std::vector<uint64_t>> ebuf_, lbuf_;  // per thread stream (workers > 1)
};

struct AnalysisSink {
  static constexpr bool kEnabled = true;
  explicit AnalysisSink(TraceAnalysis* a) : analysis(a) {}
  TraceAnalysis* analysis;
  AddressCanonicalizer canon;  // line numbers independent of this run's heap (sink.h)
  void Bind(const ArrayLayout& l) { canon = AddressCanonicalizer(l); }
  void BeginSweep(int) {}
  void Access(int thread, const MemRef& r) {
    if (r.element != AccessKind::kNone)
      analysis->AddElement(thread, static_cast<uint32_t>(r.vertex));
    if (analysis->has_lines()) analysis->AddAccess(thread, canon(thread, r), r.size);
  }
};

// Other tools' traces, each record one access (value, size in bytes):
//   text    a decimal or 0x-hex id per line, '#' comments and blank lines skipped ("-": stdin)
//   u32/u64 raw little-endian values, 4 or 8 bytes each
//   parda   PARDA's binary input (Niu et al.): the 8-byte pointers it freads, little-endian on
//           x86-64 -- the same bytes as u64
//   oracle  libCacheSim's oracleGeneral: 24-byte packed little-endian records {uint32 clock,
//           uint64 obj_id, uint32 obj_size, int64 next_access_vtime}; the id is obj_id
//   lackey  valgrind --tool=lackey --trace-mem=yes output as is: " L addr,size", " S", " M" (a
//           modify is a load then a store), "I" (instruction fetches, skipped unless
//           `instructions`); valgrind's "==PID==" lines skipped
// Any of them may be zstd-compressed (read transparently). Calls add(value, size); throws
// InputError naming the file and the line (text, lackey) or record and byte offset (binary).
enum class ExternalFormat { kText, kU32, kU64, kParda, kOracle, kLackey };
ExternalFormat ParseExternalFormat(const std::string& s);
size_t ExternalRecordBytes(ExternalFormat fmt);  // 0 for the line formats
template <class F>
void ReadExternalTrace(const std::string& path, ExternalFormat fmt, F&& add,
                       bool instructions = false);
// Accesses in a binary trace (from its size, decompressed when zstd records it); 0 if unknown.
uint64_t ExternalTraceLength(const std::string& path, ExternalFormat fmt);

}  // namespace meshreuse

#include "analysis/external_trace_impl.h"
