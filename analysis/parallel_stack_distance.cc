// ParallelStackDistances; see parallel_stack_distance.h.
#include "analysis/parallel_stack_distance.h"

#include <omp.h>

#include <algorithm>

namespace meshreuse {

std::vector<uint64_t> ParallelStackDistances(const std::vector<uint64_t>& ids, int threads,
                                             uint64_t dense_limit, StackDistance* running) {
  const size_t n = ids.size();
  const int p = static_cast<int>(std::max<size_t>(1, std::min<size_t>(threads, n)));
  std::vector<uint64_t> out(n);
  std::vector<ChunkSummary> chunks(p);
  auto begin = [&](int c) { return n * c / p; };
#pragma omp parallel for num_threads(p) schedule(static, 1)
  for (int c = 0; c < p; ++c) {
    uint64_t* o = out.data() + begin(c);
    chunks[c] = AnalyzeChunk(ids.data() + begin(c), begin(c + 1) - begin(c), dense_limit,
                             [o](size_t i, uint64_t d) { o[i] = d; });
  }
  for (int c = 0; c < p; ++c) {
    uint64_t* o = out.data() + begin(c);
    MergeChunk(running, chunks[c], [o](size_t i, uint64_t d) { o[i] = d; });
  }
  return out;
}

}  // namespace meshreuse
