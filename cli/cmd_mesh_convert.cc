// meshreuse mesh convert: any mesh the readers take, written as Triangle files, VTK or a mesh
// file (core/mesh_file.h, laid out in Hilbert order for ranges of ranks).
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "reports/inputs.h"

namespace meshreuse::cli {

int MeshConvert(const Args& args) {
  po::options_description desc("options");
  std::string in, out;
  desc.add_options()("mesh", po::value(&in)->required(), "input mesh")(
      "output,o", po::value(&out)->required(),
      (std::string(kMeshOutputFormats) + " (a .mrm is stored in Hilbert order)").c_str())(
      "quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "mesh convert MESH -o OUT",
          "Reads any supported mesh (Triangle .node/.ele, Gmsh .msh 2.2/4.1) and writes "
          "Triangle files, VTK XML or legacy (with vertex and triangle quality, for ParaView), "
          "Gmsh 4.1 or the "
          "distributed mesh file FILE.mrm that MPI ranks read in ranges (vertices in Hilbert "
          "order).",
          desc, pos, vm))
    return 0;
  for (const std::string& f : MeshOutputFiles(out)) CheckOutputPath(f, "-o", InputFiles({in}));
  const Progress progress(vm.count("quiet") > 0);
  Mesh m = LoadMesh(in, MakeLog(progress));
  if (IsMeshFilePath(out)) LayOutForRanks(&m);  // ranges of ids are then Hilbert ranges
  for (const std::string& f : SaveMesh(m, out, MakeLog(progress)))
    std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace meshreuse::cli
