// machine_misses: the many-core simulator's misses per level of the warm sweep, summed over the
// threads, as means over the meshes (thousands) per ordering x placement x thread count; the share
// of memory accesses that go to another socket's memory; the last level's coherence misses; and
// each ordering's memory accesses against ORI's and BFS's (the sums over the meshes divided, same
// placement and threads: a mean of per-mesh ratios would be ruled by the meshes that barely reach
// memory). The data of the paper's Figure 11 ("number of accesses as a function of the number of
// cores used").
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportMachineMisses(const ReportData& d) {
  using namespace report;
  if (d.machine.empty()) return {Table({}), "", "", true};
  const std::vector<std::string>& levels = d.machine.front().level_names;
  std::vector<std::string> head = {"ordering", "placement", "threads"};
  for (const std::string& l : levels) head.push_back(l + "_misses_k");
  Append(&head, {"remote_pct", levels.back() + "_coherence_k", "memory_vs_ori", "memory_vs_bfs"});
  Table t(head);
  auto memory = [](const MachineRun* r) {
    return static_cast<double>(r->total.memory_local + r->total.memory_remote);
  };
  for (const std::string& ord : d.orderings)
    for (const char* placement : {"compact", "scatter"})
      for (int p : d.cfg.machine_threads) {
        std::vector<std::vector<double>> miss(levels.size());
        std::vector<double> mem, remote, coherence;
        double sum = 0, sum_ori = 0, sum_bfs = 0;  // memory accesses over the meshes
        for (const ReportMesh& m : d.meshes) {
          const MachineRun* r = d.Machine(m.name, ord, placement, p);
          if (!r) continue;
          for (size_t i = 0; i < levels.size() && i < r->total.levels.size(); ++i)
            miss[i].push_back(static_cast<double>(r->total.levels[i].misses) / 1e3);
          mem.push_back(memory(r) / 1e3);
          remote.push_back(100 * Ratio(static_cast<double>(r->total.memory_remote), memory(r)));
          coherence.push_back(static_cast<double>(r->total.levels.back().coherence) / 1e3);
          const MachineRun* o = d.Machine(m.name, "ori", placement, p);
          const MachineRun* b = d.Machine(m.name, "bfs", placement, p);
          sum += memory(r), sum_ori += o ? memory(o) : NAN, sum_bfs += b ? memory(b) : NAN;
        }
        if (mem.empty()) continue;
        std::vector<std::string> row = {ord, placement, Int(p)};
        for (const auto& v : miss) row.push_back(Num(Mean(v), 1));
        Append(&row, {Pct(Mean(remote)), Num(Mean(coherence), 1),
                      ord == "ori" ? "" : Num(Ratio(sum, sum_ori), 2),
                      ord == "bfs" ? "" : Num(Ratio(sum, sum_bfs), 2)});
        t.AddRow(row);
      }
  ReportPart part;
  part.table = t;
  part.note =
      "The many-core simulator on the machine `" + d.cfg.machine +
      "`: the warm sweep (the last of " + std::to_string(d.cfg.machine_sweeps) +
      " traced sweeps) summed over the threads, means over the meshes (thousands). Compact "
      "placement fills socket 0 first (as the paper ran, KMP_AFFINITY=compact); scatter deals the "
      "threads over the sockets; one thread is the same run for both. Memory accesses are the "
      "last level's misses; remote: served by another socket's memory (first-touch: the mesh "
      "lives on socket 0). Coherence: misses on lines another core's write invalidated. "
      "memory_vs_ori, memory_vs_bfs: the ordering's memory accesses over the reference's, summed "
      "over the meshes (below 1: fewer). Per mesh, "
      "per level: [data/machine.csv](data/machine.csv).";
  return part;
}

}  // namespace meshreuse
