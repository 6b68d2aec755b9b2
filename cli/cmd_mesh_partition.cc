// meshreuse mesh partition: a vertex partition for smoothing across ranks (core/ranks/partition.h)
// and what it costs a distributed sweep; with --levels, the coarse mesh's partition inherited by
// its refinement (core/refine.h: the parts of `mesh refine --levels K`'s vertices).
#include <algorithm>
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "core/ranks/gmsh_split.h"
#include "core/ranks/partition.h"
#include "core/refine.h"
#include "core/table.h"
#include "reports/distributed_smooth.h"
#include "reports/inputs.h"

namespace meshreuse::cli {

int MeshPartition(const Args& args) {
  po::options_description desc("options");
  std::string in, out, method, split;
  int32_t parts = 2;
  uint64_t seed = 1;
  RefineOptions ro;
  ro.levels = 0;
  desc.add_options()("mesh", po::value(&in)->required(), "input mesh")(
      "parts,P", po::value(&parts)->default_value(2), "number of parts")(
      "method", po::value(&method)->default_value("hilbert"),
      "hilbert (contiguous ranges of the Hilbert order), metis (METIS k-way, seeded), scotch "
      "(Scotch, seeded), ranges (contiguous ranges of the stored ids) or gmsh (Gmsh's own, for "
      "MESH a file of a split set PREFIX_K.msh, `gmsh -part P -part_split`)")(
      "seed", po::value(&seed)->default_value(1), "METIS's seed")(
      "levels,K", po::value(&ro.levels)->default_value(0),
      "partition MESH, then give the parts of its refinement into 4^K (mesh refine --levels K)")(
      "output,o", po::value(&out), "write one part per vertex, a line each, here")(
      "split", po::value(&split),
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
  if (method != "hilbert" && method != "metis" && method != "scotch" && method != "ranges" &&
      method != "gmsh")
    throw UsageError("--method must be hilbert, metis, scotch, ranges or gmsh, not '" + method +
                     "'");
  if (!out.empty()) CheckOutputPath(out, "-o", InputFiles({in}));
  if (!split.empty()) {
    if (split.back() == '/') throw UsageError("--split '" + split + "': the prefix names no file");
    // Every file it will write, against the input (a whole split set with --method gmsh).
    std::vector<std::string> inputs = {in};
    const size_t us = in.rfind('_');
    if (method == "gmsh" && us != std::string::npos)
      for (int32_t p = 1; p <= parts; ++p)
        inputs.push_back(in.substr(0, us + 1) + std::to_string(p) + ".msh");
    for (int32_t p = 1; p <= parts; ++p)
      CheckOutputPath(split + std::to_string(p) + ".msh", "--split", inputs);
  }
  const Progress progress(vm.count("quiet") > 0);
  // gmsh: the parts of the Gmsh split set MESH belongs to (reports/distributed_smooth.h).
  PartitionedMesh pm;
  if (method == "gmsh")
    pm = LoadPartitioned(in, method, parts, seed, MakeLog(progress));
  else
    pm.mesh = LoadMesh(in, MakeLog(progress));
  const Mesh& coarse = pm.mesh;
  const RefinedSize size = RefinedSizeOf(coarse, ro);  // checks --levels and the sizes
  std::vector<int32_t> part =
      method == "gmsh" ? std::move(pm.part) : PartsByMethod(coarse, method, parts, seed);
  Mesh fine;
  const Mesh* m = &coarse;
  if (ro.levels > 0) {
    progress.Say("refining into " + Grouped(size.triangles) + " triangles");
    part = InheritParts(coarse, ro, part);
    fine = BuildMesh(RefineMesh(coarse, ro));
    m = &fine;
  }
  const PartitionStats s = MeasurePartition(*m, part, parts);
  Table t({"part", "colour", "owned", "cut", "ghosts"});
  for (int32_t p = 0; p < parts; ++p)
    t.AddRow({std::to_string(p), std::to_string(s.colour[p]), std::to_string(s.owned[p]),
              std::to_string(s.cut_owned[p]), std::to_string(s.ghosts[p])});
  if (parts <= 64) std::fputs(t.Aligned().c_str(), stdout);
  int64_t max_ghosts = 0;
  for (int64_t g : s.ghosts) max_ghosts = std::max(max_ghosts, g);
  std::printf(
      "vertices %s, parts %d (%s%s), cut edges %s, ghosts per part max %s, max/mean part "
      "%.3f, colours %d\n",
      Grouped(m->NumVertices()).c_str(), parts, method.c_str(),
      ro.levels > 0 ? (", inherited through " + std::to_string(ro.levels) + " levels").c_str() : "",
      Grouped(s.cut_edges).c_str(), Grouped(max_ghosts).c_str(), s.imbalance(), s.colours);
  if (!split.empty())
    for (const std::string& f : WriteGmshSplit(*m, part, parts, split))
      std::printf("wrote %s\n", f.c_str());
  if (!out.empty()) {
    std::string text = "# meshreuse partition: " + std::to_string(parts) + " parts (" + method +
                       (ro.levels > 0 ? ", levels " + std::to_string(ro.levels) : "") + ") of " +
                       std::to_string(m->NumVertices()) + " vertices; line k: vertex k's part\n";
    for (int32_t p : part) text += std::to_string(p) + "\n";
    WriteTextFile(out, text);
    std::printf("wrote %s\n", out.c_str());
  }
  return 0;
}

}  // namespace meshreuse::cli
