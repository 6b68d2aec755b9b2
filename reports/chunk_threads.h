// A ChunkTransport between threads of one process: the distributed analysis (RunDistributed,
// chunk_summary.h) with P ranks as P threads. `meshreuse analyze TRACE --threads P` runs on it:
// each thread reads and analyses its own chunk of the file (reading is parallel too, which the
// batched analyzer's one reader is not), the LRU stacks stream thread to thread in blocks, and the
// resolved chunks are handed over as objects (not encoded) and added up a binary tree, as across
// MPI ranks. The tests run the distributed runner on it without MPI. The stack's blocks between
// two ranks are a bounded queue (memory: a few blocks per link whatever the stack's size). A rank
// that throws fails the network: every rank blocked in it throws too, so a failure never hangs.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "reports/analyze.h"
#include "reports/chunk_summary.h"

namespace meshreuse {

// Whether `in` can be analysed in chunks read by range: a regular file, plain or zstd in at least
// as many frames as threads, each recording its size (`trace --compress`'s 4 MiB frames; not
// standard input, a pipe, or a zstd file in fewer frames, whose later chunks would decompress most
// of it to find their start: those go through the batched analyzer, ReuseOptions::workers), with an
// analysis that chunks support (no fixed-size sample, no exact counting below K).
bool CanAnalyzeInChunks(const AnalyzeConfig& cfg, const std::string& in);
// cfg's one trace analysed as p chunks on p threads (RunDistributed over ChunkThreads): exactly the
// serial analyzer's result. Progress is rank 0's, on `log`.
AnalyzeResult AnalyzeChunksOnThreads(const AnalyzeConfig& cfg, int p, const Log& log);

class ChunkThreads {
 public:
  // Runs body(transport) for ranks 0..size-1, each on a thread of its own, and rethrows the first
  // exception a rank threw.
  static void Run(int size, const std::function<void(ChunkTransport&)>& body);

 private:
  class Endpoint;
  explicit ChunkThreads(int size) : size_(size), ids_(size) {}
  template <class Ready>
  void Wait(std::unique_lock<std::mutex>& lock, Ready ready);

  static constexpr size_t kDepth = 4;  // blocks in flight per link
  int size_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool failed_ = false;
  std::vector<std::deque<std::vector<uint64_t>>> ids_;  // ids_[r]: from rank r - 1 (empty: end)
  std::map<std::pair<int, int>, std::deque<std::string>> bytes_;
  std::map<std::pair<int, int>, std::deque<SummaryFile>> summaries_;  // handed over, not encoded
  int arrived_ = 0;
  uint64_t round_ = 0;
  std::vector<std::vector<uint64_t>> slots_;
  std::vector<std::vector<uint64_t>> results_;
};

}  // namespace meshreuse
