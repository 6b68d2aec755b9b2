// What the subcommands share: option parsing with --help (options.h), the output format flags,
// the progress and warning lines on stderr (a Log for the runners), lists, thread lists, output
// folders, run.json. Errors are thrown as they are (core/error.h); main maps them to exit codes.
#pragma once

#include <string>
#include <vector>

#include "cli/options.h"
#include "cli/progress.h"
#include "core/permutation.h"
#include "core/ranks/rank_part.h"
#include "reports/log.h"
#include "reports/output.h"
#include "reports/run_info.h"
#include "reports/stream_source.h"

namespace meshreuse::cli {

// --json, --csv, --markdown (those a command offers): one at most (UsageError otherwise).
void AddFormatOptions(po::options_description& desc, bool markdown = false);
OutputFormat FormatOption(const po::variables_map& vm);

// Progress lines through `progress` (silent with --quiet); warnings always, as
// "meshreuse: warning: ...".
Log MakeLog(const Progress& progress);

std::vector<std::string> SplitList(const std::string& s);  // "a,b,,c" -> {a, b, c}
// "1,2,4" -> {1, 2, 4}: UsageError for a non-number, a count outside 1..kMaxThreads, an empty list.
std::vector<int> ParseThreadList(const std::string& s);
// A number option that must be within [lo, hi] (UsageError naming it). Parsed as text so that a
// negative value is refused rather than wrapped.
uint64_t ParseCount(const std::string& text, const std::string& option, uint64_t lo, uint64_t hi);

// An output folder, before any work: made if missing (with its parents); UsageError if it or an
// ancestor is a file, it cannot be written, or (must_be_empty) it already holds files.
void PrepareOutDir(const std::string& dir, bool must_be_empty = false);

// --triangle-order sorted|file, the same text on every command that lays a mesh out.
// The mesh formats -o writes, for every command's help (core/mesh_io.h WriteMesh).
inline constexpr const char* kMeshOutputFormats =
    "PATH.vtu (VTK XML, binary and compressed: ParaView's own), PATH.vtk (legacy VTK, ASCII), "
    "PATH.msh (Gmsh 4.1), PATH.mrm (the distributed mesh file) or a prefix for Triangle's "
    ".node/.ele";

void AddTriangleOrderOption(po::options_description& desc, std::string* value);
// --kernel's help: the registered kernels (cli/cmd_kernels.cc).
const char* KernelOptionHelp();

// --ranks P, --partition and --cut-placement of the per-rank runs (reports/rank_locality.h);
// `ranks` describes what --ranks does for this command. RankOptionsOf reads them back, refusing
// --partition or --cut-placement without --ranks.
struct RankOptions {
  int32_t ranks = 0;  // 0: not asked
  std::string partition = "hilbert";
  CutPlacement placement = CutPlacement::kLast;
};
struct RankOptionText {
  std::string ranks, partition = "hilbert", placement = "last";
};
void AddRankOptions(po::options_description& desc, RankOptionText* text, const char* ranks);
RankOptions RankOptionsOf(const RankOptionText& text, const po::variables_map& vm);

// The stream source's options (reports/stream_source.h), the same on every command that streams
// its inputs: --orderings, --seed, -k, -t, --mode, --triangle-order, and where `help` asks,
// --format and --instructions (other tools' traces) and --ranks, --partition, --cut-placement.
// `help` words what differs by command; SourceOf reads them back into `src`.
struct SourceHelp {
  const char* orderings = "for meshes: comma-separated orderings";
  const char* seed = "seed of seeded orderings";
  const char* iterations = "for meshes: sweeps";
  const char* threads = "for meshes: streams (static schedule)";
  std::string format;             // "" : no --format (nor --instructions)
  const char* instructions = "";  // --instructions' help
  const char* ranks = nullptr;    // --ranks' help; nullptr: no rank options
  bool thread_list = false;       // --threads takes a list (SourceOptionText::threads)
};
struct SourceOptionText {
  std::string orderings = "ori", seed = "1", mode = "gauss-seidel", triangle_order,
              kernel = kPaperKernel;
  RankOptionText ranks;
  std::string threads = "1";     // with SourceHelp::thread_list
  std::vector<int> thread_list;  // what SourceOf read from it
  bool threads_as_text = false;  // AddSourceOptions declared --threads as a list
};
void AddSourceOptions(po::options_description& desc, StreamSource* src, SourceOptionText* text,
                      const SourceHelp& help);
void SourceOf(SourceOptionText& text, const po::variables_map& vm, StreamSource* src);

// Two outputs of one run on one file (`-o same.vtk --pi-out same.vtk`; links and relative paths
// resolved): UsageError naming both options, before any work. Empty paths are not given outputs.
void CheckDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& option_paths);

// Warns (stderr) of temporaries of `path` an earlier run left when it was killed (PATH.tmp.PID
// whose process is gone): the files a cancelled job could not remove, named for the user.
void WarnStaleTemporaries(const std::string& path);

// For a caller that is not the command (cli/configs.h): UsageError naming the first of these
// options that was given ("--csv is the command line's: ...").
void RefuseCommandOptions(const po::variables_map& vm, const std::vector<std::string>& options);

// The full command line, for run.json.
const std::vector<std::string>& FullCommandLine();
// A runner's output: printed on stdout in `fmt` and, with `out_dir`, written under it (its
// tables, text files and run.json), the files written listed on `progress`.
void Emit(const RunOutput& out, OutputFormat fmt, const std::string& out_dir,
          const Progress& progress);
// DIR/run.json for this command.
void WriteRunJson(const std::string& dir, const std::string& tool, const Json& configuration,
                  const Json& extra = Json::object());

}  // namespace meshreuse::cli
