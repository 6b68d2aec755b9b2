// `meshreuse-mpi smooth`: one rank of the distributed smoother (reports/distributed_smooth.h),
// over whatever transport moves its bytes (MPI in cli/mpi_main.cc); `meshreuse smooth-ranks
// --ranks P`: the same P ranks as threads of one process (core/ranks/thread_communicator.h), for a
// machine without MPI or a shared-memory scaling study. Every rank parses and checks the same
// options; rank 0 alone prints and writes.
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/ranks/thread_communicator.h"
#include "reports/distributed_smooth.h"
#include "reports/output.h"

namespace meshreuse::cli {

namespace {

// The options every rank of the distributed smoother parses alike (meshreuse-mpi smooth, and
// smooth-ranks, which adds --ranks).
struct DistSmoothOptions {
  DistSmoothConfig cfg;
  std::string out_dir;
  bool quiet = false;
  int32_t ranks = 0;
};

// Parses `args` into `o` (false: --help was printed). `job_ranks`: the MPI job's size; 0: ranks
// as threads, whose number --ranks gives.
bool ParseDistSmooth(const Args& args, DistSmoothOptions* o, const char* usage, int32_t job_ranks) {
  std::string ranks_text;
  std::string* ranks = job_ranks == 0 ? &ranks_text : nullptr;
  po::options_description desc("options");
  DistSmoothConfig& cfg = o->cfg;
  std::string& out_dir = o->out_dir;
  std::string mode = "ordered", seed = "1", placement = "last";
  desc.add_options()("mesh", po::value(&cfg.mesh)->required(), "mesh file")(
      "partition", po::value(&cfg.partition)->default_value("hilbert"),
      "hilbert: contiguous ranges of the Hilbert order (balanced to a vertex); metis: METIS "
      "k-way, seeded; scotch: Scotch, seeded; ptscotch: PT-Scotch, computed by the MPI job's ranks "
      "together (meshreuse-mpi built with libptscotch-dev), seeded; gmsh: Gmsh's own, MESH being "
      "any file PREFIX_K.msh "
      "of a split set (`gmsh -part P -part_split`; P ranks); ranges: contiguous ranges of the "
      "stored ids; file:PATH: a partition file, one part per line (`mesh partition -o` writes one; "
      "METIS's and Scotch's outputs too), checked against the mesh. For a mesh file (FILE.mrm, "
      "written by `meshreuse mesh convert MESH -o "
      "FILE.mrm` in Hilbert order) the default is ranges, and each rank then reads only its "
      "range and ghost ring; with ptscotch its range's rows, then only its part and ghost ring "
      "(the other methods read the whole file on every rank)")(
      "ordering", po::value(&cfg.ordering)->default_value("ori"),
      ("each rank's layout of its part: " + OrderingNames()).c_str())(
      "seed", po::value(&seed)->default_value("1"), "seed of METIS and seeded orderings")(
      "cut-placement", po::value(&placement)->default_value("last"),
      "where each part keeps its cut vertices: last (after the non-cut ones, which move while the "
      "lower colours' ghosts arrive), first (moved and sent first; the non-cut ones move while "
      "they travel) or interleaved (where the ordering puts them; a rank waits for the whole "
      "sweeps of its lower-coloured neighbours); each equals its own serial order (--pi-out)")(
      "mode", po::value(&mode)->default_value("ordered"),
      "ordered: Gauss-Seidel, bit for bit the serial sweep along pi (--pi-out); jacobi: bit for "
      "bit the serial Jacobi; hybrid: ghosts refreshed once per sweep (no serial equal; timing "
      "studies)")("tol", po::value(&cfg.smooth.tol)->default_value(5e-6, "5e-6"),
                  "stop after a sweep that improves the global quality by less than this")(
      "max-iters", po::value(&cfg.smooth.max_iters)->default_value(100),
      "at most this many sweeps")(
      "output,o", po::value(&cfg.output),
      "write the smoothed mesh: PATH.pvtu for ParaView, one compressed .vtu piece per rank "
      "(PATH_RANK.vtu, written by each rank, ghost cells marked); or gathered on rank 0 as "
      "PATH.vtu, PATH.vtk, PATH.msh (Gmsh 4.1), PATH.mrm or a .node/.ele prefix (a mesh file "
      "read in ranges or parts and written as PATH.mrm is written by every rank at once)")(
      "pi-out", po::value(&cfg.pi_out),
      "write the serial visit order this run equals (ordered mode): `meshreuse smooth MESH "
      "--visit-order FILE` reproduces the run bit for bit")(
      "out", po::value(&out_dir), "write sweeps.csv, ranks.csv and run.json here")(
      "quiet,q", "no progress on stderr");
  if (ranks)
    desc.add_options()("ranks,P", po::value(ranks),
                       "P ranks as threads of this process (messages through memory)");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args, usage,
          std::string(ranks ? "The distributed smoother of `mpirun -np P meshreuse-mpi smooth` "
                              "with its P ranks as P threads of this process: the same parts, "
                              "schedule, output and pi, bit for bit. In ranks.csv, peak_rss_mb is "
                              "the whole process's peak (all ranks together). "
                            : "") +
              "Laplacian smoothing across the ranks of an MPI job: each rank reads MESH (of a "
              "mesh file FILE.mrm, only its range and ghost ring), keeps its part and one ring of "
              "ghosts, and smooths it; rank 0 gathers the result. "
              "The global quality is summed exactly: in Jacobi mode it and the number of sweeps "
              "are the same for any number of ranks; in ordered mode they are those of the serial "
              "sweep along pi, which depends on the partition.",
          desc, pos, vm))
    return false;
  if (vm["partition"].defaulted() && IsMeshFilePath(cfg.mesh)) cfg.partition = "ranges";
  cfg.seed = ParseCount(seed, "--seed", 0, UINT64_MAX >> 1);
  cfg.smooth.mode = ParseHaloMode(mode);
  cfg.placement = ParseCutPlacement(placement);
  o->quiet = vm.count("quiet") > 0;
  o->ranks = job_ranks;
  if (ranks) {
    if (ranks_text.empty()) throw UsageError("--ranks P is required (the number of ranks)");
    // Every rank holds a copy of the mesh; a thread per rank beyond a few thousand is a mistake.
    o->ranks = static_cast<int32_t>(ParseCount(ranks_text, "--ranks", 1, 4096));
  }
  CheckDistSmoothConfig(cfg);
  if (!cfg.output.empty())
    for (const std::string& f : MeshOutputFiles(cfg.output, o->ranks))
      CheckOutputPath(f, "-o", InputFiles({cfg.mesh}));
  if (!cfg.pi_out.empty()) CheckOutputPath(cfg.pi_out, "--pi-out", InputFiles({cfg.mesh}));
  std::vector<std::pair<std::string, std::string>> outputs = {{"--pi-out", cfg.pi_out}};
  if (!cfg.output.empty())
    for (const std::string& f : MeshOutputFiles(cfg.output, o->ranks))
      outputs.emplace_back("-o", f);
  if (!out_dir.empty())
    for (const char* f : {"sweeps.csv", "ranks.csv", "run.json"})
      outputs.emplace_back("--out", out_dir + "/" + f);
  CheckDistinctOutputs(outputs);
  return true;
}

// One rank's run; rank 0 prints each sweep as it ends, then the summary and the ranks' table, and
// writes --out.
void RunDistSmooth(const DistSmoothOptions& o, Communicator& tx) {
  const DistSmoothConfig& cfg = o.cfg;
  const bool writer = tx.rank() == 0;
  if (!o.out_dir.empty() && writer) PrepareOutDir(o.out_dir);
  if (writer && !cfg.output.empty())
    for (const std::string& f : MeshOutputFiles(cfg.output, o.ranks)) WarnStaleTemporaries(f);
  const Progress progress(o.quiet || !writer);
  auto on_setup = [&](const DistSmoothResult& r) {
    if (!writer) return;
    std::printf(
        "== %s: %s vertices, %s triangles, %d ranks (%s partition: %s cut edges, %d "
        "colours), ordering %s, cut vertices %s, %s\n",
        cfg.mesh.c_str(), Grouped(r.vertices).c_str(), Grouped(r.triangles).c_str(), r.parts,
        cfg.partition.c_str(), Grouped(r.cut_edges).c_str(), r.colours, cfg.ordering.c_str(),
        CutPlacementName(cfg.placement), HaloModeName(cfg.smooth.mode));
    std::printf("%6s  %10s  %12s  %10s\n", "sweep", "quality", "improvement", "time_ms");
    std::fflush(stdout);
  };
  auto on_sweep = [&](const HaloSweep& s) {
    if (!writer) return;
    std::printf("%6d  %10.6f  %+12.3e  %10.3f\n", s.sweep, s.quality, s.improvement,
                1e3 * s.seconds);
    std::fflush(stdout);
  };
  const DistSmoothResult r = RunDistributedSmooth(cfg, tx, MakeLog(progress), on_setup, on_sweep);
  if (!writer) return;
  // Warnings are not progress: --quiet keeps them, as compare does.
  const std::vector<std::string> why = r.noise.Reasons();
  std::string reasons;
  for (const std::string& w : why) reasons += (reasons.empty() ? "" : "; ") + w;
  if (!why.empty())
    std::fprintf(stderr,
                 "meshreuse: warning: timings taken on a busy machine, the sweep times are not "
                 "this code's speed: %s\n",
                 reasons.c_str());
  Emit(DistSmoothOutput(r, cfg), OutputFormat::kText, o.out_dir, progress);
}

}  // namespace

int DistSmoothCommand(const Args& args, Communicator& tx, const JobPartition& job_partition) {
  DistSmoothOptions o;
  o.cfg.job_partition = job_partition;
  if (!ParseDistSmooth(
          args, &o,
          "smooth MESH [--partition hilbert|metis|scotch|ptscotch|ranges|gmsh|file:PATH] "
          "[--ordering NAME] [--mode ordered|jacobi|hybrid] [-o OUT] [--pi-out FILE]",
          tx.size()))
    return 0;
  RunDistSmooth(o, tx);
  return 0;
}

int DistSmoothThreads(const Args& args) {
  DistSmoothOptions o;
  if (!ParseDistSmooth(args, &o,
                       "smooth-ranks MESH --ranks P [--partition hilbert|metis|scotch|ranges|gmsh|"
                       "file:PATH] [--ordering NAME] [--mode ordered|jacobi|hybrid] [-o OUT] "
                       "[--pi-out FILE]",
                       0))
    return 0;
  ThreadCommunicator::Run(o.ranks, [&](Communicator& tx) { RunDistSmooth(o, tx); });
  return 0;
}

}  // namespace meshreuse::cli
