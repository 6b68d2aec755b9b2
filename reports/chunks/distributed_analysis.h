// The exact reuse analysis of one input across ranks (../shared/scale-out.md 3a; meshreuse-mpi
// analyze, and `analyze TRACE --threads P` on threads): rank r analyses chunk r of P = size()
// (reading only its own records, summarize_chunk.h), the LRU stacks stream rank to rank, each rank
// resolves its first touches, the histograms are added up (a tree of ranks, or by distance from
// ReuseJob::scatter_from_ranks on) and rank 0 merges: its result equals the serial analyzer's; the
// other ranks return an empty result. Over the one message layer (core/ranks/communicator.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/ranks/communicator.h"
#include "reports/chunks/summary_file.h"
#include "reports/log.h"
#include "reports/reuse_job.h"

namespace meshreuse {

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
AnalyzeResult RunDistributed(const ReuseJob& job, Communicator& tx, const Log& log);

}  // namespace meshreuse
