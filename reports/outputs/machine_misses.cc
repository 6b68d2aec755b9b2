// machine_misses: the many-core simulator's misses per level of the warm sweep, summed over the
// threads, as means over the meshes (thousands) per ordering x placement x thread count; the share
// of memory accesses that go to another socket's memory; the last level's coherence misses; and
// each level's misses against ORI's and BFS's (sums over the meshes, same placement and threads).
// The data of the paper's Figure 11 ("number of accesses as a function of the number of
// cores used").
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportMachineMisses(const ReportData& d) {
  using namespace report;
  if (d.machine.empty()) return {Table({}), "", "", true};
  const std::vector<std::string>& levels = d.machine.front().level_names;
  const size_t nl = levels.size();
  std::vector<std::string> head = {"ordering", "placement", "threads"};
  for (const std::string& l : levels) head.push_back(l + "_misses_k");
  Append(&head, {"remote_pct", levels.back() + "_coherence_k"});
  for (const char* ref : {"ori", "bfs"})
    for (const std::string& l : levels) head.push_back("fewer_" + l + "_vs_" + ref + "_pct");
  Table t(head);
  auto memory = [](const MachineRun* r) {
    return static_cast<double>(r->total.memory_local + r->total.memory_remote);
  };
  for (const std::string& ord : d.orderings)
    for (const char* placement : {"compact", "scatter"})
      for (int p : d.cfg.machine_threads) {
        std::vector<std::vector<double>> miss(nl);
        std::vector<double> remote, coherence;
        // Per reference and level: the misses summed over the meshes, ours and the reference's.
        std::vector<double> sum(nl, 0),
            sum_ref[2] = {std::vector<double>(nl, 0), std::vector<double>(nl, 0)};
        for (const ReportMesh& m : d.meshes) {
          const MachineRun* r = d.Machine(m.name, ord, placement, p);
          if (!r) continue;
          const MachineRun* refs[2] = {d.Machine(m.name, "ori", placement, p),
                                       d.Machine(m.name, "bfs", placement, p)};
          for (size_t i = 0; i < nl && i < r->total.levels.size(); ++i) {
            const double x = static_cast<double>(r->total.levels[i].misses);
            miss[i].push_back(x / 1e3);
            sum[i] += x;
            for (int k = 0; k < 2; ++k)
              sum_ref[k][i] += refs[k] ? static_cast<double>(refs[k]->total.levels[i].misses) : NAN;
          }
          remote.push_back(100 * Ratio(static_cast<double>(r->total.memory_remote), memory(r)));
          coherence.push_back(static_cast<double>(r->total.levels.back().coherence) / 1e3);
        }
        if (remote.empty()) continue;
        std::vector<std::string> row = {ord, placement, Int(p)};
        for (const auto& v : miss) row.push_back(Num(Mean(v), 1));
        Append(&row, {Pct(Mean(remote)), Num(Mean(coherence), 1)});
        for (int k = 0; k < 2; ++k)
          for (size_t i = 0; i < nl; ++i)
            row.push_back(ord == (k == 0 ? "ori" : "bfs")
                              ? ""
                              : Pct(100 * (1 - Ratio(sum[i], sum_ref[k][i]))));
        t.AddRow(row);
      }
  ReportPart part;
  part.table = t;
  part.note =
      "The many-core simulator on the machine `" + d.cfg.machine +
      "`: the warm sweep (the last of " + std::to_string(d.cfg.machine_sweeps) +
      " traced sweeps) summed over the threads, means over the meshes (thousands). Compact "
      "placement fills socket 0 first (as the paper ran, KMP_AFFINITY=compact); scatter deals the "
      "threads over the sockets; one thread is the same run for both. The last level's misses are "
      "the memory accesses; remote: served by another socket's memory (first-touch: the mesh "
      "lives on socket 0). Coherence: misses on lines another core's write invalidated. fewer_X_vs_"
      "REF_pct: 1 - misses / the reference's misses at the same placement and threads, summed over "
      "the meshes (a mean of per-mesh ratios would be ruled by the meshes that barely miss). The "
      "paper, for RDR on one core: 25/71/84% fewer L1/L2/L3 misses than ORI, 6.3/51/65% than BFS, "
      "\"similar\" up to 32 cores. Per mesh, per level: [data/machine.csv](data/machine.csv).";
  return part;
}

}  // namespace meshreuse
