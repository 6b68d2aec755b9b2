// meshreuse mesh info | generate | convert.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli/common.h"
#include "cli/options.h"
#include "cli/progress.h"
#include "core/mesh_io.h"
#include "core/quality.h"
#include "core/shapes.h"
#include "core/triangle_runner.h"
#include "reports/run_info.h"
#include "reports/table.h"

namespace meshreuse::cli {

int MeshInfo(const Args& args) {
  po::options_description desc("options");
  std::string file;
  int bins = 10;
  desc.add_options()("mesh", po::value(&file)->required(),
                     "mesh file (.node, .ele, .msh or prefix)")(
      "bins", po::value(&bins)->default_value(10), "quality histogram bins")(
      "json", "print JSON instead of text")("quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(args, "mesh info MESH [--json]",
                    "Vertices, triangles, boundary vertices and vertex quality (min, mean, max and "
                    "a histogram) of a mesh.",
                    desc, pos, vm))
    return 0;
  if (bins < 1 || bins > 1000) throw po::error("--bins must be between 1 and 1000");
  const Progress progress(vm.count("quiet") > 0);
  const Mesh m = LoadMesh(file, progress);
  const QualitySummary q = SummarizeVertexQuality(m, bins);
  if (vm.count("json")) {
    std::string h;
    for (size_t i = 0; i < q.histogram.size(); ++i)
      h += (i ? ", " : "") + std::to_string(q.histogram[i]);
    std::printf(
        "{\"mesh\": %s, \"vertices\": %d, \"triangles\": %d, \"boundary_vertices\": %d, "
        "\"interior_vertices\": %zu, \"quality\": {\"min\": %s, \"mean\": %s, \"max\": %s, "
        "\"histogram\": [%s]}}\n",
        JsonString(file).c_str(), m.NumVertices(), m.NumTriangles(), m.NumBoundary(),
        m.interior.size(), JsonNumber(q.min).c_str(), JsonNumber(q.mean).c_str(),
        JsonNumber(q.max).c_str(), h.c_str());
    return 0;
  }
  std::printf("mesh               %s\n", file.c_str());
  std::printf("vertices           %s\n", Grouped(m.NumVertices()).c_str());
  std::printf("triangles          %s\n", Grouped(m.NumTriangles()).c_str());
  std::printf("boundary vertices  %s\n", Grouped(m.NumBoundary()).c_str());
  std::printf("interior vertices  %s\n",
              Grouped(static_cast<long long>(m.interior.size())).c_str());
  std::printf("vertex quality     min %.6f  mean %.6f  max %.6f\n", q.min, q.mean, q.max);
  std::printf("quality histogram (vertices):\n");
  int64_t peak = 1;
  for (int64_t c : q.histogram) peak = std::max(peak, c);
  for (int b = 0; b < bins; ++b) {
    const int bar = static_cast<int>(40.0 * static_cast<double>(q.histogram[b]) / peak + 0.5);
    std::printf("  [%.2f, %.2f%c %10s  %s\n", double(b) / bins, double(b + 1) / bins,
                b + 1 == bins ? ']' : ')', Grouped(q.histogram[b]).c_str(),
                std::string(bar, '#').c_str());
  }
  return 0;
}

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
  if (shape.empty() == poly.empty()) throw po::error("give exactly one of --shape and --poly");
  const ShapeInfo* info = nullptr;
  if (!shape.empty()) {
    info = FindShape(shape);
    if (!info) throw po::error("unknown shape '" + shape + "' (known: " + ShapeNames() + ")");
    poly = ShapesDir() + "/" + shape + ".poly";
  }
  if (!vm.count("vertices")) {
    if (!info) throw po::error("--poly needs --vertices");
    vertices = info->paper_vertices;
  }
  if (vertices < 100) throw po::error("--vertices must be at least 100");
  if (!(angle >= 0 && angle <= 34))
    throw po::error(
        "--min-angle must be between 0 and 34 degrees (Triangle may not terminate above)");
  if (out.empty()) out = "out/" + (info ? shape : std::string("mesh"));
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

int MeshConvert(const Args& args) {
  po::options_description desc("options");
  std::string in, out;
  desc.add_options()("mesh", po::value(&in)->required(), "input mesh")(
      "output,o", po::value(&out)->required(), "PATH.vtk, or a prefix for .node/.ele")(
      "quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "mesh convert MESH -o OUT",
          "Reads any supported mesh (Triangle .node/.ele, Gmsh .msh 2.2/4.1) and writes "
          "Triangle files or VTK legacy (with vertex and triangle quality, for ParaView).",
          desc, pos, vm))
    return 0;
  const Progress progress(vm.count("quiet") > 0);
  const Mesh m = LoadMesh(in, progress);
  for (const std::string& f : WriteMesh(m, out)) std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace meshreuse::cli
