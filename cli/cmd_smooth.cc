// meshreuse smooth: Laplacian smoothing of one or more meshes, per-sweep quality and time on
// stdout, a summary table at the end, and with --out DIR the tables as CSV/Markdown plus run.json.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/options.h"
#include "cli/progress.h"
#include "core/mesh_io.h"
#include "core/smoother.h"
#include "reports/run_info.h"
#include "reports/table.h"

namespace meshreuse::cli {

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void WriteText(const std::string& path, const std::string& text) {
  WriteAtomically(path, [&](std::FILE* f) { std::fputs(text.c_str(), f); });
}

}  // namespace

int SmoothCommand(const Args& args) {
  po::options_description desc("options");
  std::vector<std::string> meshes;
  std::string mode_name = "gauss-seidel", out_mesh, out_dir;
  SmoothOptions opt;
  desc.add_options()("mesh", po::value(&meshes)->required()->multitoken(), "mesh file(s)")(
      "threads,t", po::value(&opt.threads)->default_value(1), "OpenMP threads (static schedule)")(
      "tol", po::value(&opt.tol)->default_value(5e-6, "5e-6"),
      "stop after a sweep that improves the global quality by less than this")(
      "max-iters", po::value(&opt.max_iters)->default_value(100), "at most this many sweeps")(
      "mode", po::value(&mode_name)->default_value("gauss-seidel"), "gauss-seidel or jacobi")(
      "output,o", po::value(&out_mesh),
      "write the smoothed mesh (PATH.vtk or a .node/.ele prefix)")(
      "out", po::value(&out_dir), "write summary.csv, summary.md, sweeps.csv and run.json here")(
      "quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", -1);
  po::variables_map vm;
  if (!ParseOptions(args, "smooth MESH... [--threads P] [--tol T] [--max-iters N] [-o OUT]",
                    "Laplacian smoothing as in the paper (Mesquite's smoother): each sweep moves "
                    "every interior vertex, in storage order, to the average of its neighbours. "
                    "Prints the global quality and time of each sweep, then a summary.",
                    desc, pos, vm))
    return 0;
  try {
    opt.mode = ParseUpdateMode(mode_name);
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
  if (opt.threads < 1 || opt.threads > 1024)
    throw po::error("--threads must be between 1 and 1024");
  if (opt.max_iters < 1) throw po::error("--max-iters must be at least 1");
  if (std::isnan(opt.tol)) throw po::error("--tol must be a number (negative: never stop early)");
  if (!out_mesh.empty() && meshes.size() != 1) throw po::error("-o takes a single input mesh");
  const Progress progress(vm.count("quiet") > 0);

  Table summary({"mesh", "vertices", "triangles", "threads", "mode", "sweeps", "converged",
                 "quality_before", "quality_after", "median_ms_per_sweep", "total_s"});
  Table sweeps({"mesh", "sweep", "quality", "improvement", "ms"});
  std::string results_json;
  for (const std::string& path : meshes) {
    progress.Say("reading " + path);
    std::vector<std::string> warnings;
    Mesh m = ReadMesh(path, &warnings);
    for (const std::string& w : warnings)
      std::fprintf(stderr, "meshreuse: warning: %s\n", w.c_str());
    std::printf("== %s: %s vertices, %s triangles, %d thread%s, %s\n", path.c_str(),
                Grouped(m.NumVertices()).c_str(), Grouped(m.NumTriangles()).c_str(), opt.threads,
                opt.threads == 1 ? "" : "s", UpdateModeName(opt.mode));
    std::printf("%6s  %10s  %12s  %10s\n", "sweep", "quality", "improvement", "time_ms");
    std::fflush(stdout);
    progress.Say("smoothing " + path);
    NullSink untraced;
    const SmoothResult r = Smooth(m, opt, untraced, [&](const SweepRecord& s) {
      std::printf("%6d  %10.6f  %+12.3e  %10.3f\n", s.sweep, s.quality, s.improvement,
                  1e3 * s.seconds);
      std::fflush(stdout);
    });
    std::vector<double> times;
    for (const SweepRecord& s : r.sweeps) {
      times.push_back(s.seconds);
      sweeps.AddRow({path, std::to_string(s.sweep), Fixed(s.quality, 9), JsonNumber(s.improvement),
                     Fixed(1e3 * s.seconds, 3)});
    }
    const double med = Median(times);
    std::printf("sweeps %zu (%s), quality %.6f -> %.6f, median %.3f ms/sweep, total %.3f s\n\n",
                r.sweeps.size(), r.converged ? "converged" : "max-iters reached", r.quality_before,
                r.quality_after, 1e3 * med, r.seconds);
    summary.AddRow({path, std::to_string(m.NumVertices()), std::to_string(m.NumTriangles()),
                    std::to_string(opt.threads), UpdateModeName(opt.mode),
                    std::to_string(r.sweeps.size()), r.converged ? "yes" : "no",
                    Fixed(r.quality_before, 6), Fixed(r.quality_after, 6), Fixed(1e3 * med, 3),
                    Fixed(r.seconds, 3)});
    results_json += std::string(results_json.empty() ? "" : ",\n") +
                    "    {\"mesh\": " + JsonString(path) +
                    ", \"vertices\": " + std::to_string(m.NumVertices()) +
                    ", \"triangles\": " + std::to_string(m.NumTriangles()) +
                    ", \"sweeps\": " + std::to_string(r.sweeps.size()) +
                    ", \"converged\": " + (r.converged ? "true" : "false") +
                    ", \"quality_before\": " + JsonNumber(r.quality_before) +
                    ", \"quality_after\": " + JsonNumber(r.quality_after) +
                    ", \"median_seconds_per_sweep\": " + JsonNumber(med) +
                    ", \"total_seconds\": " + JsonNumber(r.seconds) + "}";
    if (!out_mesh.empty())
      for (const std::string& f : WriteMesh(m, out_mesh)) progress.Say("wrote " + f);
  }
  if (meshes.size() > 1) std::printf("%s", summary.Aligned().c_str());
  if (!out_dir.empty()) {
    std::filesystem::create_directories(out_dir);
    WriteText(out_dir + "/summary.csv", summary.Csv());
    WriteText(out_dir + "/summary.md", summary.Markdown());
    WriteText(out_dir + "/sweeps.csv", sweeps.Csv());
    WriteText(out_dir + "/run.json",
              "{\n  \"tool\": \"meshreuse smooth\",\n  \"command\": " +
                  CommandLineJson(FullCommandLine()) + ",\n  \"git_revision\": " +
                  JsonString(GitRevision()) + ",\n  \"time_utc\": " + JsonString(UtcTimestamp()) +
                  ",\n  \"machine\": " + MachineJson() +
                  ",\n  \"config\": {\"threads\": " + std::to_string(opt.threads) + ", \"mode\": " +
                  JsonString(UpdateModeName(opt.mode)) + ", \"tol\": " + JsonNumber(opt.tol) +
                  ", \"max_iters\": " + std::to_string(opt.max_iters) +
                  ", \"omp_max_threads\": " + std::to_string(omp_get_max_threads()) +
                  "},\n  \"results\": [\n" + results_json + "\n  ]\n}\n");
    progress.Say("wrote " + out_dir + "/{summary.csv,summary.md,sweeps.csv,run.json}");
  }
  return 0;
}

}  // namespace meshreuse::cli
