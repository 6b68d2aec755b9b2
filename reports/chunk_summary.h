// Exact reuse analysis of a trace in chunks that any batch system can run (SLURM arrays, GNU
// parallel, a shell loop), then one merge (../shared/scale-out.md sections 3a and 6):
//   meshreuse analyze TRACE --chunk r/P --summary-out S_r    (r = 0..P-1, anywhere, any order)
//   meshreuse analyze --merge S_0 ... S_{P-1}                 (the serial analyzer's every output)
// Chunk r takes records [N r / P, N (r + 1) / P) of a meshreuse trace or a fixed-record trace
// (u32, u64, parda, oracle), read by range from a plain file (a zstd or text trace cannot be
// entered in the middle: refused, saying so). Per thread stream and granularity its summary holds
// the chunk's first touches (ids, places), its LRU stack (bottom-up), the distances decided inside
// it as (distance, count) pairs, its profile steps, and its accesses; the merge streams the stack
// through the chunks in order (analysis/streamed_chain.h, ResolveChunk) and adds integers, so the
// result equals the serial analyzer's whatever machine ran which chunk.
// The profile places accesses by their position in their stream: a chunk of a meshreuse trace
// reads back to the start of the sweep it begins in (at most one sweep more) to count where its
// streams start; line positions assume no access straddling two lines before the chunk, and the
// merge checks that assumption against the true positions and refuses, saying so, if it fails.
// The file (version 1, little-endian): magic "MRSUMRY\0", u32 version, u32 0, u64 payload bytes,
// u64 checksum of the payload, then the payload (identity, chunk, stream info, streams). A
// missing, repeated, reordered, truncated, corrupt or foreign summary is an InputError naming it.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "analysis/parallel_stack_distance.h"
#include "reports/analyze.h"
#include "tracer/access_stream.h"

namespace meshreuse {

// "r/P" with 0 <= r < P <= 2^20 (UsageError otherwise).
std::pair<uint32_t, uint32_t> ParseChunk(const std::string& s);

struct StreamSummary {
  uint32_t thread = 0;
  Granularity granularity = Granularity::kElement;
  uint64_t accesses = 0;  // the stream's accesses in the chunk
  uint64_t offset = 0;    // where the chunk starts in the stream (as the chunk counted it)
  ChunkSummary chunk;     // first touches and the stack
  std::vector<std::pair<uint64_t, uint64_t>> hist;  // distances decided in the chunk, counts
  struct Step {
    uint64_t index, accesses, cold;
    unsigned __int128 sum;
  };
  std::vector<Step> profile;  // non-empty steps
};

struct SummaryIdentity {                      // what every summary of one analysis shares
  std::string format;                         // "" for a meshreuse trace
  uint64_t input_bytes = 0, fingerprint = 0;  // the input file's size and a hash of its ends
  uint32_t granularity = 0, line_bytes = 0, instructions = 0, chunks = 0;
  bool operator==(const SummaryIdentity& o) const;
};

struct SummaryFile {
  SummaryIdentity id;
  std::string input;  // as given to the chunk run
  uint32_t chunk = 0;
  uint64_t first = 0, end = 0, total = 0;  // records [first, end) of total
  StreamInfo info;
  std::vector<uint64_t> moves;  // per thread
  std::vector<StreamSummary> streams;
};

void WriteSummary(const std::string& path, const SummaryFile& s);
// The checksum the header holds, of the payload bytes (for tests that edit a payload).
uint64_t SummaryChecksum(const char* payload, size_t n);
SummaryFile ReadSummary(const std::string& path);  // InputError naming the file and the problem

// The chunk run: cfg.inputs holds one trace; writes cfg.summary_out.
void RunChunk(const AnalyzeConfig& cfg, const Log& log);
// The merge: cfg.inputs are summaries of chunks 0..P-1, in order.
AnalyzeResult MergeSummaries(const AnalyzeConfig& cfg, const Log& log);

}  // namespace meshreuse
