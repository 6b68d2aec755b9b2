// RunDistributedRefine (distributed_refine.h): each rank refines and writes its range of coarse
// triangles' blocks; the hashes of the whole file's blocks are shared out and finished on rank 0.
#include "reports/distributed_refine.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/fixed_sum.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/smoother.h"
#include "reports/inputs.h"
#include "reports/run_info.h"
#include "reports/shared_mesh_file.h"
#include "reports/timing.h"

namespace meshreuse {

void CheckDistRefineConfig(const DistRefineConfig& cfg) {
  if (cfg.mesh.empty()) throw UsageError("no mesh given");
  if (!IsMeshFilePath(cfg.output))
    throw UsageError("-o must name a mesh file, PATH.mrm: every rank writes its range of it (" +
                     (cfg.output.empty() ? std::string("none given") : cfg.output) + ")");
  if (cfg.refine.levels < 0 || cfg.refine.levels > 15) throw UsageError("--levels must be 0..15");
  if (!(cfg.refine.jitter >= 0 && cfg.refine.jitter <= 0.5))
    throw UsageError("--jitter must be 0..0.5");
}

namespace {

int64_t BoundaryVertices(const std::vector<uint8_t>& b) {
  return std::count(b.begin(), b.end(), uint8_t{1});
}

// V - E + T with E = (3T + boundary vertices) / 2: a triangulated surface's edges when its
// boundary is closed loops (each boundary vertex starts one boundary edge).
int64_t Euler(int64_t v, int64_t t, int64_t boundary) { return v - (3 * t + boundary) / 2 + t; }

template <class T>
void Put(std::string* b, const T& v) {
  b->append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
T Get(const std::string& b, size_t* at) {
  T v;
  if (b.size() - *at < sizeof v) throw std::logic_error("distributed refine: a short message");
  std::memcpy(&v, b.data() + *at, sizeof v);
  *at += sizeof v;
  return v;
}

}  // namespace

DistRefineResult RunDistributedRefine(const DistRefineConfig& cfg, Communicator& tx,
                                      const Log& log) {
  CheckDistRefineConfig(cfg);
  const auto t0 = std::chrono::steady_clock::now();
  const int32_t P = tx.size(), r = tx.rank();
  auto barrier = [&tx] { tx.AllGather(std::string()); };
  // Every rank reads the coarse mesh and lays it out before any file exists: a bad input or
  // size fails every rank alike, with nothing to clean up.
  Mesh coarse = LoadMesh(cfg.mesh, r == 0 ? log : Log{});
  LayOutForRanks(&coarse);
  const PiecesLayout layout(coarse, cfg.refine);  // UsageError beyond 32-bit ids
  // Ranks write the output at offsets: it must be a regular file or a new path (stat follows a
  // link to its target). Checked on every rank before rank 0 opens it (opening a FIFO would block).
  struct stat target {};
  if (::stat(cfg.output.c_str(), &target) == 0 && !S_ISREG(target.st_mode))
    throw UsageError("-o " + cfg.output +
                     ": every rank writes its range of the file, so it must be a regular file "
                     "or a new path (not a device or FIFO)");
  SharedMeshFileOutput out(cfg.output, tx);
  const std::string& tmp = out.temporary();

  DistRefineResult res;
  res.coarse_vertices = coarse.NumVertices(), res.coarse_triangles = coarse.NumTriangles();
  res.vertices = layout.vertices(), res.triangles = layout.triangles();
  res.coarse_euler =
      Euler(coarse.NumVertices(), coarse.NumTriangles(), BoundaryVertices(coarse.boundary));
  if (r == 0) {
    log.Say("refining " + Grouped(coarse.NumTriangles()) + " triangles into " +
            Grouped(res.triangles) + " (" + Grouped(res.vertices) + " vertices) on " +
            std::to_string(P) + " ranks");
    CreateMeshFile(tmp, res.vertices, res.triangles);
  }
  barrier();

  const auto r0 = std::chrono::steady_clock::now();
  const double c0 = ThreadCpuSeconds();
  const int32_t tb = layout.Split(r, P), te = layout.Split(r + 1, P);
  RefineRankStats st;
  st.rank = r, st.coarse_triangles = te - tb;
  int64_t boundary = 0;
  double min_area2 = std::numeric_limits<double>::infinity();
  {
    // Rank 0's progress stands for the job's (every rank a range of about the same size).
    const PhaseProgress phase("refining rank " + std::to_string(r) + "'s range",
                              PhaseListener(log, false));
    const RefinedRange range = RefineRange(coarse, cfg.refine, layout, tb, te);
    st.vertices = static_cast<int64_t>(range.boundary.size());
    st.triangles = static_cast<int64_t>(range.tri.size() / 3);
    boundary = BoundaryVertices(range.boundary);
    min_area2 = range.min_area2;
    WriteMeshFileRange(tmp, range);
  }
  st.seconds = Since(r0);
  st.cpu_seconds = ThreadCpuSeconds() - c0;
  st.peak_rss_bytes = PeakRssBytes();

  // Rank 0 gathers the stats and checks; every rank learns the verdict before the file is
  // finished, so all fail alike when a triangle is bad (and rank 0's temporary is removed).
  std::string msg;
  Put(&msg, st);
  Put(&msg, boundary);
  Put(&msg, min_area2);
  const std::vector<std::string> all = tx.Gather(msg);
  bool bad = false;
  if (r == 0) {
    int64_t boundary_all = 0;
    res.min_area2 = std::numeric_limits<double>::infinity();
    for (const std::string& b : all) {
      size_t at = 0;
      res.ranks.push_back(Get<RefineRankStats>(b, &at));
      boundary_all += Get<int64_t>(b, &at);
      res.min_area2 = std::min(res.min_area2, Get<double>(b, &at));
    }
    res.euler = Euler(res.vertices, res.triangles, boundary_all);
    bad = !(res.min_area2 > 0);
  }
  const std::string verdict = tx.AllGather(r == 0 ? std::string(bad ? "1" : "0") : "")[0];
  if (verdict == "1")
    throw InputError(cfg.mesh, 0,
                     "refined with --levels " + std::to_string(cfg.refine.levels) + " --jitter " +
                         Fixed(cfg.refine.jitter, 3) +
                         ", a fine triangle is degenerate or turned against its coarse triangle: "
                         "nothing written");
  res.content_id = out.Finish(MeshFileBlocks(res.vertices, res.triangles));
  res.seconds = Since(t0);
  return res;
}

Table RefineRankTable(const std::vector<RefineRankStats>& ranks) {
  Table t({"rank", "coarse_triangles", "vertices", "triangles", "seconds", "cpu_seconds", "peak_mb",
           "bytes_per_vertex"});
  for (const RefineRankStats& s : ranks)
    t.AddRow({std::to_string(s.rank), std::to_string(s.coarse_triangles),
              std::to_string(s.vertices), std::to_string(s.triangles), Fixed(s.seconds, 3),
              Fixed(s.cpu_seconds, 3), Fixed(s.peak_rss_bytes / 1e6, 1),
              s.vertices ? Fixed(static_cast<double>(s.peak_rss_bytes) / s.vertices, 0) : "-"});
  return t;
}

}  // namespace meshreuse
