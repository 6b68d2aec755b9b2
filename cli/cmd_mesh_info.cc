// meshreuse mesh info: vertices, triangles, boundary and vertex quality of a mesh.
#include <algorithm>
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/quality.h"
#include "core/table.h"
#include "reports/inputs.h"

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
  if (bins < 1 || bins > 1000) throw UsageError("--bins must be between 1 and 1000");
  const Progress progress(vm.count("quiet") > 0);
  const Mesh m = LoadMesh(file, MakeLog(progress));
  const QualitySummary q = SummarizeVertexQuality(m, bins);
  if (vm.count("json")) {
    const Json j = {
        {"mesh", file},
        {"vertices", m.NumVertices()},
        {"triangles", m.NumTriangles()},
        {"boundary_vertices", m.NumBoundary()},
        {"interior_vertices", m.interior.size()},
        {"quality",
         {{"min", q.min}, {"mean", q.mean}, {"max", q.max}, {"histogram", q.histogram}}}};
    std::printf("%s\n", j.dump().c_str());
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

}  // namespace meshreuse::cli
