// The distributed analysis (RunDistributed, distributed_analysis.h) with P ranks as P threads of
// one process (core/ranks/thread_communicator.h). `meshreuse analyze TRACE --threads P` runs on it:
// each thread reads and analyses its own chunk of the file (reading is parallel too, which the
// batched analyzer's one reader is not), the LRU stacks stream thread to thread in blocks, and the
// resolved chunks are handed over as objects (not encoded) and added up a binary tree, as across
// MPI ranks. The tests run the distributed runner on it without MPI. The stack's blocks between
// two ranks are a bounded queue (memory: a few blocks per link whatever the stack's size). A rank
// that throws fails the network: every rank blocked in it throws too, so a failure never hangs.
#pragma once

#include <cstdint>
#include <string>

#include "reports/log.h"
#include "reports/reuse_job.h"

namespace meshreuse {

// Whether `in` can be analysed in chunks read by range: a regular file, plain or zstd in at least
// as many frames as threads, each recording its size (`trace --compress`'s 4 MiB frames; not
// standard input, a pipe, or a zstd file in fewer frames, whose later chunks would decompress most
// of it to find their start: those go through the batched analyzer, ReuseOptions::workers), with an
// analysis that chunks support (no fixed-size sample, no exact counting below K).
bool CanAnalyzeInChunks(const ReuseJob& cfg, const std::string& in);
// cfg's one trace analysed as p chunks on p threads (RunDistributed over a ThreadCommunicator):
// exactly the serial analyzer's result. Progress is rank 0's, on `log`.
AnalyzeResult AnalyzeChunksOnThreads(const ReuseJob& cfg, int p, const Log& log);

}  // namespace meshreuse
