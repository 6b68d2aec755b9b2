// meshreuse kernels: the kernel registry's table (core/kernels/list.h).
#include <string>

#include "cli/common.h"
#include "core/kernels/kernel.h"

namespace meshreuse::cli {

const char* KernelOptionHelp() {
  static const std::string help =
      "for meshes: the sweep traced, analysed, simulated or timed: " + KernelNames() +
      " (`meshreuse kernels` says what each does)";
  return help.c_str();
}

int KernelsCommand(const Args& args) {
  po::options_description desc("options");
  desc.add_options()("json", "the list as JSON");
  po::positional_options_description pos;
  po::variables_map vm;
  if (!ParseOptions(args, "kernels [--json]",
                    "Lists the mesh kernels every command takes with --kernel (default laplacian, "
                    "the paper's): what one sweep does, its visit unit, what its per-sweep measure "
                    "is, its parallel form and its source.",
                    desc, pos, vm))
    return 0;
  Table t({"name", "visits", "modes", "threads", "measure", "description", "parallel form",
           "reference"});
  for (const KernelInfo& k : Kernels())
    t.AddRow({k.name, VisitUnitName(k.unit),
              k.jacobi  ? "gauss-seidel, jacobi"
              : k.moves ? "gauss-seidel"
                        : "-",
              k.threads ? "yes" : "1 only", k.measure, k.description, k.parallel, k.reference});
  Print(t, vm.count("json") ? OutputFormat::kJson : OutputFormat::kText);
  return 0;
}

}  // namespace meshreuse::cli
