// Exact reuse analysis of a trace in chunks that any batch system can run (SLURM arrays, GNU
// parallel, a shell loop), then one merge (../shared/scale-out.md sections 3a and 6):
//   meshreuse analyze TRACE --chunk r/P --summary-out S_r    (r = 0..P-1, anywhere, any order)
//   meshreuse analyze --merge S_0 ... S_{P-1}                 (the serial analyzer's every output)
// Chunk r takes records [N r / P, N (r + 1) / P) of a meshreuse trace or a fixed-record trace
// (u32, u64, parda, oracle), or of a text or lackey trace the whole lines that begin in bytes
// [B r / P, B (r + 1) / P), read by range from a plain file (a zstd trace cannot be entered in
// the middle: refused, saying so). Per thread stream and granularity its summary holds
// the chunk's first touches (ids, places), its LRU stack (bottom-up), the distances decided inside
// it as (distance, count) pairs, its profile steps, and its accesses; the merge streams the stack
// through the chunks in order (analysis/streamed_chain.h, ResolveChunk) and adds integers, so the
// result equals the serial analyzer's whatever machine ran which chunk.
// The profile places accesses by their position in their stream: a chunk of a meshreuse trace
// reads back to the start of the sweep it begins in (at most one sweep more) to count where its
// streams start, a chunk of a mesh's stream regenerates from there (SweepsOfMeshChunk); line
// positions assume no access straddling two lines before the chunk, and the merge checks that
// assumption against the true positions and refuses, saying so, if it fails. The file (version 1,
// little-endian): magic "MRSUMRY\0", u32 version, u32 0, u64 payload bytes, u64 checksum of the
// payload, then the payload (identity, chunk, stream info, streams). A missing, repeated,
// reordered, truncated, corrupt or foreign summary is an InputError naming it.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "analysis/parallel_stack_distance.h"
#include "core/ranks/communicator.h"
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
  // Resolved (a distributed run's chunk after the stack went through it): the first touches'
  // distances are in hist (cold ones as StackDistance::kCold) and profile; no first touches or
  // stack.
  bool resolved = false;
  // Resolved, its histogram travelling apart (RunDistributed's reduce-scatter by distance): hist
  // is empty here, and does not add up to the accesses.
  bool hist_apart = false;
  // The stream's sampled ids (SHARDS at a fixed rate) as a chunk of their own: accesses and
  // first touches are the sampled ones; stream_accesses counts all of the stream's in the chunk.
  bool sampled = false;
  uint64_t stream_accesses = 0;
};

struct SummaryIdentity {                      // what every summary of one analysis shares
  std::string format;                         // "" for a meshreuse trace
  uint64_t input_bytes = 0, fingerprint = 0;  // the input file's size and a hash of its ends
  uint32_t granularity = 0, line_bytes = 0, instructions = 0, chunks = 0;
  uint32_t exact = 1, sample = 0;  // the exact analysis; SHARDS at a fixed rate
  double rate = 0;
  uint64_t seed = 0;
  bool operator==(const SummaryIdentity& o) const;
};

struct SummaryFile {
  SummaryIdentity id;
  std::string input;  // as given to the chunk run
  uint32_t chunk = 0;
  uint64_t first = 0, end = 0, total = 0;  // records [first, end) of total (text: bytes)
  StreamInfo info;
  std::vector<uint64_t> moves;  // per thread
  std::vector<StreamSummary> streams;
};

std::string EncodeSummary(const SummaryFile& s);  // the file's bytes
// From bytes (a file's, or with from_rank a rank's message, which may hold resolved streams);
// `name` names them in errors.
SummaryFile DecodeSummary(const std::string& name, const std::string& bytes,
                          bool from_rank = false);
void WriteSummary(const std::string& path, const SummaryFile& s);
// The checksum the header holds, of the payload bytes (for tests that edit a payload).
uint64_t SummaryChecksum(const char* payload, size_t n);
SummaryFile ReadSummary(const std::string& path);  // InputError naming the file and the problem

// Chunk r of P of cfg.inputs[0] (one trace), analysed into its summary.
SummaryFile SummarizeChunk(const AnalyzeConfig& cfg, uint32_t r, uint32_t p, const Log& log);

// The sweeps a chunk of records [first, end) of a mesh's stream (`whole`: MeshStreamInfo)
// regenerates: from the one `first` lies in (the one before it for an even Jacobi sweep, whose
// buffers the odd sweeps share) to the one `end - 1` lies in, and the records before `from`.
// An empty chunk regenerates none (from 1, to 0).
struct MeshChunkSweeps {
  int from = 1, to = 0;
  uint64_t skipped = 0;
};
MeshChunkSweeps SweepsOfMeshChunk(const StreamInfo& whole, UpdateMode mode, uint64_t first,
                                  uint64_t end);
// The chunk run: writes cfg.summary_out.
void RunChunk(const AnalyzeConfig& cfg, const Log& log);

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
// The merge: cfg.inputs are summaries of chunks 0..P-1, in order.
AnalyzeResult MergeSummaries(const AnalyzeConfig& cfg, const Log& log);

// The chunk relay's messages over the one message layer (core/ranks/communicator.h): blocks of an
// LRU stack's ids to the next rank (an empty block ends a stream), and resolved chunks handed on
// (the object itself between ranks that share memory, its encoding elsewhere).
void SendIds(Communicator& c, const uint64_t* ids, size_t n);  // to rank + 1
size_t RecvIds(Communicator& c, std::vector<uint64_t>* ids);   // from rank - 1; 0: a stream's end
uint64_t SendSummary(Communicator& c, int32_t to, SummaryFile&& s);  // returns the bytes sent
SummaryFile RecvSummary(Communicator& c, int32_t from, const std::string& name);

// Rank r analyses chunk r of P = size() (reading only its own records), the LRU stacks stream
// rank to rank, each rank resolves its first touches, and a binary tree of ranks adds the
// resolved chunks up to rank 0: its result equals the serial analyzer's; the other ranks return
// an empty result.
AnalyzeResult RunDistributed(const AnalyzeConfig& cfg, Communicator& tx, const Log& log);

}  // namespace meshreuse
