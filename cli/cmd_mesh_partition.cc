// meshreuse mesh partition: options, output paths checked before any work, and the runner
// (reports/mesh_partition.h).
#include <algorithm>
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "reports/inputs.h"
#include "reports/mesh_partition.h"

namespace meshreuse::cli {

int MeshPartition(const Args& args) {
  po::options_description desc("options");
  MeshPartitionConfig cfg;
  std::string seed;
  const std::string& in = cfg.mesh;
  desc.add_options()("mesh", po::value(&cfg.mesh)->required(), "input mesh")(
      "parts,P", po::value(&cfg.parts)->default_value(2), "number of parts")(
      "method", po::value(&cfg.method)->default_value("hilbert"),
      "hilbert (contiguous ranges of the Hilbert order), metis (METIS k-way, seeded), scotch "
      "(Scotch, seeded), ranges (contiguous ranges of the stored ids) or gmsh (Gmsh's own, for "
      "MESH a file of a split set PREFIX_K.msh, `gmsh -part P -part_split`)")(
      "seed", po::value(&seed)->default_value("1"), "METIS's and Scotch's seed")(
      "levels,K", po::value(&cfg.levels)->default_value(0),
      "partition MESH, then give the parts of its refinement into 4^K (mesh refine --levels K)")(
      "output,o", po::value(&cfg.output), "write one part per vertex, a line each, here")(
      "split", po::value(&cfg.split),
      "write the mesh as a Gmsh split set PREFIX1.msh .. PREFIX<P>.msh (partitioned MSH 4.1; a "
      "triangle in its smallest corner's part) for Gmsh and any reader of its format; give "
      "PREFIX, e.g. out/plate_")("quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(args,
                    "mesh partition MESH --parts P [--method hilbert|metis|scotch|ranges|gmsh] "
                    "[--levels K] [-o FILE] [--split PREFIX]",
                    "Partitions the vertices for smoothing across ranks and prints what the "
                    "partition costs a distributed sweep: cut edges, owned, cut and ghost vertices "
                    "per part, balance, and the colours of a greedy colouring of the part graph "
                    "(the rounds of ordered Gauss-Seidel). With --levels K the coarse mesh is "
                    "partitioned and its refinement inherits the parts: a coarse vertex keeps its "
                    "part, an edge point takes its edge's lower-id end's, an interior point its "
                    "triangle's smallest corner's.",
                    desc, pos, vm))
    return 0;
  cfg.seed = ParseCount(seed, "--seed", 0, UINT64_MAX);
  CheckMeshPartitionConfig(cfg);
  if (!cfg.output.empty()) CheckOutputPath(cfg.output, "-o", InputFiles({in}));
  if (!cfg.split.empty()) {
    // Every file it will write, against the input (a whole split set with --method gmsh).
    std::vector<std::string> inputs = {in};
    const size_t us = in.rfind('_');
    if (cfg.method == "gmsh" && us != std::string::npos)
      for (int32_t p = 1; p <= cfg.parts; ++p)
        inputs.push_back(in.substr(0, us + 1) + std::to_string(p) + ".msh");
    std::vector<std::pair<std::string, std::string>> outputs = {{"-o", cfg.output}};
    for (int32_t p = 1; p <= cfg.parts; ++p) {
      CheckOutputPath(cfg.split + std::to_string(p) + ".msh", "--split", inputs);
      outputs.emplace_back("--split", cfg.split + std::to_string(p) + ".msh");
    }
    CheckDistinctOutputs(outputs);
  }
  const Progress progress(vm.count("quiet") > 0);
  Emit(RunMeshPartition(cfg, MakeLog(progress)), OutputFormat::kText, "", progress);
  return 0;
}

}  // namespace meshreuse::cli
