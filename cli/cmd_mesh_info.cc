// meshreuse mesh info: vertices, triangles, boundary and vertex quality of a mesh; with --kernels,
// the working set of one sweep of each kernel (reports/working_set.h).
#include <algorithm>
#include <cstdio>
#include <string>

#include "analysis/cache_model.h"
#include "cli/common.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/quality.h"
#include "core/table.h"
#include "reports/inputs.h"
#include "reports/working_set.h"

namespace meshreuse::cli {

namespace {
constexpr uint32_t kLineBytes = 64;  // the line the simulators and the report count in
}  // namespace

int MeshInfo(const Args& args) {
  po::options_description desc("options");
  std::string file;
  int bins = 10;
  std::string kernels;
  desc.add_options()("mesh", po::value(&file)->required(),
                     "mesh file (.node, .ele, .msh or prefix)")(
      "bins", po::value(&bins)->default_value(10), "quality histogram bins")(
      "kernels", po::value(&kernels),
      "also the working set of one sweep of these kernels (a list, or all): distinct 64-byte "
      "lines and accesses, measured on two traced sweeps of each")(
      "json", "print JSON instead of text")("quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(args, "mesh info MESH [--json]",
                    "Vertices, triangles, boundary vertices and vertex quality (min, mean, max and "
                    "a histogram) of a mesh; with --kernels, the working set of one sweep of each "
                    "kernel as the mesh is stored.",
                    desc, pos, vm))
    return 0;
  if (bins < 1 || bins > 1000) throw UsageError("--bins must be between 1 and 1000");
  std::vector<std::string> names;  // every one checked before the mesh is read
  if (vm.count("kernels")) {
    if (kernels == "all")
      for (const KernelInfo& k : Kernels()) names.push_back(k.name);
    else
      names = SplitList(kernels);
    if (names.empty())
      throw UsageError("--kernels: no kernel named (known: " + KernelNames() + ")");
    for (const std::string& n : names)
      if (!FindKernel(n))
        throw UsageError("--kernels: unknown kernel '" + n + "' (known: " + KernelNames() + ")");
  }
  const Progress progress(vm.count("quiet") > 0);
  const Mesh m = LoadMesh(file, MakeLog(progress));
  const QualitySummary q = SummarizeVertexQuality(m, bins);
  std::vector<KernelWorkingSet> sets;
  if (!names.empty()) sets = KernelWorkingSets(m, names, kLineBytes, MakeLog(progress));
  if (vm.count("json")) {
    Json j = {{"mesh", file},
              {"vertices", m.NumVertices()},
              {"triangles", m.NumTriangles()},
              {"boundary_vertices", m.NumBoundary()},
              {"interior_vertices", m.interior.size()},
              {"quality",
               {{"min", q.min}, {"mean", q.mean}, {"max", q.max}, {"histogram", q.histogram}}}};
    if (!names.empty()) {
      Json ws = Json::array();
      for (const KernelWorkingSet& w : sets) {
        Json arrays = Json::object();
        for (const auto& [name, lines] : w.arrays) arrays[name] = lines;
        ws.push_back({{"kernel", w.kernel},
                      {"accesses", w.accesses},
                      {"lines", w.lines},
                      {"bytes", w.lines * kLineBytes},
                      {"arrays", arrays}});
      }
      j["working_sets"] = ws;
    }
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
  if (sets.empty()) return 0;
  // Where the set would sit on the paper's machine: the smallest cache that holds it.
  const CacheSpec wx = ParseCacheSpec("westmere-ex");
  std::printf("working set of one sweep (%u-byte lines, the mesh as stored):\n", kLineBytes);
  std::printf("  %-16s %14s %12s %10s  %-8s %s\n", "kernel", "accesses", "lines", "MiB", "fits in",
              "lines per array");
  for (const KernelWorkingSet& w : sets) {
    const uint64_t bytes = w.lines * kLineBytes;
    std::string fits = "memory", arrays;
    uint64_t held = 0;
    for (const CacheLevel& c : wx.levels) {
      held += c.bytes;  // levels 1..i together (the floor's bound, sweep_footprint.h)
      if (bytes <= held) {
        fits = c.name;
        break;
      }
    }
    for (const auto& [name, lines] : w.arrays)
      arrays += (arrays.empty() ? "" : ", ") + name + " " + Grouped(static_cast<long long>(lines));
    std::printf("  %-16s %14s %12s %10.2f  %-8s %s\n", w.kernel.c_str(),
                Grouped(static_cast<long long>(w.accesses)).c_str(),
                Grouped(static_cast<long long>(w.lines)).c_str(), bytes / 1048576.0, fits.c_str(),
                arrays.c_str());
  }
  std::printf(
      "  (fits in: the smallest cache level of the paper's Westmere-EX that, with the levels "
      "inside it, holds the set)\n");
  return 0;
}

}  // namespace meshreuse::cli
