// One chunk of a reuse analysis, anywhere a batch system runs it (SLURM arrays, GNU parallel, a
// shell loop; ../shared/scale-out.md 3a):
//   meshreuse analyze TRACE --chunk r/P --summary-out S_r    (r = 0..P-1, anywhere, any order)
// Chunk r takes records [N r / P, N (r + 1) / P) of a meshreuse trace or a fixed-record trace
// (u32, u64, parda, oracle), of a text or lackey trace the whole lines that begin in bytes
// [B r / P, B (r + 1) / P), read by range from a plain file or a zstd one in sized frames, or of a
// mesh's stream in one ordering, regenerated (no file). The profile places accesses by their
// position in their stream: a chunk of a meshreuse trace reads back to the start of the sweep it
// begins in (at most one sweep more) to count where its streams start, a chunk of a mesh's stream
// regenerates from there (SweepsOfMeshChunk); line positions assume no access straddling two lines
// before the chunk, which the merge checks (merge_summaries.h). The chunk's identity ties it to
// its input: a trace file's size and a hash of its ends, a laid-out mesh's content hash.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "reports/chunks/summary_file.h"
#include "reports/log.h"
#include "reports/reuse_job.h"

namespace meshreuse {

// "r/P" with 0 <= r < P <= 2^20 (UsageError otherwise).
std::pair<uint32_t, uint32_t> ParseChunk(const std::string& s);

// Chunk r of P of job.inputs[0] (one trace, or one mesh in one ordering), analysed into its
// summary. `distributed`: a rank of a distributed run (distributed_analysis.h), whose last chunk
// keeps no stack and whose chunks keep first-touch places only for a profile.
SummaryFile SummarizeChunk(const ReuseJob& job, uint32_t r, uint32_t p, bool distributed,
                           const Log& log);
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
// The chunk run: chunk r of P summarised into the file `out`.
void RunChunk(const ReuseJob& job, uint32_t r, uint32_t p, const std::string& out, const Log& log);

}  // namespace meshreuse
