// meshreuse mesh refine and meshreuse-mpi refine: their options, output paths checked before any
// work, and the runners (reports/mesh_refine.h: one process, or `--ranks P` as threads through
// the distributed runner; reports/distributed_refine.h for MPI ranks).
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
#include "core/refine.h"
#include "core/table.h"
#include "reports/distributed_refine.h"
#include "reports/inputs.h"
#include "reports/mesh_refine.h"
#include "reports/output.h"

namespace meshreuse::cli {

namespace {

void AddRefineOptions(po::options_description& desc, std::string* in, std::string* out,
                      RefineOptions* o, std::string* seed, const char* out_help) {
  desc.add_options()("mesh", po::value(in)->required(), "input (coarse) mesh")(
      "levels,K", po::value(&o->levels)->default_value(1), "each triangle into 4^K (0..15)")(
      "jitter", po::value(&o->jitter)->default_value(0.0),
      "move each new vertex off the coarse boundary by up to JITTER/2 of the local fine spacing "
      "in x and y (0..0.5; areas stay positive)")("seed", po::value(seed)->default_value("1"),
                                                  "seed of the jitter")(
      "output,o", po::value(out)->required(), out_help);
}

}  // namespace

int DistRefineCommand(const Args& args, Communicator& tx) {
  po::options_description desc("options");
  DistRefineConfig cfg;
  std::string rank_stats;
  std::string seed;
  AddRefineOptions(desc, &cfg.mesh, &cfg.output, &cfg.refine, &seed,
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
              "Layout " + kPiecesLayoutHelp + ".",
          desc, pos, vm))
    return 0;
  cfg.refine.seed = ParseCount(seed, "--seed", 0, UINT64_MAX);
  CheckDistRefineConfig(cfg);
  const bool writer = tx.rank() == 0;
  CheckOutputPath(cfg.output, "-o", InputFiles({cfg.mesh}));
  if (writer) WarnStaleTemporaries(cfg.output);
  CheckDistinctOutputs({{"-o", cfg.output}, {"--rank-stats", rank_stats}});
  if (!rank_stats.empty()) CheckOutputPath(rank_stats, "--rank-stats", InputFiles({cfg.mesh}));
  const Progress progress(vm.count("quiet") > 0 || !writer);
  const DistRefineResult r = RunDistributedRefine(cfg, tx, MakeLog(progress));
  if (!writer) return 0;
  const RunOutput out = DistRefineOutput(r, cfg);
  Emit(out, OutputFormat::kText, "", progress);
  if (!rank_stats.empty()) WriteCsvFile(rank_stats, *out.csv);
  return 0;
}

int MeshRefine(const Args& args) {
  po::options_description desc("options");
  MeshRefineConfig cfg;
  std::string seed;
  AddRefineOptions(desc, &cfg.mesh, &cfg.output, &cfg.refine, &seed, kMeshOutputFormats);
  desc.add_options()("layout", po::value(&cfg.layout),
                     (std::string("vertex order: refinement (the ids above; the default, except "
                                  "for .mrm), hilbert (the default for .mrm), or ") +
                      kPiecesLayoutHelp)
                         .c_str())(
      "ranks", po::value(&cfg.ranks),
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
  cfg.refine.seed = ParseCount(seed, "--seed", 0, UINT64_MAX);
  if (vm.count("ranks") && cfg.ranks == 0) cfg.ranks = -1;  // refused: 1..4096
  CheckMeshRefineConfig(cfg);
  for (const std::string& f :
       cfg.ranks > 0 ? std::vector<std::string>{cfg.output} : MeshOutputFiles(cfg.output)) {
    CheckOutputPath(f, "-o", InputFiles({cfg.mesh}));
    WarnStaleTemporaries(f);
  }
  const Progress progress(vm.count("quiet") > 0);
  Emit(RunMeshRefine(cfg, MakeLog(progress)), OutputFormat::kText, "", progress);
  return 0;
}

}  // namespace meshreuse::cli
