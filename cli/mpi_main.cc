// meshreuse-mpi: `mpirun -np P meshreuse-mpi analyze INPUT [analyze's options]` -- the exact reuse
// analysis of one trace file or mesh across P ranks (reports/chunk_summary.h, RunDistributed):
// rank r reads (or, for a mesh, regenerates) only its own records, the LRU stacks stream rank to
// rank in blocks of 64 Ki ids, rank 0 prints and writes exactly what `meshreuse analyze INPUT`
// would. This file only moves bytes; the
// libraries stay MPI-free. A rank that fails prints "meshreuse-mpi: rank R: error: ..." and aborts
// the whole job with the error's exit status (2 bad input, 3 environment, 1 a bug), never a hang.
// For tests, MESHREUSE_MPI_KILL_RANK=R makes rank R kill itself (SIGKILL) after analysing its
// chunk: the job must end, non-zero, naming the rank.
#include <mpi.h>
#include <signal.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
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
  std::fprintf(out,
               "usage: mpirun -np P meshreuse-mpi analyze TRACE [--format F] [options of "
               "`meshreuse analyze`]\n       mpirun -np P meshreuse-mpi analyze MESH "
               "--orderings ONE [-k K] [--threads T] [...]\n\nThe exact reuse analysis of one "
               "input across P ranks: of a plain trace file (a meshreuse trace, a fixed-record, "
               "text or lackey one) rank r reads only its part (records [N r/P, N (r+1)/P), or "
               "the lines that begin in its bytes); of a mesh, rank r regenerates its part of the "
               "traced smoother's stream (no file). Rank 0 prints and writes what `meshreuse "
               "analyze` would. --rank-stats FILE: each rank's CPU seconds per phase, bytes sent "
               "and peak memory.\n");
}

}  // namespace
}  // namespace meshreuse::cli

int main(int argc, char** argv) {
  using namespace meshreuse::cli;
  MPI_Init(&argc, &argv);
  SetFullCommandLine(argc, argv);
  const std::vector<std::string> args(argv + 1, argv + argc);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (args.empty() || args[0] != "analyze") {
    const bool help = !args.empty() && (args[0] == "--help" || args[0] == "-h");
    if (rank == 0) Usage(help ? stdout : stderr);
    MPI_Finalize();
    return help ? 0 : meshreuse::kExitBadInput;
  }
  const char* kill = std::getenv("MESHREUSE_MPI_KILL_RANK");
  KillingTransport tx(kill && std::atoi(kill) == rank);
  const std::string who = "meshreuse-mpi: rank " + std::to_string(rank);
  const int rc = RunReportingErrors(
      "analyze", [&] { return AnalyzeCommand(Args(args.begin() + 1, args.end()), &tx); }, who);
  if (rc != 0) MPI_Abort(MPI_COMM_WORLD, rc);  // ends every rank: a failure never hangs the job
  MPI_Finalize();
  return 0;
}
