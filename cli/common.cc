// Shared CLI helpers; see common.h.
#include "cli/common.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/schedule.h"
#include "core/table.h"

namespace meshreuse::cli {

void AddFormatOptions(po::options_description& desc, bool markdown) {
  desc.add_options()("json", "print JSON")("csv", "print CSV (every digit)");
  if (markdown) desc.add_options()("markdown", "print Markdown tables");
}

OutputFormat FormatOption(const po::variables_map& vm) {
  std::string given;
  int n = 0;
  for (const char* f : {"json", "csv", "markdown"})
    if (vm.count(f)) given += std::string(n++ ? " and --" : "--") + f;
  if (n > 1) throw UsageError(given + " exclude each other: give one");
  return vm.count("json")       ? OutputFormat::kJson
         : vm.count("csv")      ? OutputFormat::kCsv
         : vm.count("markdown") ? OutputFormat::kMarkdown
                                : OutputFormat::kText;
}

Log MakeLog(const Progress& progress) {
  Log log;
  log.progress = [&progress](const std::string& s) { progress.Say(s); };
  log.warn = [](const std::string& w) {
    std::fprintf(stderr, "meshreuse: warning: %s\n", w.c_str());
  };
  return log;
}

std::vector<std::string> SplitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

uint64_t ParseCount(const std::string& text, const std::string& option, uint64_t lo, uint64_t hi) {
  const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    throw UsageError(option + " takes a whole number in " + range + ", found '" + text + "'");
  const uint64_t v = std::stoull(text);
  if (v < lo || v > hi) throw UsageError(option + " must be in " + range + ", found " + text);
  return v;
}

std::vector<int> ParseThreadList(const std::string& s) {
  std::vector<int> out;
  for (const std::string& t : SplitList(s))
    out.push_back(static_cast<int>(ParseCount(t, "--threads", 1, kMaxThreads)));
  if (out.empty()) throw UsageError("--threads is empty");
  return out;
}

void PrepareOutDir(const std::string& dir, bool must_be_empty) {
  namespace fs = std::filesystem;
  if (dir.empty()) throw UsageError("--out: the folder name is empty");
  std::error_code ec;
  for (fs::path p = fs::path(dir); !p.empty(); p = p.parent_path()) {
    if (fs::exists(p, ec)) {
      if (!fs::is_directory(p, ec))
        throw UsageError("cannot write to '" + dir + "': '" + p.string() + "' is not a folder");
      break;
    }
    if (p == p.parent_path()) break;
  }
  fs::create_directories(dir, ec);
  if (ec) throw UsageError("cannot make the folder '" + dir + "': " + ec.message());
  if (::access(dir.c_str(), W_OK) != 0)
    throw UsageError("cannot write to the folder '" + dir + "': permission denied");
  if (must_be_empty && !fs::is_empty(dir, ec))
    throw UsageError("the folder '" + dir +
                     "' is not empty (a previous run's files would mix with this one's): give a "
                     "new folder");
}

void AddTriangleOrderOption(po::options_description& desc, std::string* value) {
  desc.add_options()("triangle-order", po::value(value)->default_value("sorted"),
                     "sorted: triangles follow the new vertex order (every ordering alike, ori "
                     "too); file: the file's triangle order (with ori: the file as is, the "
                     "paper's ORI)");
}

void WriteRunJson(const std::string& dir, const std::string& tool, const Json& configuration,
                  const Json& extra) {
  WriteTextFile(dir + "/run.json",
                RunJsonText(RunJson(tool, FullCommandLine(), configuration, extra)));
}

void Emit(const RunOutput& out, OutputFormat fmt, const std::string& out_dir,
          const Progress& progress) {
  if (fmt == OutputFormat::kJson) {
    if (const RunOutput::TablePtr* t = std::get_if<RunOutput::TablePtr>(&out.json))
      Print(**t, fmt);
    else
      std::printf("%s\n", std::get<Json>(out.json).dump(1).c_str());
  } else if (fmt != OutputFormat::kText) {
    if (out.csv) Print(*out.csv, fmt);
  } else {
    for (const auto& part : out.text)
      if (const RunOutput::TablePtr* t = std::get_if<RunOutput::TablePtr>(&part))
        Print(**t, fmt);
      else
        std::printf("%s\n", std::get<std::string>(part).c_str());
  }
  if (out_dir.empty()) return;
  std::string wrote;
  for (const RunOutput::TableFile& f : out.tables) {
    WriteTableFiles(out_dir, f.name, *f.table, f.exts);
    for (const std::string& e : f.exts) wrote += (wrote.empty() ? "" : ",") + f.name + "." + e;
  }
  for (const auto& [name, text] : out.files) {
    WriteTextFile(out_dir + "/" + name, text);
    wrote += (wrote.empty() ? "" : ",") + name;
  }
  WriteRunJson(out_dir, out.tool, out.configuration, out.extra);
  progress.Say("wrote " + out_dir + "/{" + wrote + (wrote.empty() ? "" : ",") + "run.json}");
}

void CheckDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& option_paths) {
  std::vector<std::pair<std::string, const std::pair<std::string, std::string>*>> seen;
  for (const auto& op : option_paths) {
    if (op.second.empty() || op.second == "-") continue;
    std::error_code ec;
    std::string key = std::filesystem::weakly_canonical(op.second, ec).string();
    if (ec) key = op.second;
    for (const auto& [k, first] : seen)
      if (k == key)
        throw UsageError(op.first + " '" + op.second + "' is the file " + first->first +
                         " writes too: give each output its own path");
    seen.emplace_back(key, &op);
  }
}

void WarnStaleTemporaries(const std::string& path) {
  for (const std::string& t : StaleTemporaries(path))
    std::fprintf(stderr,
                 "meshreuse: warning: %s: a temporary an earlier run left when it was killed (its "
                 "process is gone): remove it\n",
                 t.c_str());
}

void AddSourceOptions(po::options_description& desc, StreamSource* src, SourceOptionText* text,
                      const SourceHelp& help) {
  desc.add_options()("orderings", po::value(&text->orderings)->default_value(text->orderings),
                     help.orderings)("seed", po::value(&text->seed)->default_value("1"), help.seed)(
      "iterations,k", po::value(&src->iterations)->default_value(src->iterations), help.iterations);
  text->threads_as_text = help.thread_list;
  if (help.thread_list)
    desc.add_options()("threads,t", po::value(&text->threads)->default_value("1"), help.threads);
  else
    desc.add_options()("threads,t", po::value(&src->threads)->default_value(1), help.threads);
  desc.add_options()("mode", po::value(&text->mode)->default_value("gauss-seidel"),
                     "for meshes: gauss-seidel or jacobi")(
      "kernel", po::value(&text->kernel)->default_value(kPaperKernel), KernelOptionHelp());
  if (!help.format.empty())
    desc.add_options()("format", po::value(&src->format), help.format.c_str())("instructions",
                                                                               help.instructions);
  if (help.ranks) AddRankOptions(desc, &text->ranks, help.ranks);
  AddTriangleOrderOption(desc, &text->triangle_order);
}

void SourceOf(SourceOptionText& text, const po::variables_map& vm, StreamSource* src) {
  if (text.threads_as_text) {
    text.thread_list = ParseThreadList(text.threads);
    src->threads = text.thread_list[0];
  }
  src->orderings = ParseOrderingSpecs(SplitList(text.orderings));
  src->seed = ParseCount(text.seed, "--seed", 0, UINT64_MAX >> 1);
  src->mode = ParseUpdateMode(text.mode);
  src->kernel = ParseKernel(text.kernel).name;
  src->triangle_order = ParseTriangleOrder(text.triangle_order);
  src->instructions = vm.count("instructions") > 0;
  if (vm.count("ranks") || vm.count("partition")) {
    const RankOptions ro = RankOptionsOf(text.ranks, vm);
    src->ranks = ro.ranks, src->partition = ro.partition, src->cut_placement = ro.placement;
  }
}

void AddRankOptions(po::options_description& desc, RankOptionText* text, const char* ranks) {
  desc.add_options()("ranks", po::value(&text->ranks), ranks)(
      "partition", po::value(&text->partition)->default_value("hilbert"),
      "with --ranks: hilbert, metis, scotch, ranges, gmsh (a Gmsh split set's own) or file:PATH "
      "(one part per line: `mesh partition -o`'s, METIS's or Scotch's)")(
      "cut-placement", po::value(&text->placement)->default_value("last"),
      "with --ranks: where each part keeps its cut vertices: last, first or interleaved "
      "(meshreuse-mpi smooth --help)");
}

RankOptions RankOptionsOf(const RankOptionText& text, const po::variables_map& vm) {
  RankOptions o;
  if (!text.ranks.empty())
    o.ranks = static_cast<int32_t>(ParseCount(text.ranks, "--ranks", 1, 65536));
  o.partition = text.partition;
  o.placement = ParseCutPlacement(text.placement);
  if (o.ranks == 0 && (!vm["partition"].defaulted() || !vm["cut-placement"].defaulted()))
    throw UsageError("--partition and --cut-placement need --ranks");
  return o;
}

void RefuseCommandOptions(const po::variables_map& vm, const std::vector<std::string>& options) {
  for (const std::string& o : options)
    if (vm.count(o) && !vm[o].defaulted())
      throw UsageError("--" + o +
                       " is the command line's (printing and writing tables): here the results "
                       "are returned");
}

}  // namespace meshreuse::cli
