// meshreuse mesh refine: uniform refinement, each triangle into 4^K (core/refine.h), with global
// ids any process can compute from the coarse mesh alone, and an optional deterministic jitter.
#include <cinttypes>
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "core/refine.h"
#include "core/table.h"
#include "reports/inputs.h"

namespace meshreuse::cli {

int MeshRefine(const Args& args) {
  po::options_description desc("options");
  std::string in, out;
  RefineOptions o;
  desc.add_options()("mesh", po::value(&in)->required(), "input mesh")(
      "levels,K", po::value(&o.levels)->default_value(1), "each triangle into 4^K (0..15)")(
      "jitter", po::value(&o.jitter)->default_value(0.0),
      "move each new vertex off the coarse boundary by up to JITTER/2 of the local fine spacing "
      "in x and y (0..0.5; areas stay positive)")("seed", po::value(&o.seed)->default_value(1),
                                                  "seed of the jitter")(
      "output,o", po::value(&out)->required(),
      "PATH.vtk, PATH.mrm (the distributed mesh file, in Hilbert order), or a prefix for "
      ".node/.ele")("quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "mesh refine MESH --levels K [--jitter F] [--seed S] -o OUT",
          "Refines every triangle into 4^K (each edge halved K times), new vertices on the edges "
          "and inside by linear interpolation, so a point on a shared edge is bit for bit the same "
          "from both sides; ids: the coarse vertices, then each coarse edge's points (edges by "
          "(lower id, higher id)), then each coarse triangle's interior points. Prints the fine "
          "mesh's size and content hash (the same for any process computing any part of it).",
          desc, pos, vm))
    return 0;
  for (const std::string& f : MeshOutputFiles(out)) CheckOutputPath(f, "-o", InputFiles({in}));
  const Progress progress(vm.count("quiet") > 0);
  const Mesh coarse = LoadMesh(in, MakeLog(progress));
  const RefinedSize size = RefinedSizeOf(coarse, o);  // UsageError beyond 32-bit ids
  progress.Say("refining " + Grouped(coarse.NumTriangles()) + " triangles into " +
               Grouped(size.triangles));
  RawMesh raw = RefineMesh(coarse, o);
  const uint64_t hash = MeshContentHash(raw.xy, raw.tri);
  Mesh fine = BuildMesh(std::move(raw));
  std::printf("coarse     %s vertices, %s triangles, %s edges\n",
              Grouped(coarse.NumVertices()).c_str(), Grouped(coarse.NumTriangles()).c_str(),
              Grouped(size.edges).c_str());
  std::printf("refined    %s vertices, %s triangles (K = %d, jitter %g, seed %" PRIu64 ")\n",
              Grouped(fine.NumVertices()).c_str(), Grouped(fine.NumTriangles()).c_str(), o.levels,
              o.jitter, o.seed);
  std::printf("hash       %016" PRIx64 "\n", hash);
  // The hash is of the refinement's own ids; a mesh file stores them in Hilbert order.
  if (IsMeshFilePath(out)) LayOutForRanks(&fine);
  for (const std::string& f : WriteMesh(fine, out)) std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace meshreuse::cli
