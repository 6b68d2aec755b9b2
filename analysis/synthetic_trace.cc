// Synthetic id traces; see synthetic_trace.h.
#include "analysis/synthetic_trace.h"

#include <algorithm>
#include <stdexcept>

#include "core/synthetic.h"

namespace meshreuse {

std::vector<uint64_t> CyclicScanTrace(uint64_t ids, uint64_t laps) {
  std::vector<uint64_t> t;
  t.reserve(ids * laps);
  for (uint64_t l = 0; l < laps; ++l)
    for (uint64_t i = 0; i < ids; ++i) t.push_back(i);
  return t;
}

std::vector<uint64_t> UniformTrace(uint64_t ids, uint64_t accesses, uint64_t seed) {
  if (ids == 0) throw std::invalid_argument("a trace needs at least one id");
  SplitMix64 rng(seed);
  std::vector<uint64_t> t(accesses);
  for (uint64_t& v : t) v = rng.Below(ids);
  return t;
}

std::vector<uint64_t> MeshLikeTrace(uint64_t ids, uint64_t accesses, double far_fraction,
                                    uint64_t seed) {
  if (ids == 0) throw std::invalid_argument("a trace needs at least one id");
  SplitMix64 rng(seed);
  const uint64_t laps = std::max<uint64_t>(1, accesses / (15 * ids));
  const uint64_t far = static_cast<uint64_t>(far_fraction * 0x1.0p53);
  std::vector<uint64_t> t(accesses);
  for (uint64_t i = 0; i < accesses; ++i) {
    const uint64_t base = static_cast<uint64_t>(static_cast<unsigned __int128>(i) * laps * ids /
                                                std::max<uint64_t>(1, accesses));
    if ((rng.Next() >> 11) < far)
      t[i] = rng.Below(ids);
    else
      t[i] = (base + ids * 2 + rng.Below(33) - 16) % ids;
  }
  return t;
}

}  // namespace meshreuse
