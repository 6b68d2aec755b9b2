// The mesh partition runner; see mesh_partition.h.
#include "reports/mesh_partition.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "core/ranks/gmsh_split.h"
#include "core/ranks/partition.h"
#include "core/refine.h"
#include "core/table.h"
#include "reports/distributed_smooth.h"
#include "reports/inputs.h"

namespace meshreuse {

void CheckMeshPartitionConfig(const MeshPartitionConfig& cfg) {
  // As many parts as ranks may be (--ranks), checked before any per-part work (the split set's
  // file names are checked one by one).
  if (cfg.parts < 1 || cfg.parts > 65536)
    throw UsageError("--parts must be 1..65536, found " + std::to_string(cfg.parts));
  const std::string& m = cfg.method;
  if (m != "hilbert" && m != "metis" && m != "scotch" && m != "ranges" && m != "gmsh")
    throw UsageError("--method must be hilbert, metis, scotch, ranges or gmsh, not '" + m + "'");
  if (!cfg.split.empty() && cfg.split.back() == '/')
    throw UsageError("--split '" + cfg.split + "': the prefix names no file");
}

RunOutput RunMeshPartition(const MeshPartitionConfig& cfg, const Log& log) {
  CheckMeshPartitionConfig(cfg);
  RefineOptions ro;
  ro.levels = cfg.levels;
  // gmsh: the parts of the Gmsh split set the mesh belongs to (reports/distributed_smooth.h).
  PartitionedMesh pm;
  if (cfg.method == "gmsh")
    pm = LoadPartitioned(cfg.mesh, cfg.method, cfg.parts, cfg.seed, log);
  else
    pm.mesh = LoadMesh(cfg.mesh, log);
  const Mesh& coarse = pm.mesh;
  const RefinedSize size = RefinedSizeOf(coarse, ro);  // checks --levels and the sizes
  std::vector<int32_t> part = cfg.method == "gmsh"
                                  ? std::move(pm.part)
                                  : PartsByMethod(coarse, cfg.method, cfg.parts, cfg.seed);
  Mesh fine;
  const Mesh* m = &coarse;
  if (ro.levels > 0) {
    log.Say("refining into " + Grouped(size.triangles) + " triangles");
    part = InheritParts(coarse, ro, part);
    fine = BuildMesh(RefineMesh(coarse, ro));
    m = &fine;
  }
  const PartitionStats s = MeasurePartition(*m, part, cfg.parts);
  RunOutput o;
  o.tool = "meshreuse mesh partition";
  Table t({"part", "colour", "owned", "cut", "ghosts"});
  for (int32_t p = 0; p < cfg.parts; ++p)
    t.AddRow({std::to_string(p), std::to_string(s.colour[p]), std::to_string(s.owned[p]),
              std::to_string(s.cut_owned[p]), std::to_string(s.ghosts[p])});
  o.csv = RunOutput::Share(std::move(t));
  if (cfg.parts <= 64) o.text.emplace_back(o.csv);
  int64_t max_ghosts = 0;
  for (int64_t g : s.ghosts) max_ghosts = std::max(max_ghosts, g);
  char line[160];
  std::snprintf(line, sizeof line, "max/mean part %.3f, colours %d", s.imbalance(), s.colours);
  o.text.emplace_back(
      "vertices " + Grouped(m->NumVertices()) + ", parts " + std::to_string(cfg.parts) + " (" +
      cfg.method +
      (ro.levels > 0 ? ", inherited through " + std::to_string(ro.levels) + " levels" : "") +
      "), cut edges " + Grouped(s.cut_edges) + ", ghosts per part max " + Grouped(max_ghosts) +
      ", " + line);
  if (!cfg.split.empty())
    for (const std::string& f : WriteGmshSplit(*m, part, cfg.parts, cfg.split))
      o.text.emplace_back("wrote " + f);
  if (!cfg.output.empty()) {
    std::string text = "# meshreuse partition: " + std::to_string(cfg.parts) + " parts (" +
                       cfg.method + (ro.levels > 0 ? ", levels " + std::to_string(ro.levels) : "") +
                       ") of " + std::to_string(m->NumVertices()) +
                       " vertices; line k: vertex k's part\n";
    for (int32_t p : part) text += std::to_string(p) + "\n";
    WriteTextFile(cfg.output, text);
    o.text.emplace_back("wrote " + cfg.output);
  }
  return o;
}

}  // namespace meshreuse
