// The merge of chunk summaries (../shared/scale-out.md 3a, 6):
//   meshreuse analyze --merge S_0 ... S_{P-1}                 (the serial analyzer's every output)
// The merge streams each stream's LRU stack through the chunks in order (analysis/streamed_chain.h,
// ResolveChunk) and adds integers, so the result equals the serial analyzer's whatever machine ran
// which chunk. A missing, repeated, reordered or foreign summary is an InputError naming it; a
// profile whose chunk offsets disagree with the true positions (accesses straddling two lines
// before a chunk) is refused, saying so.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "reports/chunks/summary_file.h"
#include "reports/log.h"
#include "reports/reuse_job.h"

namespace meshreuse {

// Summaries of chunks 0..P-1 added in order into one analysis (InputError naming the one that is
// out of order, foreign or missing).
class SummaryMerger {
 public:
  // reread: the trace named in the summaries is at hand (a distributed run): a lackey trace
  // without records is read whole again for the message a whole read gives.
  explicit SummaryMerger(bool profile, bool reread = false);
  ~SummaryMerger();
  void Add(SummaryFile s, const std::string& name, size_t given);  // `given`: summaries in all
  AnalyzeResult Finish();

 private:
  bool profile_;
  std::unique_ptr<ReuseAnalysis> a_;
  struct Sampled {  // a stream's sampled ids, merged as a stream of their own
    Sampled() { hist.UsePages(); }
    std::vector<uint64_t> stack;
    ReuseHistogram hist;
    uint64_t accesses = 0;  // the whole stream's
  };
  std::map<std::pair<int, int>, Sampled> sampled_;  // by (thread, granularity)
  ShardsOptions shards_;
  SummaryIdentity id_;
  Granularity granularity_ = Granularity::kBoth;
  std::string first_name_;
  uint32_t expect_ = 0;
  uint64_t next_record_ = 0;
  bool reread_ = false, any_access_ = false;
  std::string input_;
};
// The merge: `paths` are the summaries of chunks 0..P-1, in order.
AnalyzeResult MergeSummaries(const std::vector<std::string>& paths, bool profile, const Log& log);

}  // namespace meshreuse
