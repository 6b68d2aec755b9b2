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
#include "analysis/stack_distance.h"
#include "tracer/sink.h"

namespace meshreuse {

enum class Granularity { kElement = 1, kLine = 2, kBoth = 3 };
Granularity ParseGranularity(const std::string& s);  // element | line | both
const char* GranularityName(Granularity g);

struct StreamAnalysis {
  explicit StreamAnalysis(uint64_t dense_limit) : sd(dense_limit), dense_limit(dense_limit) {
    hist.Reserve(dense_limit);
  }
  StackDistance sd;  // the stream's LRU stack (its distinct() is the stream's distinct ids)
  ReuseHistogram hist;
  ReuseProfile profile;
  uint64_t dense_limit;
  void Add(uint64_t id) {
    const uint64_t d = sd.Access(id);
    hist.Add(d);
    if (profile.enabled()) profile.Add(d);
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
    const uint64_t first = address >> line_shift_;
    const uint64_t last = (address + (size ? size - 1 : 0)) >> line_shift_;
    Feed(*line_[thread], lbuf_[thread], first);
    if (last != first) Feed(*line_[thread], lbuf_[thread], last);
  }
  void Finish();  // analyses what is buffered (workers > 1); results are complete after it
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

// Other tools' traces: one id or address per record. Text: a decimal or 0x-hex number per line,
// '#' comments and blank lines skipped ("-" reads stdin). u32 / u64: raw little-endian values.
// Calls `add(value)` for each; throws InputError naming the file and line (text) or byte offset.
enum class ExternalFormat { kText, kU32, kU64 };
ExternalFormat ParseExternalFormat(const std::string& s);
template <class F>
void ReadExternalTrace(const std::string& path, ExternalFormat fmt, F&& add);
uint64_t ExternalTraceLength(const std::string& path, ExternalFormat fmt);  // 0 if unknown (text)

}  // namespace meshreuse

#include "analysis/external_trace_impl.h"
