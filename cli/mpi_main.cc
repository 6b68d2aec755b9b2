// meshreuse-mpi: `mpirun -np P meshreuse-mpi analyze INPUT [analyze's options]` -- the exact reuse
// analysis of one trace file or mesh across P ranks (reports/chunk_summary.h, RunDistributed):
// rank r reads (or, for a mesh, regenerates) only its own records, the LRU stacks stream rank to
// rank in blocks of 64 Ki ids, rank 0 prints and writes exactly what `meshreuse analyze INPUT`
// would. `mpirun -np P meshreuse-mpi smooth MESH [smooth's options]`: the distributed Laplacian
// smoother (reports/distributed_smooth.h), ghosts exchanged between neighbouring ranks. `mpirun -np
// P meshreuse-mpi refine MESH --levels K -o OUT.mrm`: the refined mesh file written by every rank
// (reports/distributed_refine.h). This file
// only moves bytes; the libraries stay MPI-free. A rank that fails prints "meshreuse-mpi: rank R:
// error: ..." and aborts the whole job with the error's exit status (2 bad input, 3 environment, 1
// a bug), never a hang. For tests, MESHREUSE_MPI_KILL_RANK=R makes rank R kill itself (SIGKILL)
// after analysing its chunk, or in smooth's first sweep: the job must end, non-zero, naming the
// rank.
#include <mpi.h>
#include <signal.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli/commands.h"
#ifdef MESHREUSE_HAVE_PTSCOTCH
#include "cli/mpi_ptscotch.h"
#endif
#include "core/error.h"
#include "core/halo_smoother.h"
#include "reports/chunk_summary.h"

namespace meshreuse::cli {
namespace {

constexpr int kTagIds = 1, kTagSize = 2, kTagBytes = 3;
constexpr size_t kPiece = size_t{1} << 30;  // bytes per message: counts are int

class MpiTransport : public ChunkTransport {
 public:
  MpiTransport() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void SendIds(const uint64_t* ids, size_t n) override {
    MPI_Send(ids, static_cast<int>(n), MPI_UINT64_T, rank_ + 1, kTagIds, MPI_COMM_WORLD);
  }
  size_t RecvIds(std::vector<uint64_t>* ids) override {
    MPI_Status st;
    MPI_Probe(rank_ - 1, kTagIds, MPI_COMM_WORLD, &st);
    int n = 0;
    MPI_Get_count(&st, MPI_UINT64_T, &n);
    ids->resize(static_cast<size_t>(n));
    MPI_Recv(ids->data(), n, MPI_UINT64_T, rank_ - 1, kTagIds, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return static_cast<size_t>(n);
  }
  void SendBytes(int to, const std::string& b) override {
    uint64_t n = b.size();
    MPI_Send(&n, 1, MPI_UINT64_T, to, kTagSize, MPI_COMM_WORLD);
    for (size_t at = 0; at < b.size(); at += kPiece)
      MPI_Send(b.data() + at, static_cast<int>(std::min(kPiece, b.size() - at)), MPI_BYTE, to,
               kTagBytes, MPI_COMM_WORLD);
  }
  std::string RecvBytes(int from) override {
    uint64_t n = 0;
    MPI_Recv(&n, 1, MPI_UINT64_T, from, kTagSize, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::string b(n, '\0');
    for (size_t at = 0; at < n; at += kPiece)
      MPI_Recv(&b[at], static_cast<int>(std::min<uint64_t>(kPiece, n - at)), MPI_BYTE, from,
               kTagBytes, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return b;
  }
  std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v) override {
    std::vector<uint64_t> out(v.size());
    MPI_Allreduce(v.data(), out.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_MAX,
                  MPI_COMM_WORLD);
    return out;
  }
  std::vector<uint64_t> ExclusiveScanSum(const std::vector<uint64_t>& v) override {
    std::vector<uint64_t> out(v.size(), 0);
    MPI_Exscan(v.data(), out.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_SUM,
               MPI_COMM_WORLD);
    if (rank_ == 0) std::fill(out.begin(), out.end(), 0);  // MPI leaves rank 0's undefined
    return out;
  }

 private:
  int rank_ = 0, size_ = 1;
};

// The distributed smoother's messages: ghost values to and from neighbouring ranks (one message per
// neighbour per sweep and direction, in order: MPI does not overtake on one tag and communicator),
// the 128-bit quality sum through a user-defined reduction, the gather to rank 0.
constexpr int kTagHalo = 4, kTagGather = 5;

void SumFixed(void* in, void* inout, int* len, MPI_Datatype*) {
  const uint64_t* a = static_cast<const uint64_t*>(in);
  uint64_t* b = static_cast<uint64_t*>(inout);
  for (int i = 0; i < *len; ++i) {
    meshreuse::FixedSum s = meshreuse::FixedSum::FromWords(b + 2 * i);
    s.Add(meshreuse::FixedSum::FromWords(a + 2 * i));
    s.ToWords(b + 2 * i);
  }
}

class MpiHalo : public HaloTransport {
 public:
  // kill: the tests' fault injection, this rank dies (SIGKILL) in its second reduction.
  explicit MpiHalo(bool kill) : kill_(kill) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Type_contiguous(2, MPI_UINT64_T, &fixed_);
    MPI_Type_commit(&fixed_);
    MPI_Op_create(&SumFixed, /*commute=*/1, &sum_);
  }
  ~MpiHalo() override {
    MPI_Op_free(&sum_);
    MPI_Type_free(&fixed_);
  }
  int32_t rank() const override { return rank_; }
  int32_t size() const override { return size_; }
  void Send(int32_t to, const double* data, size_t n) override {
    requests_.emplace_back();
    MPI_Isend(data, Count(n), MPI_DOUBLE, to, kTagHalo, MPI_COMM_WORLD, &requests_.back());
  }
  void Recv(int32_t from, double* data, size_t n) override {
    MPI_Recv(data, Count(n), MPI_DOUBLE, from, kTagHalo, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  void Flush() override {
    MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    requests_.clear();
  }
  meshreuse::FixedSum SumAll(const meshreuse::FixedSum& mine) override {
    if (kill_ && ++reductions_ == 2) raise(SIGKILL);
    uint64_t in[2], out[2];
    mine.ToWords(in);
    MPI_Allreduce(in, out, 1, fixed_, sum_, MPI_COMM_WORLD);
    return meshreuse::FixedSum::FromWords(out);
  }
  std::vector<std::string> Gather(const std::string& mine) override {
    if (rank_ != 0) {
      tx_.SendBytes(0, mine);
      return {};
    }
    std::vector<std::string> all(size_);
    all[0] = mine;
    for (int r = 1; r < size_; ++r) all[r] = tx_.RecvBytes(r);
    return all;
  }
  // Small messages (a rank's share of the checks): sizes first, then the bytes.
  std::vector<std::string> AllGather(const std::string& mine) override {
    const int n = Count(mine.size());
    std::vector<int> sizes(size_), at(size_, 0);
    MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int64_t total = 0;
    for (int r = 0; r < size_; ++r) at[r] = static_cast<int>(total), total += sizes[r];
    if (total > INT_MAX) throw std::length_error("an all-gather of more than 2^31 bytes");
    std::string bytes(static_cast<size_t>(total), '\0');
    MPI_Allgatherv(mine.data(), n, MPI_BYTE, &bytes[0], sizes.data(), at.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
    std::vector<std::string> all(size_);
    for (int r = 0; r < size_; ++r) all[r] = bytes.substr(at[r], sizes[r]);
    return all;
  }

 private:
  static int Count(size_t n) {
    if (n > static_cast<size_t>(INT_MAX))  // MPI 3.1 counts are int
      throw std::length_error("a ghost message of more than 2^31 values");
    return static_cast<int>(n);
  }
  int rank_ = 0, size_ = 1;
  bool kill_;
  int reductions_ = 0;
  MPI_Datatype fixed_;
  MPI_Op sum_;
  std::vector<MPI_Request> requests_;
  MpiTransport tx_;  // its byte messages for the gather
};

// The fault-injection hook of the tests: the transport of a rank that dies after its chunk.
class KillingTransport : public MpiTransport {
 public:
  explicit KillingTransport(bool kill) : kill_(kill) {}
  std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v) override {
    if (kill_) raise(SIGKILL);
    return MpiTransport::AllReduceMax(v);
  }

 private:
  bool kill_;
};

void Usage(std::FILE* out) {
  std::fprintf(
      out,
      "usage: mpirun -np P meshreuse-mpi analyze TRACE [--format F] [options of "
      "`meshreuse analyze`]\n       mpirun -np P meshreuse-mpi analyze MESH "
      "--orderings ONE [-k K] [--threads T] [...]\n\nThe exact reuse analysis of one "
      "input across P ranks: of a plain trace file (a meshreuse trace, a fixed-record, "
      "text or lackey one) rank r reads only its part (records [N r/P, N (r+1)/P), or "
      "the lines that begin in its bytes); of a mesh, rank r regenerates its part of the "
      "traced smoother's stream (no file). Rank 0 prints and writes what `meshreuse "
      "analyze` would. --rank-stats FILE: each rank's CPU seconds per phase, bytes sent "
      "and peak memory.\n\n       mpirun -np P meshreuse-mpi smooth MESH [--partition "
      "hilbert|metis|scotch|ranges|gmsh] [--ordering NAME] [--mode ordered|jacobi|hybrid] [-o "
      "OUT] [--pi-out "
      "FILE]\n\nLaplacian smoothing across P ranks (every rank reads MESH and keeps its "
      "part): ordered Gauss-Seidel equals the serial sweep along the order --pi-out "
      "writes, bit for bit; jacobi the serial Jacobi. `meshreuse-mpi smooth --help` for "
      "every option.\n\n       mpirun -np P meshreuse-mpi refine MESH --levels K [--jitter F] "
      "[--seed S] -o OUT.mrm\n\nUniform refinement written into one mesh file by every "
      "rank at once (each its range of blocks of coarse triangles), none holding the fine "
      "mesh: byte for byte `meshreuse mesh refine MESH --levels K --layout pieces -o "
      "OUT.mrm`.\n");
}

}  // namespace
}  // namespace meshreuse::cli

int main(int argc, char** argv) {
  using namespace meshreuse::cli;
  // PT-Scotch runs threads of its own that call MPI (Debian builds it with POSIX threads): without
  // MPI_THREAD_MULTIPLE it hung or crashed in about one run in three at -np 4 on 2 cores. Asked for
  // only when an argument names it, so every other run keeps the single-threaded library.
  bool ptscotch_asked = false;
  for (int i = 1; i < argc; ++i)
    ptscotch_asked = ptscotch_asked || std::strstr(argv[i], "ptscotch") != nullptr;
  // And Open MPI's waits yield the core (unless the user says otherwise): busy-waiting ranks beside
  // PT-Scotch's threads stalled a 16-rank partition of 3.8 million vertices for over 200 s on 16
  // cores; yielding, the whole run took 16 s.
  if (ptscotch_asked) setenv("OMPI_MCA_mpi_yield_when_idle", "1", /*overwrite=*/0);
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, ptscotch_asked ? MPI_THREAD_MULTIPLE : MPI_THREAD_SINGLE,
                  &provided);
  SetFullCommandLine(argc, argv);
  const std::vector<std::string> args(argv + 1, argv + argc);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (args.empty() || (args[0] != "analyze" && args[0] != "smooth" && args[0] != "refine")) {
    const bool help = !args.empty() && (args[0] == "--help" || args[0] == "-h");
    if (rank == 0) Usage(help ? stdout : stderr);
    MPI_Finalize();
    return help ? 0 : meshreuse::kExitBadInput;
  }
  const char* kill = std::getenv("MESHREUSE_MPI_KILL_RANK");
  const std::string who = "meshreuse-mpi: rank " + std::to_string(rank);
  const Args rest(args.begin() + 1, args.end());
  int rc;
  if (args[0] == "refine") {
    MpiHalo halo(false);
    rc = RunReportingErrors(
        "refine", [&] { return DistRefineCommand(rest, halo); }, who);
  } else if (args[0] == "smooth") {
    MpiHalo halo(kill && std::atoi(kill) == rank);
#ifdef MESHREUSE_HAVE_PTSCOTCH
    const JobPartition ptscotch = [provided](const meshreuse::Mesh& m, int32_t parts,
                                             uint64_t seed) {
      if (provided < MPI_THREAD_MULTIPLE)
        throw meshreuse::EnvironmentError(
            "--partition ptscotch",
            "PT-Scotch needs MPI_THREAD_MULTIPLE, which this MPI library "
            "does not provide");
      return PtScotchParts(m, parts, seed);
    };
#else
    const JobPartition ptscotch;  // --partition ptscotch refused: built without PT-Scotch
#endif
    rc = RunReportingErrors(
        "smooth", [&] { return DistSmoothCommand(rest, halo, ptscotch); }, who);
  } else {
    KillingTransport tx(kill && std::atoi(kill) == rank);
    rc = RunReportingErrors(
        "analyze", [&] { return AnalyzeCommand(rest, &tx); }, who);
  }
  if (rc != 0) MPI_Abort(MPI_COMM_WORLD, rc);  // ends every rank: a failure never hangs the job
  MPI_Finalize();
  return 0;
}
