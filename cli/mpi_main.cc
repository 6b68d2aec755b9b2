// meshreuse-mpi: `mpirun -np P meshreuse-mpi analyze INPUT [analyze's options]` -- the exact reuse
// analysis of one trace file or mesh across P ranks (reports/chunks/distributed_analysis.h,
// RunDistributed): rank r reads (or, for a mesh, regenerates) only its own records, the LRU stacks
// stream rank to rank in blocks of 64 Ki ids, rank 0 prints and writes exactly what `meshreuse
// analyze INPUT` would. `mpirun -np P meshreuse-mpi smooth MESH [smooth's options]`: the
// distributed Laplacian smoother (reports/distributed_smooth.h), ghosts exchanged between
// neighbouring ranks. `mpirun -np P meshreuse-mpi refine MESH --levels K -o OUT.mrm`: the refined
// mesh file written by every rank (reports/distributed_refine.h). This file and its communicator
// (cli/mpi_communicator.h) only move bytes; the libraries stay MPI-free. A rank that fails prints
// "meshreuse-mpi: rank R: error: ..." and aborts the whole job with the error's exit status (2 bad
// input, 3 environment, 1 a bug), never a hang. For tests, MESHREUSE_MPI_KILL_RANK=R makes rank R
// kill itself (SIGKILL) after analysing its chunk, or in smooth's first sweep: the job must end,
// non-zero, naming the rank.
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/mpi_communicator.h"
#ifdef MESHREUSE_HAVE_PTSCOTCH
#include "cli/mpi_ptscotch.h"
#endif
#include "core/error.h"
#include "core/output_file.h"

namespace meshreuse::cli {
namespace {

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
  // Temporaries (this rank's outputs, and a file every rank writes together) are removed on
  // SIGINT and SIGTERM (what mpirun forwards when cancelled: SLURM's scancel) and before an abort.
  meshreuse::InstallOutputCleanup();
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
    MpiCommunicator comm;
    rc = RunReportingErrors(
        "refine", [&] { return DistRefineCommand(rest, comm); }, who);
  } else if (args[0] == "smooth") {
    // The fault injection dies in the rank's second all-reduce: the first sweep's quality sum.
    MpiCommunicator comm(kill && std::atoi(kill) == rank ? 2 : 0);
#ifdef MESHREUSE_HAVE_PTSCOTCH
    const JobPartition ptscotch = [provided](const meshreuse::GraphRows& rows, int32_t parts,
                                             uint64_t seed) {
      if (provided < MPI_THREAD_MULTIPLE)
        throw meshreuse::EnvironmentError(
            "--partition ptscotch",
            "PT-Scotch needs MPI_THREAD_MULTIPLE, which this MPI library "
            "does not provide");
      return PtScotchParts(rows, parts, seed);
    };
#else
    const JobPartition ptscotch;  // --partition ptscotch refused: built without PT-Scotch
#endif
    rc = RunReportingErrors(
        "smooth", [&] { return DistSmoothCommand(rest, comm, ptscotch); }, who);
  } else {
    // The fault injection dies in the rank's first all-reduce, after analysing its chunk.
    MpiCommunicator comm(kill && std::atoi(kill) == rank ? 1 : 0);
    rc = RunReportingErrors(
        "analyze", [&] { return AnalyzeCommand(rest, &comm); }, who);
  }
  if (rc != 0) {
    meshreuse::RemoveTemporaries();  // MPI_Abort ends the ranks without unwinding
    // What follows is Open MPI's own report of the abort (its banner, ORTE_ERROR_LOG lines):
    // said, so that a user reads the line above as the cause.
    std::fprintf(stderr,
                 "%s: ending the job with exit status %d; the lines that follow, if any, are "
                 "Open MPI's own report of the abort\n",
                 who.c_str(), rc);
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, rc);  // ends every rank: a failure never hangs the job
  }
  MPI_Finalize();
  return 0;
}
