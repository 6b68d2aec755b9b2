// The analysis of a trace as chunks on threads (chunk_threads.h).
#include "reports/chunks/chunk_threads.h"

#include <sys/stat.h>

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <thread>

#include "core/ranks/thread_communicator.h"
#include "reports/chunks/distributed_analysis.h"
#include "tracer/input_stream.h"

namespace meshreuse {

bool CanAnalyzeInChunks(const ReuseJob& cfg, const std::string& in) {
  if (in == "-" || (cfg.sample && (cfg.shards.s_max || cfg.shards.exact_below))) return false;
  if (cfg.IdsOf(in)) return true;  // ids in memory: cut as a u64 file of them
  struct stat st;
  if (::stat(in.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  try {
    const InputStream s(in);
    return !s.compressed() ||
           (s.seekable() && s.entry_points() >= static_cast<uint64_t>(std::max(cfg.threads, 1)));
  } catch (const std::exception&) {
    return false;  // the batched analyzer reports it
  }
}

AnalyzeResult AnalyzeChunksOnThreads(const ReuseJob& cfg, int p, const Log& log) {
  ReuseJob one = cfg;
  one.threads = 1;  // each chunk on its own thread
  AnalyzeResult result;
  const Log quiet;
  ThreadCommunicator::Run(p, [&](Communicator& tx) {
    AnalyzeResult r = RunDistributed(one, tx, tx.rank() == 0 ? log : quiet);
    if (tx.rank() == 0) result = std::move(r);
  });
  return result;
}

}  // namespace meshreuse
