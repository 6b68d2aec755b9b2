// RunDistributedSmooth (distributed_smooth.h): read, partition, lay out, smooth, gather.
#include "reports/distributed_smooth.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/mesh_file.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/permutation.h"
#include "core/progress.h"
#include "core/ranks/gmsh_split.h"
#include "core/ranks/part_directory.h"
#include "core/ranks/partition.h"
#include "core/ranks/rank_neighbourhood.h"
#include "core/ranks/rank_part.h"
#include "core/ranks/rank_piece.h"
#include "core/vtu_io.h"
#include "reports/inputs.h"
#include "reports/shared_mesh_file.h"
#include "reports/timing.h"

namespace meshreuse {

void CheckDistSmoothConfig(const DistSmoothConfig& cfg) {
  if (cfg.mesh.empty()) throw UsageError("no mesh given");
  if (cfg.partition == "ptscotch") {
    if (!cfg.job_partition)
      throw UsageError(
          "--partition ptscotch is computed by the ranks of an MPI job together (PT-Scotch): run "
          "`mpirun -np P meshreuse-mpi smooth`, built with libptscotch-dev");
  } else {
    CheckPartitionMethod(cfg.partition);
  }
  CheckOrderingSpec(cfg.ordering);
  if (cfg.smooth.max_iters < 1) throw UsageError("--max-iters must be at least 1");
  if (std::isnan(cfg.smooth.tol))
    throw UsageError("--tol must be a number (negative: never stop early)");
  if (!cfg.pi_out.empty() && cfg.smooth.mode != HaloMode::kOrdered)
    throw UsageError(
        "--pi-out needs --mode ordered (jacobi equals serial Jacobi, hybrid no order)");
}

namespace {

// Little byte packer for the gather: what each rank sends rank 0.
class Packer {
 public:
  template <class T>
  void Put(const T& v) {
    b_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void PutVector(const T* p, size_t n) {
    Put<uint64_t>(n);
    if (n) b_.append(reinterpret_cast<const char*>(p), n * sizeof(T));  // p may be null when n is 0
  }
  std::string Take() { return std::move(b_); }

 private:
  std::string b_;
};

class Unpacker {
 public:
  explicit Unpacker(const std::string& b) : b_(b) {}
  template <class T>
  T Get() {
    T v;
    Need(sizeof v);
    std::memcpy(&v, b_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  template <class T>
  std::vector<T> GetVector() {
    const uint64_t n = Get<uint64_t>();
    if (n > (b_.size() - at_) / sizeof(T))
      throw std::logic_error("distributed smooth: short gather message");
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), b_.data() + at_, n * sizeof(T));  // v.data() is null when n is 0
    at_ += n * sizeof(T);
    return v;
  }

 private:
  void Need(uint64_t n) const {
    if (n > b_.size() - at_) throw std::logic_error("distributed smooth: short gather message");
  }
  const std::string& b_;
  size_t at_ = 0;
};

// The smoothed mesh file written by every rank (mesh_file.h): a copy of the input in P byte
// ranges, each rank's owned coordinates over it, each rank's share of the coordinate blocks
// hashed, rank 0 renewing the tables and renaming the temporary into place. False (nothing done)
// when the output is a device or FIFO: rank 0 then writes what it gathers.
bool WriteInRanges(const DistSmoothConfig& cfg, const RankPart& p, Communicator& tx, const Log& log,
                   DistSmoothResult* res) {
  const int32_t P = tx.size(), r = tx.rank();
  SharedMeshFileOutput out(cfg.output, tx);
  const std::string& tmp = out.temporary();
  if (tmp.empty()) return false;
  auto barrier = [&tx] { tx.AllGather(std::string()); };
  log.Say("writing " + cfg.output + " from every rank");
  struct stat st {};
  if (::stat(cfg.mesh.c_str(), &st) != 0)
    throw EnvironmentError(cfg.mesh, std::string("cannot stat: ") + std::strerror(errno));
  const int64_t size = st.st_size;
  CopyFileBytes(cfg.mesh, tmp, size * r / P, size * (r + 1) / P);
  barrier();
  // The owned coordinates by increasing global id (a range, or a PT-Scotch part's runs).
  std::vector<int32_t> by_id(static_cast<size_t>(p.owned));
  for (int32_t k = 0; k < p.owned; ++k) by_id[k] = k;
  std::sort(by_id.begin(), by_id.end(), [&p](int32_t a, int32_t b) { return p.gid[a] < p.gid[b]; });
  std::vector<int64_t> ids(by_id.size());
  std::vector<double> xy(2 * by_id.size());
  for (size_t i = 0; i < by_id.size(); ++i) {
    ids[i] = p.gid[by_id[i]];
    xy[2 * i] = p.xy[2 * int64_t{by_id[i]}];
    xy[2 * i + 1] = p.xy[2 * int64_t{by_id[i]} + 1];
  }
  WriteMeshFileCoordinates(tmp, ids, xy);
  out.Finish(CoordinateBlocks(res->vertices));  // only the coordinates changed
  if (r == 0) {
    log.Say("wrote " + cfg.output);
    res->written.push_back(cfg.output);
  }
  return true;
}

// -o X.pvtu: every rank writes its piece X_RANK.vtu (core/ranks/rank_piece.h), then rank 0 the
// .pvtu naming them, once every piece is complete.
void WritePieces(const DistSmoothConfig& cfg, const RankPart& p, Communicator& tx, const Log& log,
                 DistSmoothResult* res) {
  const int32_t P = tx.size(), r = tx.rank();
  log.Say("writing " + cfg.output + ": one .vtu piece from every rank");
  const RankPiece piece = BuildRankPiece(p, tx);
  const VtuGrid grid = PieceGrid(p, piece);
  {
    const PhaseProgress phase("writing " + PvtuPiece(cfg.output, r), PhaseListener(log, true));
    WriteVtu(grid, PvtuPiece(cfg.output, r));
  }
  tx.Barrier();
  if (r != 0) return;
  std::vector<std::string> sources;
  for (int32_t k = 0; k < P; ++k) {
    const std::string f = PvtuPiece(cfg.output, k);
    sources.push_back(f.substr(f.find_last_of('/') + 1));  // beside the .pvtu
    res->written.push_back(f);
  }
  WritePvtu(cfg.output, sources, grid);
  res->written.push_back(cfg.output);
  log.Say("wrote " + cfg.output + " and its " + std::to_string(P) + " pieces");
}

}  // namespace

bool ReadsRanges(const DistSmoothConfig& cfg) {
  return (cfg.partition == "ranges" || cfg.partition == "ptscotch") && IsMeshFilePath(cfg.mesh);
}

Mesh LoadForRanks(const std::string& path, int32_t parts, const Log& log) {
  Mesh m = LoadMesh(path, log);
  // The serial `smooth`'s default layout (ori, triangles sorted by their smallest corner): vertex
  // ids unchanged, so -o writes what `meshreuse smooth MESH -o` writes.
  ApplyPermutationInPlace(&m, Permutation::Identity(m.NumVertices()), TriangleOrder::kSorted);
  if (parts > m.NumVertices())
    throw UsageError(std::to_string(parts) + " ranks for a mesh of " +
                     std::to_string(m.NumVertices()) + " vertices: at most one rank per vertex");
  return m;
}

PartitionedMesh LoadPartitioned(const std::string& path, const std::string& method, int32_t parts,
                                uint64_t seed, const Log& log) {
  PartitionedMesh pm;
  if (method != "gmsh") {
    pm.mesh = LoadForRanks(path, parts, log);
    log.Say("partitioning " + std::to_string(pm.mesh.NumVertices()) + " vertices into " +
            std::to_string(parts) + " parts (" + method + ")");
    pm.part = PartsByMethod(pm.mesh, method, parts, seed);
    return pm;
  }
  log.Say("reading the Gmsh split set of " + path);
  GmshSplit split = ReadGmshSplit(path);
  for (const std::string& w : split.raw.warnings) log.Warn(w);
  if (split.parts != parts)
    throw UsageError("--partition gmsh: " + path + " belongs to a set of " +
                     std::to_string(split.parts) + " parts (" + split.files.front() + ".." +
                     split.files.back() + "): run " + std::to_string(split.parts) + " ranks, not " +
                     std::to_string(parts));
  BuildReport report;
  pm.mesh = BuildMesh(std::move(split.raw), &report);
  for (const std::string& w : report.warnings) log.Warn(w);
  pm.part = std::move(split.part);
  if (!report.kept.empty()) {  // nodes no triangle uses (lines' and points') were dropped
    std::vector<int32_t> kept(report.kept.size());
    for (size_t v = 0; v < kept.size(); ++v) kept[v] = pm.part[report.kept[v]];
    pm.part.swap(kept);
  }
  ApplyPermutationInPlace(&pm.mesh, Permutation::Identity(pm.mesh.NumVertices()),
                          TriangleOrder::kSorted);
  return pm;
}

namespace {

// A rank's part from a distributed read: each rank reads its part (its range, or its PT-Scotch
// part), gets its ghosts from their owners, and one all-gather of counts checks what no rank can
// alone and gives every rank the part graph to colour.
RankPart SetUpFromRanges(const DistSmoothConfig& cfg, Communicator& tx, const Log& log,
                         DistSmoothResult* res, SmoothRankStats* st) {
  const int32_t parts = tx.size(), rank = tx.rank();
  RankNeighbourhood nb;
  uint64_t rows_read = 0;
  if (cfg.partition == "ptscotch") {
    log.Say("reading rank " + std::to_string(rank) + "'s range of graph rows of " + cfg.mesh);
    GraphRows rows = ReadRangeGraphRows(cfg.mesh, rank, parts);
    rows_read = rows.bytes_read;
    const int64_t n = rows.vertices;
    log.Say("partitioning " + Grouped(n) + " vertices into " + std::to_string(parts) +
            " parts (PT-Scotch, all ranks)");
    const std::vector<int32_t> mine = cfg.job_partition(rows, parts, cfg.seed);
    rows = GraphRows();  // the rows are PT-Scotch's alone: freed before the part is read
    std::vector<int64_t> owned = GatherOwnedIds(tx, n, mine);
    log.Say("reading rank " + std::to_string(rank) + "'s PT-Scotch part of " + cfg.mesh);
    nb = ReadPartNeighbourhood(
        cfg.mesh, rank, parts, std::move(owned),
        [&](const std::vector<int64_t>& ghosts) { return LookUpParts(tx, n, mine, ghosts); },
        GhostExchange(tx));
  } else {
    log.Say("reading rank " + std::to_string(rank) + "'s range of " + cfg.mesh);
    const PhaseProgress phase("reading rank " + std::to_string(rank) + "'s range",
                              PhaseListener(log, true));
    nb = ReadRankNeighbourhood(cfg.mesh, rank, parts, GhostExchange(tx));
  }
  nb.bytes_read += rows_read;
  log.Say("rank " + std::to_string(rank) + " read " + Grouped(nb.owned) + " owned vertices and " +
          Grouped(nb.mesh.NumVertices() - nb.owned) + " ghosts (" +
          Fixed(nb.bytes_read / 1048576.0, 1) + " MB of the file)");
  std::vector<RankShare> shares;
  for (const std::string& b : tx.AllGather(PackShare(ShareOf(nb))))
    shares.push_back(UnpackShare(b));
  const std::vector<std::vector<int32_t>> graph = CheckRankShares(cfg.mesh, shares);
  const std::vector<int32_t> colour = GreedyPartColouring(graph, &res->colours);
  const std::string laying =
      "laying out rank " + std::to_string(rank) + "'s part (" + cfg.ordering + ")";
  log.Say(laying);
  const int64_t vertices = nb.vertices, triangles = nb.triangles, bytes_read = nb.bytes_read;
  RankPart p = [&] {
    const PhaseProgress phase(laying, PhaseListener(log, false));
    return BuildRankPart(std::move(nb), colour, cfg.ordering, cfg.seed, cfg.placement);
  }();
  res->vertices = static_cast<int32_t>(vertices);
  res->triangles = static_cast<int32_t>(triangles);
  for (const RankShare& s : shares) res->cut_edges += s.cut_edges;
  st->bytes_read = static_cast<uint64_t>(bytes_read);
  return p;
}

// A rank's part from the whole mesh, which every rank reads (and partitions, or PT-Scotch does
// over the job); `m` keeps the mesh for rank 0's output.
RankPart SetUpWhole(const DistSmoothConfig& cfg, Communicator& tx, const Log& log,
                    DistSmoothResult* res, Mesh* m) {
  const int32_t parts = tx.size(), rank = tx.rank();
  PartitionedMesh pm;
  if (cfg.partition == "ptscotch") {  // every rank reads the whole mesh; the job partitions it
    pm.mesh = LoadForRanks(cfg.mesh, parts, log);
    log.Say("partitioning " + std::to_string(pm.mesh.NumVertices()) + " vertices into " +
            std::to_string(parts) + " parts (PT-Scotch, all ranks)");
    const std::vector<int32_t> mine =
        cfg.job_partition(RangeGraphRows(pm.mesh, rank, parts), parts, cfg.seed);
    pm.part = AllParts(tx, pm.mesh.NumVertices(), mine);
  } else {
    pm = LoadPartitioned(cfg.mesh, cfg.partition, parts, cfg.seed, log);
  }
  *m = std::move(pm.mesh);
  const std::vector<int32_t>& part = pm.part;
  const PartitionStats ps = MeasurePartition(*m, part, parts);
  const std::string laying =
      "laying out rank " + std::to_string(rank) + "'s part (" + cfg.ordering + ")";
  log.Say(laying);
  RankPart p = [&] {
    const PhaseProgress phase(laying, PhaseListener(log, false));
    return BuildRankPart(*m, part, parts, ps.colour, rank, cfg.ordering, cfg.seed, cfg.placement);
  }();
  res->vertices = m->NumVertices(), res->triangles = m->NumTriangles();
  res->colours = ps.colours, res->cut_edges = ps.cut_edges;
  return p;
}

// Rank 0 gathers the moved vertices (boundary ones never move), pi's pieces and the ranks'
// statistics, and writes the mesh (unless every rank wrote its range) and pi.
void GatherAndWrite(const DistSmoothConfig& cfg, const RankPart& p, const SmoothRankStats& st,
                    bool parallel_out, Communicator& tx, const Log& log, DistSmoothResult* res,
                    Mesh* m) {
  const int32_t parts = tx.size(), rank = tx.rank();
  Packer out;
  out.Put(st);
  out.Put(p.colour);
  // The moves only when something needs them (-o, --pi-out): 24 bytes a vertex on rank 0.
  const size_t moved = (cfg.output.empty() || parallel_out) && cfg.pi_out.empty() ? 0 : p.movable;
  out.PutVector(p.gid.data(), moved);
  out.PutVector(p.xy.data(), 2 * moved);
  out.Put<int64_t>(p.noncut);
  const std::vector<std::string> all = tx.Gather(out.Take());
  if (rank != 0) return;
  // A distributed read leaves no rank the whole mesh: rank 0 reads it now to write it (a mesh that
  // fits one node; the ranks' moves are what it gathered).
  if (ReadsRanges(cfg) && !cfg.output.empty() && !parallel_out)
    *m = LoadForRanks(cfg.mesh, parts, log);
  std::vector<RankMoves> moves(parts);
  for (int32_t r = 0; r < parts; ++r) {
    Unpacker in(all[r]);
    res->ranks.push_back(in.Get<SmoothRankStats>());
    RankMoves& mv = moves[r];
    mv.colour = in.Get<int32_t>();
    mv.placement = cfg.placement;
    mv.gid = in.GetVector<int64_t>();
    const std::vector<double> xy = in.GetVector<double>();
    mv.noncut = static_cast<int32_t>(in.Get<int64_t>());
    for (size_t k = 0; k < mv.gid.size() && !m->xy.empty(); ++k) {
      m->xy[2 * mv.gid[k]] = xy[2 * k];
      m->xy[2 * mv.gid[k] + 1] = xy[2 * k + 1];
    }
  }
  if (!cfg.output.empty() && !parallel_out)
    for (const std::string& f : SaveMesh(*m, cfg.output, log)) {
      log.Say("wrote " + f);
      res->written.push_back(f);
    }
  if (!cfg.pi_out.empty()) {
    const std::vector<int64_t> pi = VisitOrderOf(moves);
    WriteAtomically(cfg.pi_out, [&](std::FILE* f) {
      std::fprintf(f,
                   "# the serial Gauss-Seidel visit order of `meshreuse-mpi smooth %s` on %d "
                   "ranks (ordered mode, cut vertices %s): meshreuse smooth MESH --visit-order "
                   "THIS\n",
                   cfg.mesh.c_str(), parts, CutPlacementName(cfg.placement));
      for (int64_t v : pi) std::fprintf(f, "%lld\n", static_cast<long long>(v));
    });
    log.Say("wrote " + cfg.pi_out);
    res->written.push_back(cfg.pi_out);
  }
}

}  // namespace

DistSmoothResult RunDistributedSmooth(const DistSmoothConfig& cfg, Communicator& tx, const Log& log,
                                      const std::function<void(const DistSmoothResult&)>& on_setup,
                                      const std::function<void(const HaloSweep&)>& on_sweep) {
  CheckDistSmoothConfig(cfg);
  const auto t0 = std::chrono::steady_clock::now();
  DistSmoothResult res;
  res.parts = tx.size();
  Mesh m;
  SmoothRankStats st;
  RankPart p = ReadsRanges(cfg) ? SetUpFromRanges(cfg, tx, log, &res, &st)
                                : SetUpWhole(cfg, tx, log, &res, &m);
  st.rank = tx.rank(), st.colour = p.colour;
  st.owned = p.owned, st.noncut = p.noncut, st.cut = p.cut(), st.boundary = p.owned - p.movable;
  st.ghosts = p.ghosts(), st.triangles = static_cast<int64_t>(p.weight.size());
  st.links = static_cast<int64_t>(p.links.size());
  st.setup_seconds = Since(t0);
  // A barrier: with ranks as threads (`smooth-ranks`) stdout is shared, and a rank still inside
  // METIS has it redirected (core/stdout_guard.h); rank 0 prints only once every rank is past.
  tx.AllReduceSum(FixedSum());
  if (on_setup) on_setup(res);
  log.Say("smoothing (" + std::string(HaloModeName(cfg.smooth.mode)) + ")");
  res.noise.cores = Cores();
  res.noise.load_before = LoadAverage();
  res.result = SmoothRankPart(p, cfg.smooth, tx, on_sweep);
  res.noise.load_after = LoadAverage();
  for (const HaloSweep& s : res.result.sweeps) {
    st.smooth_seconds += s.seconds;
    st.cpu_seconds += s.cpu_seconds;
    st.wait_seconds += s.wait_seconds;
    st.work_seconds += s.work_seconds;
  }
  st.messages = res.result.messages;
  st.bytes_sent = res.result.values_sent * sizeof(double);
  st.peak_rss_bytes = PeakRssBytes();
  // A mesh file read in ranges is written by every rank at once (mesh_file.h); -o in any other
  // format, or onto a device, is gathered.
  bool parallel_out =
      ReadsRanges(cfg) && IsMeshFilePath(cfg.output) && WriteInRanges(cfg, p, tx, log, &res);
  if (IsPvtuPath(cfg.output)) {
    WritePieces(cfg, p, tx, log, &res);
    parallel_out = true;
  }
  GatherAndWrite(cfg, p, st, parallel_out, tx, log, &res, &m);
  // Spans under 10 ms say nothing about the machine.
  for (const SmoothRankStats& r : res.ranks)
    if (r.work_seconds > 0.01 && !(res.noise.cpu_per_wall <= r.cpu_seconds / r.work_seconds))
      res.noise.cpu_per_wall = r.cpu_seconds / r.work_seconds;
  return res;
}

Table RankStatsTable(const std::vector<SmoothRankStats>& ranks) {
  Table t({"rank", "colour", "owned", "noncut", "cut", "boundary", "ghosts", "triangles", "links",
           "read_mb", "setup_s", "smooth_s", "cpu_s", "wait_s", "messages", "bytes_sent",
           "peak_rss_mb", "rss_bytes_per_owned"});
  for (const SmoothRankStats& s : ranks)
    t.AddRow({std::to_string(s.rank), std::to_string(s.colour), std::to_string(s.owned),
              std::to_string(s.noncut), std::to_string(s.cut), std::to_string(s.boundary),
              std::to_string(s.ghosts), std::to_string(s.triangles), std::to_string(s.links),
              s.bytes_read ? Fixed(s.bytes_read / 1048576.0, 1) : "-", Fixed(s.setup_seconds, 3),
              Fixed(s.smooth_seconds, 3), Fixed(s.cpu_seconds, 3), Fixed(s.wait_seconds, 3),
              std::to_string(s.messages), std::to_string(s.bytes_sent),
              Fixed(s.peak_rss_bytes / 1048576.0, 1),
              s.owned ? Fixed(static_cast<double>(s.peak_rss_bytes) / s.owned, 0) : "-"});
  return t;
}

Json DistSmoothJson(const DistSmoothConfig& cfg, const DistSmoothResult& r) {
  Json sweeps = Json::array();
  for (const HaloSweep& s : r.result.sweeps)
    sweeps.push_back({{"sweep", s.sweep},
                      {"quality", s.quality},
                      {"improvement", s.improvement},
                      {"seconds", s.seconds}});
  return {{"mesh", cfg.mesh},
          {"partition", cfg.partition},
          {"ordering", cfg.ordering},
          {"cut_placement", CutPlacementName(cfg.placement)},
          {"seed", cfg.seed},
          {"mode", HaloModeName(cfg.smooth.mode)},
          {"ranks", r.parts},
          {"colours", r.colours},
          {"cut_edges", r.cut_edges},
          {"vertices", r.vertices},
          {"triangles", r.triangles},
          {"converged", r.result.converged},
          {"quality_before", r.result.quality_before.ToDouble()},
          {"quality_after", r.result.quality_after.ToDouble()},
          {"sweeps", sweeps},
          {"noise", r.noise.ToJson()},
          {"per_rank", RankStatsTable(r.ranks).JsonValue()}};
}

RunOutput DistSmoothOutput(const DistSmoothResult& r, const DistSmoothConfig& cfg) {
  RunOutput o;
  o.tool = "meshreuse-mpi smooth";
  const HaloResult& h = r.result;
  char line[200];
  std::snprintf(line, sizeof line, "sweeps %zu (%s), quality %.6f -> %.6f", h.sweeps.size(),
                h.converged ? "converged" : "max-iters reached", h.quality_before.ToDouble(),
                h.quality_after.ToDouble());
  o.text.emplace_back(line);
  o.text.emplace_back("");
  o.csv = RunOutput::Share(RankStatsTable(r.ranks));
  o.text.emplace_back(o.csv);
  Table sweeps({"sweep", "quality", "improvement", "ms"});
  for (const HaloSweep& s : h.sweeps)
    sweeps.AddRow({std::to_string(s.sweep), ExactNumber(s.quality), ExactNumber(s.improvement),
                   ExactNumber(1e3 * s.seconds)});
  o.tables = {{"sweeps", RunOutput::Share(std::move(sweeps)), {"csv"}}, {"ranks", o.csv, {"csv"}}};
  o.configuration = DistSmoothJson(cfg, r);
  return o;
}

}  // namespace meshreuse
