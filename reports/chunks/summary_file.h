// The chunk summary file (reports/chunks/; ../shared/scale-out.md 3a, 6): what one chunk of a
// trace's (or a mesh stream's) reuse analysis leaves for the merge. Per thread stream and
// granularity: the chunk's first touches (ids, places), its LRU stack (bottom-up), the distances
// decided inside it as (distance, count) pairs, its profile steps, and its accesses. The file
// (version 1, little-endian): magic "MRSUMRY\0", u32 version, u32 0, u64 payload bytes, u64
// checksum of the payload, then the payload (identity, chunk, stream info, streams). Decoding
// trusts no count before the bytes that hold it are there: a truncated, corrupt or foreign
// summary is an InputError naming it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "analysis/parallel_stack_distance.h"
#include "analysis/reuse_analysis.h"
#include "tracer/access_stream.h"

namespace meshreuse {

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
// The same hash, of bytes given in pieces (n in all): what ties a summary to its input's bytes.
class SummaryHasher {
 public:
  explicit SummaryHasher(uint64_t n);
  ~SummaryHasher();
  void Add(const char* p, size_t n);
  uint64_t Finish() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};
SummaryFile ReadSummary(const std::string& path);  // InputError naming the file and the problem

// "3/8": how messages name chunk r of P.
std::string ChunkName(uint32_t r, uint32_t p);

}  // namespace meshreuse
