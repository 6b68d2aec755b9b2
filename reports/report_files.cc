// The report's files; see report_files.h.
#include "reports/report_files.h"

#include <set>

#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/table.h"
#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse::report {

std::string LevelsText(const std::vector<CacheLevel>& levels) {
  std::string s;
  for (const CacheLevel& l : levels)
    s += (s.empty() ? "" : ", ") + l.name + " " + std::to_string(l.bytes / 1024) + " KiB " +
         std::to_string(l.ways) + "-way";
  return s;
}

namespace {

std::string FigureTitle(const ReportFigure& f, const ReportConfig& cfg) {
  std::string t = f.title;
  auto sub = [&](const std::string& key, const std::string& value) {
    for (size_t at; (at = t.find(key)) != std::string::npos;) t.replace(at, key.size(), value);
  };
  sub("{figure1_mesh}", cfg.figure1_mesh);
  sub("{profile_mesh}", cfg.profile_mesh);
  sub("{profile_sweeps}", std::to_string(cfg.profile_sweeps));
  return t;
}

std::vector<std::string> Words(const std::string& s) {
  std::vector<std::string> w;
  size_t i = 0;
  while (i < s.size()) {
    const size_t j = s.find(' ', i);
    if (j > i) w.push_back(s.substr(i, j == std::string::npos ? std::string::npos : j - i));
    if (j == std::string::npos) break;
    i = j + 1;
  }
  return w;
}

}  // namespace

Json ConfigurationJson(const ReportConfig& cfg) {
  Json j;
  j["label"] = cfg.label;
  j["meshes"] = cfg.meshes;
  j["orderings"] = cfg.orderings;
  j["ordering_seeds"] = OrderingSeedsJson(ParseOrderingSpecs(cfg.orderings), cfg.seed);
  j["seed"] = cfg.seed;
  cfg.AddJson(&j);
  j["caches"] = LevelsText(cfg.cache.levels);
  j["machine"] = cfg.machine;
  j["machine_threads"] = cfg.machine_threads;
  j["machine_sweeps"] = cfg.machine_sweeps;
  j["machine_interleave"] = "a vertex visit of each thread per turn";
  j["prefetch_levels"] = cfg.prefetch_levels;
  j["cache_spec"] = cfg.cache.text;
  j["element_bytes"] = cfg.element_bytes;
  j["line_bytes"] = cfg.line_bytes;
  j["validate_sweeps"] = cfg.validate_sweeps;
  j["profile_sweeps"] = cfg.profile_sweeps;
  j["figure1_mesh"] = cfg.figure1_mesh;
  j["figure1_orderings"] = cfg.figure1_orderings;
  j["profile_mesh"] = cfg.profile_mesh;
  j["timing"] = cfg.timing;
  j["kernels"] = cfg.kernels;
  j["kernel_orderings"] = cfg.kernel_orderings;
  j["kernel_sweeps"] = cfg.kernel_sweeps;
  return j;
}

// Every output of report_list.h that this run has, written; the manifest of what was, with the
// README's sections.
Json WriteOutputs(const ReportData& d, const std::string& out, std::string* sections) {
  Json manifest;
  manifest["tables"] = Json::array();
  manifest["data"] = Json::array();
  manifest["figures"] = Json::array();
  std::set<std::string> written;
  for (const ReportOutput& o : ReportOutputs()) {
    const ReportPart p = o.build(d);
    if (p.skip) continue;
    if (!o.is_table) {
      if (p.text.empty())
        WriteCsvFile(out + "/data/" + o.name, p.table);
      else
        WriteTextFile(out + "/data/" + o.name, p.text);
      written.insert(std::string("data/") + o.name);
      manifest["data"].push_back({{"file", std::string("data/") + o.name}});
      continue;
    }
    WriteTableFiles(out + "/tables", o.name, p.table, {"csv", "md", "tex"}, o.caption);
    for (const char* e : {".csv", ".md", ".tex"})
      written.insert("tables/" + std::string(o.name) + e);
    manifest["tables"].push_back(
        {{"name", o.name}, {"paper", o.paper}, {"title", o.title}, {"caption", o.caption}});
    if (!*o.title) continue;
    const std::string n = o.name;
    *sections += "## " + std::string(o.title) + "\n\n" + p.note + (p.note.empty() ? "" : "\n\n") +
                 p.table.Markdown() + "\nFiles: [csv](tables/" + n + ".csv), [md](tables/" + n +
                 ".md), [tex](tables/" + n + ".tex)\n\n";
  }
  for (const ReportFigure& f : ReportFigures()) {
    const std::vector<std::string> inputs = Words(f.inputs);
    bool ok = *f.when == '\0' || d.cfg.label == f.when;
    for (const std::string& i : inputs) ok = ok && written.count(i);
    if (!ok) continue;
    const std::string script = f.script;
    const size_t colon = script.find(':');
    manifest["figures"].push_back(
        {{"name", f.name},
         {"paper", f.paper},
         {"title", FigureTitle(f, d.cfg)},
         {"script", script.substr(0, colon)},
         {"variant", colon == std::string::npos ? "" : script.substr(colon + 1)},
         {"inputs", inputs},
         {"files",
          {std::string("figures/") + f.name + ".png", std::string("figures/") + f.name + ".pdf"}}});
  }
  return manifest;
}

// "timings taken on a busy machine: ..." naming what it affects, or "" for a quiet one.
std::string BusyNote(const ReportData& d) {
  const std::vector<std::string> why = d.noise.Reasons();
  if (!d.cfg.timing || why.empty()) return "";
  std::string s = "Timings taken on a busy machine: ";
  for (size_t i = 0; i < why.size(); ++i) s += (i ? "; " : "") + why[i];
  return s +
         ". Affected: the tables time, speedup, scaling, scaling_mean and reorder_cost and the "
         "figures time, speedup, speedup-mean and gain (their intervals say how much; the CPU "
         "times rank orderings by the work they cost" +
         (d.cfg.clock == TimeClock::kWall ? ", and `--clock cpu` computes the speedups on them"
                                          : "") +
         "). Run again on an idle machine to compare wall times.";
}

std::string Readme(const ReportData& d, const Json& manifest, const std::string& sections) {
  const ReportConfig& cfg = d.cfg;
  std::string r = "# meshreuse report" + (cfg.label.empty() ? "" : " (" + cfg.label + ")") + "\n\n";
  if (const std::string busy = BusyNote(d); !busy.empty()) r += "> **" + busy + "**\n\n";
  for (const std::string& n : d.notes) r += "> " + n + "\n\n";
  bool any_paper_size = false;
  for (const ReportMesh& m : d.meshes)
    any_paper_size = any_paper_size || paper::Sized(m.name, m.vertices);
  if (!any_paper_size)
    r += "> None of these meshes is within 5% of the paper's size for its name, so the paper's "
         "columns stay empty: `scripts/reproduce.sh` (without `--quick`) meshes the nine shapes at "
         "the paper's vertex counts and fills them.\n\n";
  r += "Made by `meshreuse report` (" + GitRevision() + ", " + UtcTimestamp() + ") on " +
       std::to_string(d.meshes.size()) + " mesh(es), orderings ";
  for (size_t i = 0; i < d.orderings.size(); ++i) r += (i ? ", " : "") + d.orderings[i];
  if (cfg.timing) {
    r += "; threads";
    for (int p : cfg.threads) r += " " + std::to_string(p);
  }
  if (cfg.timing)
    r += "; " +
         (cfg.repeat_auto ? "rounds until every speedup was within +-2% (at most " +
                                std::to_string(cfg.repeat_cap) + "; the `rounds` columns)"
                          : std::to_string(cfg.repeat) + " rounds") +
         " after a warm-up, speedups on the " + ClockName(cfg.clock) + " clock";
  else
    r += "; **nothing was timed** (`--no-timing`: the time, speedup and gain tables and figures "
         "are absent; everything else is counted or simulated, not timed)";
  r += ", seed " + std::to_string(cfg.seed) +
       ". Configuration, machine and build: [run.json](run.json). Caches: " +
       LevelsText(cfg.cache.levels) + "; misses are **" + d.counters +
       "**. Every table is also in `tables/` as CSV, Markdown and LaTeX (booktabs); an empty "
       "cell is a value the paper does not give (or not for a mesh of its size).\n\n";
  r += sections;
  r += "## Figures\n\nMade by `scripts/plot_report.py` from `data/` and `tables/` (PNG and PDF in "
       "`figures/`; what was drawn from what: [manifest.json](manifest.json)).\n\n";
  for (const Json& f : manifest["figures"]) {
    const std::string n = f["name"];
    r += "- **" + n + "** (the paper's " + f["paper"].get<std::string>() +
         "): " + f["title"].get<std::string>() + " ([pdf](figures/" + n + ".pdf))\n\n  ![" + n +
         "](figures/" + n + ".png)\n";
  }
  return r;
}

}  // namespace meshreuse::report
