// The meshreuse subcommands, one file each (cmd_*.cc). Each parses its own options
// (Boost.Program_options, --help on each) into a runner's configuration (reports/), calls it and
// prints; none does any computing of its own. The table in main.cc maps names to these functions.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace meshreuse {
class Communicator;
struct GraphRows;
}  // namespace meshreuse

namespace meshreuse::cli {

using Args = std::vector<std::string>;  // the arguments after the subcommand's name

int MeshInfo(const Args& args);
int MeshGenerate(const Args& args);
int MeshConvert(const Args& args);
int MeshRefine(const Args& args);
int MeshPartition(const Args& args);
int SmoothCommand(const Args& args);
int OrderingsCommand(const Args& args);
int KernelsCommand(const Args& args);
int ReorderCommand(const Args& args);
int CompareCommand(const Args& args);
int TraceCommand(const Args& args);
int CompressCommand(const Args& args);
int AnalyzeCommand(const Args& args);
// With a transport: one rank of a distributed analysis (cli/mpi_main.cc); rank 0 prints and writes.
int AnalyzeCommand(const Args& args, Communicator* transport);
// One rank of the distributed smoother (cli/mpi_main.cc); rank 0 prints and writes.
// `job_partition`: what --partition ptscotch calls (DistSmoothConfig::job_partition).
using JobPartition = std::function<std::vector<int32_t>(const GraphRows&, int32_t, uint64_t)>;
int DistSmoothCommand(const Args& args, Communicator& transport,
                      const JobPartition& job_partition = {});
// One rank of the distributed refinement into a mesh file (`meshreuse-mpi refine`; `meshreuse
// mesh refine --ranks P` runs it on threads); rank 0 prints.
int DistRefineCommand(const Args& args, Communicator& transport);
// The same ranks as threads of this process (core/ranks/thread_communicator.h): `meshreuse
// smooth-ranks`.
int DistSmoothThreads(const Args& args);
int SimulateCommand(const Args& args);
int ValidateCommand(const Args& args);
int ReportCommand(const Args& args);

// cli/entry.cc: body() with core/error.h's errors reported on stderr as "WHO: error: ..." and
// mapped to exit codes (2 bad input or options, 3 environment, 1 a bug).
int RunReportingErrors(const char* name, const std::function<int()>& body,
                       const std::string& who = "meshreuse");
void SetFullCommandLine(int argc, char** argv);

}  // namespace meshreuse::cli
