// The mesh refine runners; see mesh_refine.h.
#include "reports/mesh_refine.h"

#include <sys/stat.h>

#include <cinttypes>
#include <cstdio>

#include "core/error.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/ranks/thread_communicator.h"
#include "core/table.h"
#include "reports/inputs.h"

namespace meshreuse {

const char* const kPiecesLayoutHelp =
    "pieces: blocks of coarse triangles, the coarse mesh first laid out in Hilbert order; a "
    "block holds its triangle's interior points and the corners and edge points it owns (those "
    "of their lowest-id coarse triangle), so any range of blocks is computed from the coarse mesh "
    "alone and written in place by any number of ranks";

namespace {

std::string Hex(uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%016" PRIx64, v);
  return b;
}

std::string Layout(const MeshRefineConfig& cfg) {
  if (!cfg.layout.empty()) return cfg.layout;
  return IsMeshFilePath(cfg.output) ? "hilbert" : "refinement";
}

std::string RefinedLine(int64_t vertices, int64_t triangles, const RefineOptions& o,
                        const char* tail) {
  char b[200];
  std::snprintf(
      b, sizeof b, "refined    %s vertices, %s triangles (K = %d, jitter %g, seed %" PRIu64 "%s)",
      Grouped(vertices).c_str(), Grouped(triangles).c_str(), o.levels, o.jitter, o.seed, tail);
  return b;
}

}  // namespace

void CheckMeshRefineConfig(const MeshRefineConfig& cfg) {
  const std::string layout = Layout(cfg);
  if (layout != "refinement" && layout != "hilbert" && layout != "pieces")
    throw UsageError("--layout must be refinement, hilbert or pieces, not '" + layout + "'");
  if (cfg.ranks != 0) {
    if (layout != "pieces" || !IsMeshFilePath(cfg.output))
      throw UsageError("--ranks needs --layout pieces and -o PATH.mrm");
    if (cfg.ranks < 1 || cfg.ranks > 4096) throw UsageError("--ranks must be 1..4096");
  }
}

RunOutput DistRefineOutput(const DistRefineResult& r, const DistRefineConfig& cfg) {
  RunOutput o;
  o.tool = "meshreuse-mpi refine";
  o.text.emplace_back("coarse     " + Grouped(r.coarse_vertices) + " vertices, " +
                      Grouped(r.coarse_triangles) + " triangles");
  o.text.emplace_back(RefinedLine(r.vertices, r.triangles, cfg.refine, "; layout pieces"));
  char b[200];
  std::snprintf(
      b, sizeof b, "checked    Euler characteristic %lld (coarse %lld), smallest area %.6g",
      static_cast<long long>(r.euler), static_cast<long long>(r.coarse_euler), r.min_area2 / 2);
  o.text.emplace_back(b);
  o.text.emplace_back("content id " + Hex(r.content_id));
  std::snprintf(b, sizeof b, "wrote %s from %zu rank%s in %.2f s", cfg.output.c_str(),
                r.ranks.size(), r.ranks.size() == 1 ? "" : "s", r.seconds);
  o.text.emplace_back(b);
  o.text.emplace_back("");
  o.csv = RunOutput::Share(RefineRankTable(r.ranks));
  o.text.emplace_back(o.csv);
  return o;
}

RunOutput RunMeshRefine(const MeshRefineConfig& cfg, const Log& log) {
  CheckMeshRefineConfig(cfg);
  const std::string layout = Layout(cfg);
  if (cfg.ranks > 0) {
    DistRefineConfig d;
    d.mesh = cfg.mesh, d.output = cfg.output, d.refine = cfg.refine;
    CheckDistRefineConfig(d);
    RunOutput out;
    const Log quiet;
    ThreadCommunicator::Run(cfg.ranks, [&](Communicator& tx) {
      const DistRefineResult r = RunDistributedRefine(d, tx, tx.rank() == 0 ? log : quiet);
      if (tx.rank() == 0) out = DistRefineOutput(r, d);
    });
    return out;
  }
  const RefineOptions& o = cfg.refine;
  Mesh coarse = LoadMesh(cfg.mesh, log);
  // Pieces: blocks of the coarse triangles in Hilbert order, so that ranges of ids are compact.
  if (layout == "pieces") LayOutForRanks(&coarse);
  const RefinedSize size = RefinedSizeOf(coarse, o);  // UsageError beyond 32-bit ids
  log.Say("refining " + Grouped(coarse.NumTriangles()) + " triangles into " +
          Grouped(size.triangles));
  RawMesh raw;
  {
    const PhaseProgress phase("refining", PhaseListener(log, false));
    raw = layout == "pieces" ? RefineMeshPieces(coarse, o) : RefineMesh(coarse, o);
  }
  const uint64_t hash = MeshContentHash(raw.xy, raw.tri);
  Mesh fine = BuildMesh(std::move(raw));
  RunOutput out;
  out.tool = "meshreuse mesh refine";
  out.text.emplace_back("coarse     " + Grouped(coarse.NumVertices()) + " vertices, " +
                        Grouped(coarse.NumTriangles()) + " triangles, " + Grouped(size.edges) +
                        " edges");
  out.text.emplace_back(RefinedLine(fine.NumVertices(), fine.NumTriangles(), o, ""));
  // The hash is of the refinement's own ids (pieces: of the pieces ids); hilbert stores them in
  // Hilbert order.
  out.text.emplace_back("hash       " + Hex(hash));
  if (layout == "hilbert") LayOutForRanks(&fine);
  for (const std::string& f : SaveMesh(fine, cfg.output, log)) out.text.emplace_back("wrote " + f);
  struct stat st {};
  if (IsMeshFilePath(cfg.output) && ::stat(cfg.output.c_str(), &st) == 0 && S_ISREG(st.st_mode))
    out.text.emplace_back("content id " + Hex(MeshFile(cfg.output).content_id()));
  return out;
}

}  // namespace meshreuse
