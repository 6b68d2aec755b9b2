// nd: METIS nested dissection (METIS_NodeND; Karypis and Kumar 1998), the fill-reducing order of
// sparse direct solvers: separators last, recursively. METIS's `perm` is new -> old ("row i of A'
// is row perm[i] of A"). Seeded by --seed through METIS_OPTION_SEED, so it is deterministic.
#include "core/orderings/metis_graph.h"
#include "core/orderings/registry.h"
#include "core/stdout_guard.h"

namespace meshreuse {

Permutation OrderNd(const Mesh& m, const OrderingContext& ctx) {
  orderings::MetisGraph g = orderings::ToMetis(m);
  if (g.n == 0) return Permutation::FromNewToOld({});
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = static_cast<idx_t>(ctx.seed & 0x7FFFFFFF);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> perm(g.n), iperm(g.n);
  const StdoutToStderr quiet;  // METIS may printf: stdout holds only results
  orderings::MetisCheck(METIS_NodeND(&g.n, g.xadj.data(), g.adjncy.data(), nullptr, options,
                                     perm.data(), iperm.data()),
                        "METIS_NodeND");
  return Permutation::FromNewToOld(std::vector<int32_t>(perm.begin(), perm.end()));
}

}  // namespace meshreuse
