// kernels and kernels_mean: the paper's closing conjecture tested (issue 41). `kernels`: per mesh,
// kernel and ordering, the time per sweep with its spread, the speedup against ORI and the gain
// against BFS of the same kernel (intervals, verdicts), the last traced sweep's simulated misses
// per level beside the floor no layout can beat (analysis/sweep_footprint.h), and the line-level
// reuse-distance quantiles. `kernels_mean`: the means over the meshes, and in the README one
// paragraph per kernel saying which ordering is fastest, what RDR does against ORI and BFS, and
// where in reuse distances and misses.
#include <cmath>

#include "core/kernels/kernel.h"
#include "reports/report_outputs.h"

namespace meshreuse {

namespace {

std::vector<std::string> Unique(const ReportData& d, std::string KernelRun::*field) {
  std::vector<std::string> v;
  for (const KernelRun& r : d.kernels)
    if (std::find(v.begin(), v.end(), r.*field) == v.end()) v.push_back(r.*field);
  return v;
}

const KernelRun* Find(const ReportData& d, const std::string& mesh, const std::string& kernel,
                      const std::string& ordering) {
  for (const KernelRun& r : d.kernels)
    if (r.mesh == mesh && r.kernel == kernel && r.ordering == ordering) return &r;
  return nullptr;
}

// The mean over meshes of T_ref / T (or the gain) of `kernel` in `ordering`.
Spread MeanAgainst(const ReportData& d, const std::string& kernel, const std::string& ordering,
                   const std::string& ref, bool gain) {
  std::vector<std::pair<const CompareRow*, const CompareRow*>> pairs;
  for (const ReportMesh& m : d.meshes) {
    const KernelRun* r = Find(d, m.name, kernel, ordering);
    const KernelRun* x = Find(d, m.name, kernel, ref);
    if (r && x && !r->time.rounds.empty()) pairs.emplace_back(&x->time, &r->time);
  }
  return MeanRatio(pairs, d.cfg.seed, gain, d.cfg.clock);
}

// The mean over meshes of a per-run value.
double MeanOf(const ReportData& d, const std::string& kernel, const std::string& ordering,
              const std::function<double(const KernelRun&)>& f) {
  std::vector<double> v;
  for (const KernelRun& r : d.kernels)
    if (r.kernel == kernel && r.ordering == ordering) v.push_back(f(r));
  return report::Mean(v);
}

// One kernel's paragraph: the fastest ordering, RDR against ORI and BFS, and why in reuse
// distances and misses (level `lv`: the one whose misses differ the most, the L2 by default).
std::string Paragraph(const ReportData& d, const std::string& kernel,
                      const std::vector<std::string>& ords) {
  using report::Num;
  const KernelInfo* k = FindKernel(kernel);
  std::string s =
      "- **" + kernel + "**" + (k ? std::string(" (") + k->description + ")" : "") + ": ";
  if (d.cfg.timing) {
    std::string best;
    Spread best_s;
    for (const std::string& o : ords) {
      const Spread x = o == "ori" ? Spread{} : MeanAgainst(d, kernel, o, "ori", false);
      const double v = o == "ori" ? 1.0 : x.median;
      if (std::isfinite(v) && (best.empty() || v > best_s.median)) {
        best = o;
        best_s = o == "ori" ? Spread{} : x;
        best_s.median = v;
      }
    }
    s += "the fastest is " + best + " (" + Num(best_s.median, 2) + "x ORI per sweep, mean over " +
         std::to_string(d.meshes.size()) + " mesh(es))";
    const Spread rdr_ori = MeanAgainst(d, kernel, "rdr", "ori", false);
    const Spread rdr_bfs = MeanAgainst(d, kernel, "rdr", "bfs", true);
    if (std::isfinite(rdr_ori.median)) {
      s += "; RDR is " + Num(rdr_ori.median, 2) + "x ORI [" + Num(rdr_ori.lo, 2) + ", " +
           Num(rdr_ori.hi, 2) + "] (" + report::VerdictCell(rdr_ori) + ")";
      if (std::isfinite(rdr_bfs.median))
        s += " and " + Num(100 * std::fabs(rdr_bfs.median), 1) + "% " +
             (rdr_bfs.median >= 0 ? "faster" : "slower") + " than BFS (" +
             report::VerdictCell(rdr_bfs, true) + ")";
      const std::string vs_ori = report::VerdictCell(rdr_ori);
      const bool beats_bfs = report::VerdictCell(rdr_bfs, true) == "faster";
      s += vs_ori == "faster" && beats_bfs ? ": the conjecture holds for this kernel here"
           : vs_ori == "faster"            ? ": RDR helps against ORI, but not beyond BFS"
           : vs_ori == "slower"            ? ": the conjecture does not hold for this kernel here"
                                : ": RDR is not told apart from ORI, so the conjecture is not "
                                  "shown for this kernel here";
    }
    s += ". ";
  }
  if (!d.cfg.cache.levels.empty()) {
    const size_t lv = d.cfg.cache.levels.size() > 1 ? 1 : 0;
    const std::string name = d.cfg.cache.levels[lv].name;
    auto misses = [&](const std::string& o) {
      return MeanOf(d, kernel, o, [&](const KernelRun& r) {
        return lv < r.misses.size() ? static_cast<double>(r.misses[lv]) : NAN;
      });
    };
    auto floor = [&](const std::string& o) {
      return MeanOf(d, kernel, o, [&](const KernelRun& r) {
        return lv < r.floor.size() ? static_cast<double>(r.floor[lv]) : NAN;
      });
    };
    auto q90 = [&](const std::string& o) {
      return MeanOf(d, kernel, o, [](const KernelRun& r) { return static_cast<double>(r.q90); });
    };
    s += "Reuse distances (lines, every traced access; means over the meshes): q90 ORI " +
         Num(q90("ori"), 0) + ", BFS " + Num(q90("bfs"), 0) + ", RDR " + Num(q90("rdr"), 0) +
         "; simulated " + name + " misses of the warm sweep per 1000 accesses ORI " +
         Num(1e3 * misses("ori") /
                 MeanOf(d, kernel, "ori",
                        [](const KernelRun& r) { return static_cast<double>(r.accesses); }),
             2) +
         ", RDR/BFS " + Num(misses("rdr") / misses("bfs"), 2) + "x, BFS over the floor " +
         Num(misses("bfs") / floor("bfs"), 2) + "x.";
  }
  return s;
}

}  // namespace

ReportPart ReportKernels(const ReportData& d) {
  using namespace report;
  if (d.kernels.empty()) return {Table({}), "", "", true};
  ReportPart p;
  std::vector<std::string> head = {"mesh", "kernel", "ordering", "sweeps"};
  Append(&head, SpreadColumns("ms_per_sweep"));
  Append(&head, SpreadColumns("speedup_vs_ori"));
  head.push_back("vs_ori");
  Append(&head, SpreadColumns("gain_vs_bfs_pct"));
  Append(&head, {"vs_bfs", "measure", "accesses"});
  for (const CacheLevel& l : d.cfg.cache.levels)
    Append(&head, {l.name + "_misses", l.name + "_floor"});
  Append(&head, {"q50_lines", "q90_lines"});
  p.table = Table(head);
  const bool cpu = d.cfg.clock == TimeClock::kCpu;
  for (const KernelRun& r : d.kernels) {
    std::vector<std::string> row = {r.mesh, r.kernel, r.ordering,
                                    r.time.rounds.empty() ? "" : Int(r.time.rounds[0].sweeps)};
    Append(&row, SpreadCells(cpu ? r.time.sweep_cpu : r.time.sweep, 1e3));
    Append(&row, SpreadCells(r.time.speedup_vs_ori1));
    row.push_back(VerdictCell(r.time.speedup_vs_ori1));
    Append(&row, SpreadCells(r.time.gain_vs_bfs, 100));
    Append(&row, {VerdictCell(r.time.gain_vs_bfs, true),
                  std::isfinite(r.time.final_quality) ? ExactNumber(r.time.final_quality) : "",
                  Int(r.accesses)});
    for (size_t i = 0; i < d.cfg.cache.levels.size(); ++i)
      Append(&row, {i < r.misses.size() ? Int(r.misses[i]) : "",
                    i < r.floor.size() ? Int(r.floor[i]) : ""});
    Append(&row, {Int(r.q50), Int(r.q90)});
    p.table.AddRow(row);
  }
  return p;
}

ReportPart ReportKernelsMean(const ReportData& d) {
  using namespace report;
  if (d.kernels.empty()) return {Table({}), "", "", true};
  ReportPart p;
  const std::vector<std::string> kernels = Unique(d, &KernelRun::kernel);
  const std::vector<std::string> ords = Unique(d, &KernelRun::ordering);
  std::vector<std::string> head = {"kernel", "ordering", "meshes"};
  Append(&head, SpreadColumns("speedup_vs_ori"));
  head.push_back("vs_ori");
  Append(&head, SpreadColumns("gain_vs_bfs_pct"));
  head.push_back("vs_bfs");
  for (const CacheLevel& l : d.cfg.cache.levels)
    Append(&head, {l.name + "_misses_per_1000", l.name + "_over_floor"});
  head.push_back("q90_lines");
  p.table = Table(head);
  for (const std::string& k : kernels)
    for (const std::string& o : ords) {
      const Spread s = o == "ori" ? Spread{} : MeanAgainst(d, k, o, "ori", false);
      const Spread g = o == "bfs" ? Spread{} : MeanAgainst(d, k, o, "bfs", true);
      std::vector<std::string> row = {k, o, Int(d.meshes.size())};
      Append(&row, SpreadCells(s));
      row.push_back(VerdictCell(s));
      Append(&row, SpreadCells(g, 100));
      row.push_back(VerdictCell(g, true));
      for (size_t i = 0; i < d.cfg.cache.levels.size(); ++i) {
        const double m = MeanOf(d, k, o, [&](const KernelRun& r) {
          return i < r.misses.size() && r.accesses
                     ? 1e3 * static_cast<double>(r.misses[i]) / static_cast<double>(r.accesses)
                     : NAN;
        });
        const double over = MeanOf(d, k, o, [&](const KernelRun& r) {
          return i < r.floor.size() && r.floor[i]
                     ? static_cast<double>(r.misses[i]) / static_cast<double>(r.floor[i])
                     : NAN;
        });
        Append(&row, {Num(m, 3), Num(over, 3)});
      }
      row.push_back(
          Num(MeanOf(d, k, o, [](const KernelRun& r) { return static_cast<double>(r.q90); }), 1));
      p.table.AddRow(row);
    }
  const std::string timed =
      d.cfg.timing ? std::to_string(d.cfg.kernel_sweeps) + " sweeps per run, " +
                         std::to_string(d.cfg.repeat) +
                         " interleaved rounds after a warm-up, one thread, speedups on per-sweep "
                         "medians (" +
                         ClockName(d.cfg.clock) +
                         " clock) against ORI and BFS of the same kernel, means over the meshes "
                         "with 95% intervals; "
                   : "nothing timed (--no-timing); ";
  std::string n =
      "The paper ends with a conjecture it does not test: that its ordering \"could improve other "
      "mesh application performances such as mesh untangling, constraint mesh smoothing, and mesh "
      "swapping\". Each kernel of `meshreuse kernels` here, in each ordering, on every mesh: " +
      timed + "misses of the last of " + std::to_string(d.cfg.validate_sweeps) +
      " traced sweeps simulated on the configured caches, over the floor no layout can beat. Per "
      "mesh: [tables/kernels.md](tables/kernels.md).\n\n";
  for (const std::string& k : kernels) n += Paragraph(d, k, ords) + "\n";
  p.note = n;
  return p;
}

}  // namespace meshreuse
