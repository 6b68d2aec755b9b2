// meshreuse mesh refine: uniform refinement, each triangle into 4^K (core/refine.h), with global
// ids any process can compute from the coarse mesh alone, and an optional deterministic jitter.
// `--layout pieces` stores the fine vertices in blocks of coarse triangles (core/refine.h,
// PiecesLayout): the whole mesh in memory, or with `--ranks P` written into FILE.mrm by P ranks
// as threads of this process, none holding the fine mesh (reports/distributed_refine.h; the same
// runner as `mpirun -np P meshreuse-mpi refine`, DistRefineCommand), byte for byte the same file.
#include <sys/stat.h>

#include <cinttypes>
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "core/ranks/thread_communicator.h"
#include "core/refine.h"
#include "core/table.h"
#include "reports/distributed_refine.h"
#include "reports/inputs.h"
#include "reports/output.h"

namespace meshreuse::cli {

namespace {

void AddRefineOptions(po::options_description& desc, std::string* in, std::string* out,
                      RefineOptions* o, const char* out_help) {
  desc.add_options()("mesh", po::value(in)->required(), "input (coarse) mesh")(
      "levels,K", po::value(&o->levels)->default_value(1), "each triangle into 4^K (0..15)")(
      "jitter", po::value(&o->jitter)->default_value(0.0),
      "move each new vertex off the coarse boundary by up to JITTER/2 of the local fine spacing "
      "in x and y (0..0.5; areas stay positive)")("seed", po::value(&o->seed)->default_value(1),
                                                  "seed of the jitter")(
      "output,o", po::value(out)->required(), out_help);
}

const char* kPiecesHelp =
    "pieces: blocks of coarse triangles, the coarse mesh first laid out in Hilbert order; a "
    "block holds its triangle's interior points and the corners and edge points it owns (those "
    "of their lowest-id coarse triangle), so any range of blocks is computed from the coarse mesh "
    "alone and written in place by any number of ranks";

void PrintSizes(const DistRefineResult& r, const RefineOptions& o) {
  std::printf("coarse     %s vertices, %s triangles\n", Grouped(r.coarse_vertices).c_str(),
              Grouped(r.coarse_triangles).c_str());
  std::printf(
      "refined    %s vertices, %s triangles (K = %d, jitter %g, seed %" PRIu64 "; layout pieces)\n",
      Grouped(r.vertices).c_str(), Grouped(r.triangles).c_str(), o.levels, o.jitter, o.seed);
  std::printf("checked    Euler characteristic %lld (coarse %lld), smallest area %.6g\n",
              static_cast<long long>(r.euler), static_cast<long long>(r.coarse_euler),
              r.min_area2 / 2);
}

}  // namespace

int DistRefineCommand(const Args& args, Communicator& tx) {
  po::options_description desc("options");
  DistRefineConfig cfg;
  std::string rank_stats;
  AddRefineOptions(desc, &cfg.mesh, &cfg.output, &cfg.refine,
                   "PATH.mrm, the distributed mesh file (a regular file or a new path)");
  desc.add_options()("rank-stats", po::value(&rank_stats),
                     "write each rank's coarse triangles, vertices, seconds and peak memory (CSV)")(
      "quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args, "refine MESH --levels K [--jitter F] [--seed S] -o OUT.mrm",
          std::string("Refines every triangle into 4^K and writes the fine mesh file from every "
                      "rank at once, no rank holding the fine mesh; the file is byte for byte "
                      "`meshreuse mesh refine MESH --levels K --layout pieces -o OUT.mrm`. ") +
              "Layout " + kPiecesHelp + ".",
          desc, pos, vm))
    return 0;
  CheckDistRefineConfig(cfg);
  const bool writer = tx.rank() == 0;
  CheckOutputPath(cfg.output, "-o", InputFiles({cfg.mesh}));
  if (!rank_stats.empty()) CheckOutputPath(rank_stats, "--rank-stats", InputFiles({cfg.mesh}));
  const Progress progress(vm.count("quiet") > 0 || !writer);
  const DistRefineResult r = RunDistributedRefine(cfg, tx, MakeLog(progress));
  if (!writer) return 0;
  PrintSizes(r, cfg.refine);
  std::printf("content id %016" PRIx64 "\n", r.content_id);
  std::printf("wrote %s from %zu rank%s in %.2f s\n\n", cfg.output.c_str(), r.ranks.size(),
              r.ranks.size() == 1 ? "" : "s", r.seconds);
  const Table t = RefineRankTable(r.ranks);
  Print(t, OutputFormat::kText);
  if (!rank_stats.empty()) WriteCsvFile(rank_stats, t);
  return 0;
}

int MeshRefine(const Args& args) {
  po::options_description desc("options");
  std::string in, out, layout;
  RefineOptions o;
  int32_t ranks = 0;
  AddRefineOptions(desc, &in, &out, &o,
                   "PATH.vtk, PATH.mrm (the distributed mesh file), or a prefix for .node/.ele");
  desc.add_options()("layout", po::value(&layout),
                     (std::string("vertex order: refinement (the ids above; the default, except "
                                  "for .mrm), hilbert (the default for .mrm), or ") +
                      kPiecesHelp)
                         .c_str())(
      "ranks", po::value(&ranks),
      "with --layout pieces and -o PATH.mrm: write the file from this many ranks as threads of "
      "this process, none holding the fine mesh (as `meshreuse-mpi refine`)")(
      "quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(
          args,
          "mesh refine MESH --levels K [--jitter F] [--seed S] [--layout "
          "refinement|hilbert|pieces] "
          "[--ranks P] -o OUT",
          "Refines every triangle into 4^K (each edge halved K times), new vertices on the edges "
          "and inside by linear interpolation, so a point on a shared edge is bit for bit the same "
          "from both sides; ids: the coarse vertices, then each coarse edge's points (edges by "
          "(lower id, higher id)), then each coarse triangle's interior points. Prints the fine "
          "mesh's size and content hash (the same for any process computing any part of it).",
          desc, pos, vm))
    return 0;
  if (layout.empty()) layout = IsMeshFilePath(out) ? "hilbert" : "refinement";
  if (layout != "refinement" && layout != "hilbert" && layout != "pieces")
    throw UsageError("--layout must be refinement, hilbert or pieces, not '" + layout + "'");
  if (vm.count("ranks")) {
    if (layout != "pieces" || !IsMeshFilePath(out))
      throw UsageError("--ranks needs --layout pieces and -o PATH.mrm");
    if (ranks < 1 || ranks > 4096) throw UsageError("--ranks must be 1..4096");
    Args rest;
    for (size_t i = 0; i < args.size(); ++i) {  // DistRefineCommand's options: drop ours
      const std::string& a = args[i];
      if (a == "--layout" || a == "--ranks") {
        ++i;
        continue;
      }
      if (a.rfind("--layout=", 0) == 0 || a.rfind("--ranks=", 0) == 0) continue;
      rest.push_back(a);
    }
    ThreadCommunicator::Run(ranks, [&](Communicator& tx) { DistRefineCommand(rest, tx); });
    return 0;
  }
  for (const std::string& f : MeshOutputFiles(out)) CheckOutputPath(f, "-o", InputFiles({in}));
  const Progress progress(vm.count("quiet") > 0);
  Mesh coarse = LoadMesh(in, MakeLog(progress));
  // Pieces: blocks of the coarse triangles in Hilbert order, so that ranges of ids are compact.
  if (layout == "pieces") LayOutForRanks(&coarse);
  const RefinedSize size = RefinedSizeOf(coarse, o);  // UsageError beyond 32-bit ids
  progress.Say("refining " + Grouped(coarse.NumTriangles()) + " triangles into " +
               Grouped(size.triangles));
  RawMesh raw = layout == "pieces" ? RefineMeshPieces(coarse, o) : RefineMesh(coarse, o);
  const uint64_t hash = MeshContentHash(raw.xy, raw.tri);
  Mesh fine = BuildMesh(std::move(raw));
  std::printf("coarse     %s vertices, %s triangles, %s edges\n",
              Grouped(coarse.NumVertices()).c_str(), Grouped(coarse.NumTriangles()).c_str(),
              Grouped(size.edges).c_str());
  std::printf("refined    %s vertices, %s triangles (K = %d, jitter %g, seed %" PRIu64 ")\n",
              Grouped(fine.NumVertices()).c_str(), Grouped(fine.NumTriangles()).c_str(), o.levels,
              o.jitter, o.seed);
  // The hash is of the refinement's own ids (pieces: of the pieces ids); hilbert stores them in
  // Hilbert order.
  std::printf("hash       %016" PRIx64 "\n", hash);
  if (layout == "hilbert") LayOutForRanks(&fine);
  for (const std::string& f : WriteMesh(fine, out)) std::printf("wrote %s\n", f.c_str());
  struct stat st {};
  if (IsMeshFilePath(out) && ::stat(out.c_str(), &st) == 0 && S_ISREG(st.st_mode))
    std::printf("content id %016" PRIx64 "\n", MeshFile(out).content_id());
  return 0;
}

}  // namespace meshreuse::cli
