// meshreuse mesh generate: one of the nine shapes (or a .poly) meshed with Shewchuk's Triangle
// to a vertex count (core/triangle_runner.h).
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_io.h"
#include "core/shapes.h"
#include "core/table.h"
#include "core/triangle_runner.h"

namespace meshreuse::cli {

int MeshGenerate(const Args& args) {
  po::options_description desc("options");
  std::string shape, poly, out;
  int64_t vertices = 0;
  double angle = 20.0;
  desc.add_options()("shape", po::value(&shape), ("one of: " + ShapeNames()).c_str())(
      "poly", po::value(&poly), "mesh this .poly file instead of a shipped shape")(
      "vertices,n", po::value(&vertices),
      "target vertex count (default: the paper's count for --shape); reached within 5%")(
      "min-angle", po::value(&angle)->default_value(20.0), "Triangle's quality bound -q, degrees")(
      "output,o", po::value(&out),
      "output prefix: writes PREFIX.node and PREFIX.ele (default out/SHAPE)")(
      "quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  po::variables_map vm;
  if (!ParseOptions(args, "mesh generate --shape NAME [--vertices N] [-o PREFIX]",
                    "Meshes one of the paper's nine shapes (or your own .poly) with Shewchuk's "
                    "Triangle, searching the maximum-area constraint until the vertex count is "
                    "within 3% of the paper's Table 4 (or within 5% of --vertices). Triangle's own "
                    "vertex numbering is kept: it is the ORI ordering.",
                    desc, pos, vm))
    return 0;
  if (shape.empty() == poly.empty()) throw UsageError("give exactly one of --shape and --poly");
  const ShapeInfo* info = nullptr;
  if (!shape.empty()) {
    info = FindShape(shape);
    if (!info) throw UsageError("unknown shape '" + shape + "' (known: " + ShapeNames() + ")");
    poly = ShapesDir() + "/" + shape + ".poly";
  }
  if (!vm.count("vertices")) {
    if (!info) throw UsageError("--poly needs --vertices");
    vertices = info->paper_vertices;
  }
  // Ids are 32-bit; Triangle reaches 10^7 vertices in minutes, 10^9 in days: a bound up front,
  // not a search that runs Triangle over and over.
  constexpr int64_t kMaxVertices = int64_t{1} << 30;
  if (vertices < 100 || vertices > kMaxVertices)
    throw UsageError("--vertices must be 100.." + std::to_string(kMaxVertices) + ", found " +
                     std::to_string(vertices));
  if (!(angle >= 0 && angle <= 34))
    throw UsageError(
        "--min-angle must be between 0 and 34 degrees (Triangle may not terminate above)");
  if (out.empty()) out = "out/" + (info ? shape : std::string("mesh"));
  MeshOutputFiles(out);  // refuses a prefix that names no file
  // The folders it makes: none of them may already be a file.
  for (std::filesystem::path p = std::filesystem::path(out).parent_path(); !p.empty();
       p = p.parent_path()) {
    std::error_code ec;
    if (std::filesystem::exists(p, ec)) {
      if (!std::filesystem::is_directory(p, ec))
        throw UsageError("-o '" + out + "': " + p.string() + " is not a folder");
      break;
    }
    if (p == p.parent_path()) break;
  }
  const Progress progress(vm.count("quiet") > 0);
  TriangulateOptions opt;
  opt.target_vertices = vertices;
  opt.min_angle = angle;
  opt.accept = vm.count("vertices") ? 0.05 : 0.03;
  opt.progress = [&](const std::string& s) { progress.Say(s); };
  progress.Say("meshing " + poly + " to " + Grouped(vertices) + " vertices");
  const TriangulateResult r = TriangulatePoly(poly, out, opt);
  const double err = 100.0 * (static_cast<double>(r.vertices) / vertices - 1.0);
  std::printf("shape      %s\n", info ? info->name : poly.c_str());
  std::printf("vertices   %s  (target %s, %+.2f%%)\n", Grouped(r.vertices).c_str(),
              Grouped(vertices).c_str(), err);
  std::printf("triangles  %s%s\n", Grouped(r.triangles).c_str(),
              info ? ("  (paper " + Grouped(info->paper_triangles) + ")").c_str() : "");
  std::printf("triangle   %s  (%d runs)\n", r.switches.c_str(), r.runs);
  std::printf("files      %s %s\n", r.node_file.c_str(), r.ele_file.c_str());
  return 0;
}

}  // namespace meshreuse::cli
