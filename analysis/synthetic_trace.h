// Synthetic id traces with known reuse structure, for tests, benchmarks and the sampling error
// table: a cyclic scan (every warm distance = ids - 1), uniform random ids, and a mesh-like walk
// (a window sliding over the ids, as a sweep over a well-ordered mesh, with a fraction of
// accesses to uniformly random far ids). Seeded: the same arguments give the same trace.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshreuse {

std::vector<uint64_t> CyclicScanTrace(uint64_t ids, uint64_t laps);
std::vector<uint64_t> UniformTrace(uint64_t ids, uint64_t accesses, uint64_t seed);
// Access i goes to base(i) + a uniform offset in [-16, 16] (mod ids), where base(i) walks over
// the ids `laps` times, laps = max(1, accesses / (15 ids)) (about 15 accesses per id per lap, as a
// sweep's element trace); with probability far_fraction it goes to a uniformly random id instead.
std::vector<uint64_t> MeshLikeTrace(uint64_t ids, uint64_t accesses, double far_fraction,
                                    uint64_t seed);

}  // namespace meshreuse
