// The reorder runner; see reorder.h.
#include "reports/reorder.h"

#include <algorithm>
#include <chrono>

#include "core/mesh_io.h"
#include "core/orderings/rdr.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/quality.h"
#include "reports/inputs.h"

namespace meshreuse {

ReorderResult RunReorder(const ReorderConfig& cfg, const Log& log) {
  const OrderingSpec spec = ParseOrderingSpec(cfg.ordering);
  for (const std::string& f : MeshOutputFiles(cfg.output))
    CheckOutputPath(f, "-o", InputFiles({cfg.mesh}));
  CheckOutputPath(cfg.output + ".perm", "-o", InputFiles({cfg.mesh}));
  const Mesh m = LoadMesh(cfg.mesh, log);
  ReorderResult r;
  auto t0 = std::chrono::steady_clock::now();
  const Permutation p = ComputeOrdering(cfg.ordering, m, cfg.seed);
  r.order_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  const Mesh out = ApplyPermutation(m, p, cfg.triangle_order);
  r.apply_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.written = SaveMesh(out, cfg.output, log);
  WritePermutation(p.new_to_old(), cfg.output + ".perm",
                   "meshreuse reorder " + cfg.mesh + " --ordering " + cfg.ordering +
                       (spec.info->seeded ? " --seed " + std::to_string(cfg.seed) : ""));
  r.written.push_back(cfg.output + ".perm");
  if (spec.name == "rdr" || spec.name == "rdr-frontier") {  // the chains behind the order
    RdrChains c;
    (spec.name == "rdr" ? RdrOrder : RdrFrontierOrder)(m, VertexQualities(m), &c);
    std::vector<int64_t> n;
    for (int64_t k : c.placed)
      if (k > 0) n.push_back(k);
    std::sort(n.begin(), n.end());
    if (!n.empty()) {
      r.chains = static_cast<int64_t>(n.size());
      r.longest = n.back();
      r.median = n[n.size() / 2];
      r.short_chains = std::lower_bound(n.begin(), n.end(), 10) - n.begin();
    }
  }
  return r;
}

}  // namespace meshreuse
