// random: a uniform shuffle (Fisher-Yates) driven by SplitMix64 seeded with --seed, so the same
// seed gives the same order on every platform. The paper's worst case (its Figure 1).
#include "core/orderings/registry.h"
#include "core/synthetic.h"

namespace meshreuse {

Permutation OrderRandom(const Mesh& m, const OrderingContext& ctx) {
  const int32_t n = m.NumVertices();
  std::vector<int32_t> order(n);
  for (int32_t i = 0; i < n; ++i) order[i] = i;
  SplitMix64 rng(ctx.seed);
  for (int32_t i = n - 1; i > 0; --i) std::swap(order[i], order[rng.Below(uint64_t(i) + 1)]);
  return Permutation::FromNewToOld(std::move(order));
}

}  // namespace meshreuse
