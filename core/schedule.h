// OpenMP's schedule(static) without a chunk size, as libgomp splits it: P contiguous blocks of
// n / P iterations, the first n % P of them one longer. The smoother's threads take their shares of
// the interior list this way, so the stream of each thread depends on the mesh and the thread count
// alone: traced runs, the analyzer's per-thread profiles and the many-core streams all use these.
#pragma once

#include <cstdint>
#include <string>

#include "core/error.h"

namespace meshreuse {

// The most threads (streams) any command takes: a trace record names its thread in one byte.
inline constexpr int kMaxThreads = 256;

// The most (sweep, stream) pairs a traced run may have: the analyses keep state and write rows per
// sweep and stream (profiles, per-sweep counts, per-sweep misses), so the product of two options,
// or of a trace header's two counts, is bounded before anything is allocated.
inline constexpr int64_t kMaxStreamSweeps = int64_t{1} << 16;
inline void CheckStreamSweeps(int64_t sweeps, int64_t threads) {
  if (sweeps * threads > kMaxStreamSweeps)
    throw UsageError("--iterations " + std::to_string(sweeps) + " x --threads " +
                     std::to_string(threads) + " = " + std::to_string(sweeps * threads) +
                     " (sweep, stream) pairs: at most " + std::to_string(kMaxStreamSweeps) +
                     " (each keeps per-sweep state and rows)");
}

// The thread that iteration k of n goes to with `threads` threads.
inline int StaticOwner(int64_t k, int64_t n, int threads) {
  const int64_t q = n / threads, r = n % threads;
  return static_cast<int>(k < r * (q + 1) ? k / (q + 1) : r + (k - r * (q + 1)) / (q > 0 ? q : 1));
}
// The same split as a range: thread t of P gets [*b, *e).
inline void StaticRange(int64_t n, int threads, int t, int64_t* b, int64_t* e) {
  const int64_t q = n / threads, r = n % threads;
  *b = t < r ? t * (q + 1) : r * (q + 1) + (t - r) * q;
  *e = *b + (t < r ? q + 1 : q);
}

}  // namespace meshreuse
