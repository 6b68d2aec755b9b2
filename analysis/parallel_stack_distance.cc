// ParallelStackDistances; see parallel_stack_distance.h.
#include "analysis/parallel_stack_distance.h"

#include <algorithm>

#include "analysis/streamed_chain.h"

namespace meshreuse {

std::vector<uint64_t> ParallelStackDistances(const std::vector<uint64_t>& ids, int threads,
                                             uint64_t dense_limit, std::vector<uint64_t>* stack) {
  const size_t n = ids.size();
  const int p = static_cast<int>(std::max<size_t>(1, std::min<size_t>(std::max(threads, 1), n)));
  std::vector<uint64_t> out(n);
  auto begin = [&](int c) { return n * c / p; };
  StreamedChain(
      p, stack,
      [&](int c) {
        uint64_t* o = out.data() + begin(c);
        return AnalyzeChunk(ids.data() + begin(c), begin(c + 1) - begin(c), dense_limit,
                            [o](size_t i, uint64_t d) { o[i] = d; });
      },
      [&](int c, const ChunkSummary& s, const std::vector<uint64_t>& first) {
        uint64_t* o = out.data() + begin(c);
        for (size_t k = 0; k < first.size(); ++k) o[s.first_positions[k]] = first[k];
      });
  return out;
}

}  // namespace meshreuse
