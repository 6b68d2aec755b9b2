// meshreuse trace: every access of K sweeps of a mesh to a binary trace file (reports/trace.h).
#include <cstdio>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/ranks/rank_part.h"
#include "core/table.h"
#include "reports/trace.h"
#include "tracer/trace_format.h"

namespace meshreuse::cli {

int TraceCommand(const Args& args) {
  po::options_description desc("options");
  TraceConfig cfg;
  std::string mode = "gauss-seidel", triangle_order, seed = "1", element_bytes = "66";
  RankOptionText rank_text;
  desc.add_options()("mesh", po::value(&cfg.mesh)->required(), "input mesh")(
      "ordering", po::value(&cfg.ordering)->default_value("ori"),
      ("one of: " + OrderingNames()).c_str())("seed", po::value(&seed)->default_value("1"),
                                              "seed of seeded orderings")(
      "iterations,k", po::value(&cfg.iterations)->default_value(1), "sweeps to trace")(
      "threads,t", po::value(&cfg.threads)->default_value(1),
      "streams: the static schedule's threads")(
      "mode", po::value(&mode)->default_value("gauss-seidel"), "gauss-seidel or jacobi")(
      "kernel", po::value(&cfg.kernel)->default_value(kPaperKernel), KernelOptionHelp())(
      "element-bytes", po::value(&element_bytes)->default_value("66"),
      "element size recorded in the header")("output,o", po::value(&cfg.output)->required(),
                                             "trace file")(
      "compress", "zstd-compress the trace (read back transparently by analyze and simulate)")(
      "quiet,q", "no progress on stderr");
  AddTriangleOrderOption(desc, &triangle_order);
  AddRankOptions(desc, &rank_text,
                 "one trace per rank's part of a distributed smoothing run on P ranks, laid out "
                 "and swept as that rank does (--ordering inside each part): OUTPUT.rank0 ... "
                 "OUTPUT.rank(P-1)");
  po::positional_options_description pos;
  pos.add("mesh", 1);
  po::variables_map vm;
  if (!ParseOptions(args, "trace MESH [--ordering NAME] [--iterations K] [--threads P] -o FILE",
                    "Writes every access of K smoothing sweeps (or of K sweeps of another "
                    "--kernel) (vertex id, byte address, kind, "
                    "thread) to a binary trace (format in tracer/trace_format.h, 16 bytes per "
                    "access). The access sequence of one vertex visit is documented in "
                    "core/smoother.h, each other kernel's at the head of its core/kernels/ file.",
                    desc, pos, vm))
    return 0;
  cfg.seed = ParseCount(seed, "--seed", 0, UINT64_MAX >> 1);
  cfg.element_bytes =
      static_cast<uint32_t>(ParseCount(element_bytes, "--element-bytes", 1, 1 << 20));
  cfg.mode = ParseUpdateMode(mode);
  cfg.triangle_order = ParseTriangleOrder(triangle_order);
  cfg.compress = vm.count("compress") > 0;
  const RankOptions ro = RankOptionsOf(rank_text, vm);
  cfg.ranks = ro.ranks, cfg.partition = ro.partition, cfg.cut_placement = ro.placement;
  const Progress progress(vm.count("quiet") > 0);
  const TraceRunResult r = RunTrace(cfg, MakeLog(progress));
  if (cfg.ranks > 0) {
    std::printf(
        "wrote %s.rank0 ... %s.rank%d: %s accesses, %s element touches, %d sweep(s), %.2f s\n",
        cfg.output.c_str(), cfg.output.c_str(), cfg.ranks - 1,
        Grouped(static_cast<long long>(r.records)).c_str(),
        Grouped(static_cast<long long>(r.elements)).c_str(), cfg.iterations, r.seconds);
    return 0;
  }
  const double per = static_cast<double>(r.vertices) * cfg.iterations;
  std::printf(
      "wrote %s: %s accesses (%s per vertex per sweep), %s element touches (%s), %d sweep(s), "
      "%d stream(s), %.1f MB%s, %.2f s\n",
      cfg.output.c_str(), Grouped(static_cast<long long>(r.records)).c_str(),
      Fixed(static_cast<double>(r.records) / per, 2).c_str(),
      Grouped(static_cast<long long>(r.elements)).c_str(),
      Fixed(static_cast<double>(r.elements) / per, 2).c_str(), cfg.iterations, cfg.threads,
      (static_cast<double>(r.records) * sizeof(TraceRecord)) / 1e6,
      cfg.compress
          ? (" (" + Fixed(static_cast<double>(r.compressed_bytes) / 1e6, 1) + " MB compressed)")
                .c_str()
          : "",
      r.seconds);
  return 0;
}

}  // namespace meshreuse::cli
