// meshreuse reorder: a mesh in an ordering, written with its permutation (reports/reorder.h).
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/orderings/registry.h"
#include "reports/reorder.h"

namespace meshreuse::cli {

int ReorderCommand(const Args& args) {
  po::options_description desc("options");
  ReorderConfig cfg;
  std::string triangle_order, seed = "1";
  desc.add_options()("mesh", po::value(&cfg.mesh)->required(), "input mesh")(
      "ordering", po::value(&cfg.ordering)->required(), ("one of: " + OrderingNames()).c_str())(
      "seed", po::value(&seed)->default_value("1"), "seed of seeded orderings")(
      "output,o", po::value(&cfg.output)->required(),
      "prefix: writes PREFIX.node, PREFIX.ele and PREFIX.perm (the permutation, file: format)")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(args, "reorder MESH --ordering NAME -o PREFIX",
                    "Reorders a mesh's vertices (and its triangles to follow them) and writes the "
                    "reordered mesh and the permutation. PREFIX.perm lists, one per line, the old "
                    "id of each new vertex (its header names the ordering and, for a seeded one, "
                    "the seed); `--ordering file:PREFIX.perm` reads it back.",
                    desc, pos, vm))
    return 0;
  cfg.seed = ParseCount(seed, "--seed", 0, UINT64_MAX >> 1);
  cfg.triangle_order = ParseTriangleOrder(triangle_order);
  CheckOrderingSpec(cfg.ordering);
  const Progress progress(vm.count("quiet") > 0);
  const ReorderResult r = RunReorder(cfg, MakeLog(progress));
  for (const std::string& f : r.written) std::printf("wrote %s\n", f.c_str());
  std::printf("ordering %s: %.3f ms to compute, %.3f ms to apply\n", cfg.ordering.c_str(),
              1e3 * r.order_seconds, 1e3 * r.apply_seconds);
  if (r.chains)
    std::printf("chains placing vertices: %lld, longest %lld, median %lld, fewer than ten: %lld\n",
                static_cast<long long>(r.chains), static_cast<long long>(r.longest),
                static_cast<long long>(r.median), static_cast<long long>(r.short_chains));
  return 0;
}

}  // namespace meshreuse::cli
