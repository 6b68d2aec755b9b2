// meshreuse analyze: reuse distances, quantiles, histograms, profiles and modelled misses of
// meshes (streamed, no file), trace files or other tools' traces (reports/analyze.h).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/analyze_options.h"
#include "cli/common.h"
#include "core/error.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "reports/analyze.h"
#include "reports/chunks/chunk_threads.h"
#include "reports/chunks/summarize_chunk.h"
#include "tracer/trace_formats.h"

namespace meshreuse::cli {

int AnalyzeCommand(const Args& args) { return AnalyzeCommand(args, nullptr); }

int AnalyzeCommand(const Args& args, Communicator* transport) {
  AnalyzeConfig cfg;
  AnalyzeOptionText t;
  po::variables_map vm;
  if (!ParseAnalyze(args, transport, {}, &cfg, &t, &vm)) return 0;
  const std::string &hist_csv = t.hist_csv, &prof_csv = t.prof_csv, &mrc_csv = t.mrc_csv,
                    &out_dir = t.out_dir, &rank_stats = t.rank_stats;
  // A distributed run: every rank analyses its chunk; rank 0 alone prints and writes.
  const bool writer = !transport || transport->rank() == 0;
  const OutputFormat fmt = FormatOption(vm);
  if (cfg.chunk) {
    if (!hist_csv.empty() || !prof_csv.empty() || !mrc_csv.empty() || !out_dir.empty() ||
        !cfg.vtk.empty() || fmt != OutputFormat::kText)
      throw UsageError("--chunk writes its summary only: merge the summaries for the tables");
    CheckOutputPath(cfg.summary_out, "--summary-out", InputFiles(cfg.inputs));
    const Progress progress(vm.count("quiet") > 0);
    RunChunk(cfg, cfg.chunk->first, cfg.chunk->second, cfg.summary_out, MakeLog(progress));
    return 0;
  }
  if (!rank_stats.empty() && !transport) {
    bool chunked = cfg.threads > 1 && cfg.ranks == 0;
    for (const std::string& in : cfg.inputs)  // a missing file is reported by the analysis
      chunked = chunked && (!std::filesystem::exists(in) ||
                            ((!cfg.format.empty() || ClassifyInput(in) != InputKind::kMesh) &&
                             CanAnalyzeInChunks(cfg, in)));
    if (!chunked)
      throw UsageError(
          "--rank-stats is for a distributed run (mpirun ... meshreuse-mpi analyze), or "
          "--threads over trace files that can be cut (plain, or zstd in frames: a chunk per "
          "thread)");
  }
  if (writer) {
    std::vector<std::pair<std::string, std::string>> outputs = {{"--histogram-csv", hist_csv},
                                                                {"--profile-csv", prof_csv},
                                                                {"--mrc-csv", mrc_csv},
                                                                {"--vtk", cfg.vtk},
                                                                {"--rank-stats", rank_stats}};
    if (!out_dir.empty())
      for (const char* f :
           {"analyze.csv", "analyze.json", "histogram.csv", "profile.csv", "run.json"})
        outputs.emplace_back("--out", out_dir + "/" + f);
    CheckDistinctOutputs(outputs);
    if (!rank_stats.empty()) CheckOutputPath(rank_stats, "--rank-stats", InputFiles(cfg.inputs));
    for (const auto& [path, opt] :
         {std::pair{hist_csv, "--histogram-csv"}, std::pair{prof_csv, "--profile-csv"},
          std::pair{mrc_csv, "--mrc-csv"}})
      if (!path.empty()) CheckOutputPath(path, opt, InputFiles(cfg.inputs));
    if (!cfg.vtk.empty()) CheckOutputPath(cfg.vtk, "--vtk", InputFiles(cfg.inputs));
    if (!out_dir.empty()) PrepareOutDir(out_dir);
  }

  const Progress progress(vm.count("quiet") > 0 || !writer);
  const AnalyzeResult r = RunAnalyze(cfg, MakeLog(progress));
  if (!writer) return 0;
  if (r.sampling) {  // merged summaries of a sampled analysis: their tables
    cfg.sample = true;
    cfg.shards = *r.sampling;
    cfg.sample_error = r.sampling_with_exact;
  }
  if (!rank_stats.empty())
    WriteAtomically(rank_stats, [&](std::FILE* f) {
      const std::string j = RankStatsJson(r.ranks).dump(2) + "\n";
      if (std::fwrite(j.data(), 1, j.size(), f) != j.size())
        throw EnvironmentError(rank_stats, "cannot write");
    });
  const Table prof = ProfileTable(r);
  // A trace without sweeps (a foreign one of unknown length) has no profile: say so rather than
  // write an empty file.
  const bool no_profile = cfg.profile && prof.Rows() == 0;
  if (no_profile)
    std::fprintf(stderr,
                 "meshreuse: note: no profile written: the input has no sweeps (a foreign trace "
                 "whose length is not known up front, on standard input or in zstd frames that "
                 "do not record their size, cannot be cut into time steps)\n");
  if (!hist_csv.empty()) WriteCsvFile(hist_csv, HistogramTable(r));
  if (!prof_csv.empty() && !no_profile) WriteCsvFile(prof_csv, prof);
  if (!mrc_csv.empty()) WriteCsvFile(mrc_csv, MrcTable(r));
  for (const std::string& w : SampleWarnings(r, cfg))  // warnings: --quiet keeps them
    std::fprintf(stderr, "meshreuse: warning: %s\n", w.c_str());
  Emit(AnalyzeOutput(r, cfg), fmt, out_dir, progress);
  return 0;
}

}  // namespace meshreuse::cli
