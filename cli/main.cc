// meshreuse: the command-line front end. One table maps subcommand names to functions; errors are
// reported by RunReportingErrors (cli/entry.cc, core/error.h): bad input or options exit 2, a
// failing environment (disk full, permission denied, a missing program, out of memory) exits 3, a
// bug exits 1.
#include <malloc.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/common.h"
#include "core/error.h"
#include "core/output_file.h"
#include "reports/run_info.h"

namespace meshreuse::cli {

namespace {

struct Command {
  const char* name;  // words, e.g. "mesh info"
  const char* summary;
  int (*run)(const Args&);
};

const Command kCommands[] = {
    {"mesh info", "vertices, triangles, boundary and quality of a mesh", MeshInfo},
    {"mesh generate", "mesh one of the nine shapes (or a .poly) with Triangle", MeshGenerate},
    {"mesh convert", "read any supported mesh, write .vtu, .vtk, .msh, .mrm or .node/.ele",
     MeshConvert},
    {"mesh refine", "each triangle into 4^K, ids computable anywhere", MeshRefine},
    {"mesh partition", "parts for smoothing across ranks, and what they cost", MeshPartition},
    {"orderings", "list the vertex orderings", OrderingsCommand},
    {"kernels", "list the mesh kernels (--kernel): laplacian, assembly, spmv, ...", KernelsCommand},
    {"reorder", "reorder a mesh's vertices, write the mesh and the permutation", ReorderCommand},
    {"smooth", "Laplacian smoothing, per-sweep quality and time", SmoothCommand},
    {"smooth-ranks", "the MPI smoother's P ranks as threads of one process, bit for bit",
     DistSmoothThreads},
    {"compare", "time the smoother under several orderings and thread counts", CompareCommand},
    {"trace", "write the smoother's access trace to a binary file", TraceCommand},
    {"compress", "any trace into zstd frames that chunks and threads can enter", CompressCommand},
    {"analyze", "reuse distances, quantiles, histograms, profiles and modelled misses",
     AnalyzeCommand},
    {"simulate", "set-associative cache simulation of every load and store", SimulateCommand},
    {"validate", "the miss model against the simulator and hardware counters; Table 3",
     ValidateCommand},
    {"report", "the paper's experiment: every table and figure's data, with the paper's values",
     ReportCommand},
};

void Usage(std::FILE* out) {
  std::fprintf(out,
               "meshreuse: locality research on unstructured meshes\n\n"
               "usage: meshreuse <command> [options]   (meshreuse <command> --help; meshreuse "
               "--version)\n\ncommands:\n");
  for (const Command& c : kCommands) std::fprintf(out, "  %-16s %s\n", c.name, c.summary);
}

// Number of words of `name` that match args from `first`, or 0.
size_t Matches(const char* name, const std::vector<std::string>& args) {
  size_t i = 0;
  const char* p = name;
  while (*p) {
    const char* sp = std::strchr(p, ' ');
    const size_t len = sp ? static_cast<size_t>(sp - p) : std::strlen(p);
    if (i >= args.size() || args[i] != std::string(p, len)) return 0;
    ++i;
    p += len + (sp ? 1 : 0);
  }
  return i;
}

}  // namespace

int Main(int argc, char** argv) {
  SetFullCommandLine(argc, argv);
  InstallOutputCleanup();
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    Usage(args.empty() ? stderr : stdout);
    return args.empty() ? kExitBadInput : 0;
  }
  if (args[0] == "--version" || args[0] == "version") {
    std::printf("%s\n", VersionString().c_str());
    return 0;
  }
  const Command* cmd = nullptr;
  size_t used = 0;
  for (const Command& c : kCommands) {
    const size_t n = Matches(c.name, args);
    if (n > used) cmd = &c, used = n;
  }
  if (!cmd) {
    // "mesh" alone, or "mesh --help": the group's commands.
    if (args[0] == "mesh") {
      const bool help = args.size() > 1 && (args[1] == "--help" || args[1] == "-h");
      std::FILE* out = help ? stdout : stderr;
      if (!help && args.size() > 1)
        std::fprintf(stderr, "meshreuse: unknown command 'mesh %s'\n\n", args[1].c_str());
      std::fprintf(out,
                   "usage: meshreuse mesh info|generate|convert|refine|partition [options]\n\n");
      for (const Command& c : kCommands)
        if (std::strncmp(c.name, "mesh ", 5) == 0)
          std::fprintf(out, "  %-16s %s\n", c.name, c.summary);
      return help ? 0 : kExitBadInput;
    }
    std::fprintf(stderr, "meshreuse: unknown command '%s'\n\n", args[0].c_str());
    Usage(stderr);
    return kExitBadInput;
  }
  return RunReportingErrors(cmd->name,
                            [&] { return cmd->run(Args(args.begin() + used, args.end())); });
}

}  // namespace meshreuse::cli

int main(int argc, char** argv) {
  // Arrays of a megabyte or more are mapped on their own and given back when freed. glibc would
  // otherwise raise this threshold after the first large free (up to 32 MiB), and the arrays a
  // command frees on its way (reading, reordering) would stay resident in its heap: the memory
  // budget (README) is of what a command holds, not of what the allocator keeps.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  return meshreuse::cli::Main(argc, argv);
}
