// The report runner on small synthetic meshes: Table 2 against the textbook stack distance of the
// same element stream, Figure 1's bins adding up to the stream, the paper's values only beside a
// mesh of the paper's size, and the same configuration giving the same non-timing files byte for
// byte.
#include "reports/report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "analysis/reference.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/orderings/registry.h"
#include "reports/kernel_runs.h"
#include "reports/run_info.h"
#include "reports/simulate.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::map<std::string, std::string>> Csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> head;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& l) {
    std::vector<std::string> c;
    std::stringstream ss(l);
    for (std::string x; std::getline(ss, x, ',');) c.push_back(x);
    if (!l.empty() && l.back() == ',') c.push_back("");
    return c;
  };
  if (std::getline(in, line)) head = split(line);
  while (std::getline(in, line)) {
    const auto c = split(line);
    EXPECT_EQ(c.size(), head.size()) << path << ": " << line;
    std::map<std::string, std::string> r;
    for (size_t i = 0; i < head.size() && i < c.size(); ++i) r[head[i]] = c[i];
    rows.push_back(r);
  }
  return rows;
}

// Two meshes written as Triangle files named like the paper's (ocean for Figure 1, carabiner
// for the profile).
struct Fixture {
  testing::TempDir dir;
  std::vector<std::string> meshes;
  Fixture() {
    int k = 0;
    for (const char* name : {"ocean", "carabiner"}) {
      SyntheticOptions o;
      o.nx = 14 + 5 * k, o.ny = 11, o.holes = k, o.graded = true, o.seed = 3 + k++;
      WriteTriangleFiles(BuildMesh(MakeSyntheticMesh(o)), dir / name);
      meshes.push_back(dir / (std::string(name) + ".node"));
    }
  }
  ReportConfig Config() const {
    ReportConfig c;
    c.meshes = meshes;
    c.orderings = {"ori", "bfs", "rdr"};
    c.timing = false;
    c.profile_sweeps = 3;
    c.figure1_time_bins = 16;
    c.counter_events = {};
    return c;
  }
};

struct ElementSink {
  static constexpr bool kEnabled = true;
  std::vector<int32_t>* ids;
  void Bind(const ArrayLayout&) {}
  void BeginSweep(int) {}
  void Access(int, const MemRef& r) {
    if (r.element != AccessKind::kNone) ids->push_back(r.vertex);
  }
};

// The element stream of the first sweep of `mesh` laid out in `ord`, as vertex ids.
std::vector<int32_t> FirstSweepElements(const std::string& path, const std::string& ord) {
  const Mesh base = ReadMesh(path);
  Mesh m = ApplyPermutation(base, ComputeOrdering(ord, base, 1), TriangleOrder::kSorted);
  std::vector<int32_t> ids;
  ElementSink s{&ids};
  SmoothOptions o;
  o.max_iters = 1;
  o.tol = -std::numeric_limits<double>::infinity();
  Smooth(m, o, s);
  return ids;
}

TEST(Report, Table2MatchesTheTextbookStackDistance) {
  Fixture f;
  testing::TempDir out;
  RunReport(f.Config(), out / "r", {});
  const auto t2 = Csv(out / "r/tables/table2.csv");
  ASSERT_EQ(t2.size(), 6u);
  for (const auto& row : t2) {
    const std::string path = f.dir / (row.at("mesh") + ".node");
    const std::vector<int32_t> ids = FirstSweepElements(path, row.at("ordering"));
    std::vector<uint64_t> finite;
    uint64_t cold = 0;
    for (uint64_t d : TextbookStackDistances(ids))
      d == StackDistance::kCold ? ++cold : (finite.push_back(d), 0);
    std::sort(finite.begin(), finite.end());
    auto q = [&](double x) {  // the smallest d with at least x of the finite distances <= d
      const size_t k = static_cast<size_t>(std::ceil(x * finite.size()));
      return finite[k == 0 ? 0 : k - 1];
    };
    EXPECT_EQ(row.at("accesses"), std::to_string(ids.size()));
    EXPECT_EQ(row.at("cold"), std::to_string(cold));
    EXPECT_EQ(row.at("q50"), std::to_string(q(0.5))) << row.at("mesh") << row.at("ordering");
    EXPECT_EQ(row.at("q75"), std::to_string(q(0.75)));
    EXPECT_EQ(row.at("q90"), std::to_string(q(0.9)));
    EXPECT_EQ(row.at("q100"), std::to_string(finite.back()));
    // Not the paper's size: no paper value beside ours (missing = empty in CSV).
    EXPECT_EQ(row.at("paper_q50"), "");
  }
  // Figure 1: one panel per configured ordering, in its order, bins adding up to the accesses.
  const auto f1 = Csv(out / "r/data/figure1.csv");
  std::map<std::string, uint64_t> sums;
  std::vector<std::string> order;
  for (const auto& r : f1) {
    if (order.empty() || order.back() != r.at("ordering")) order.push_back(r.at("ordering"));
    sums[r.at("ordering")] += std::stoull(r.at("count"));
  }
  EXPECT_EQ(order, (std::vector<std::string>{"random", "ori", "bfs"}));
  for (const auto& [ord, n] : sums)
    EXPECT_EQ(n, FirstSweepElements(f.meshes[0], ord).size()) << ord;
  // The profile: 3 sweeps of carabiner per ordering, the accesses of each sweep complete.
  const auto prof = Csv(out / "r/data/profile.csv");
  uint64_t n = 0;
  for (const auto& r : prof)
    if (r.at("ordering") == "rdr" && r.at("iteration") == "2") n += std::stoull(r.at("accesses"));
  EXPECT_EQ(n, FirstSweepElements(f.meshes[1], "rdr").size());
  // Every table in three formats; the README links them.
  const std::string readme = Slurp(out / "r/README.md");
  for (const char* t : {"table1", "table2", "table3", "miss_reduction"})
    for (const char* ext : {".csv", ".md", ".tex"}) {
      EXPECT_TRUE(std::filesystem::exists(out / ("r/tables/" + std::string(t) + ext))) << t << ext;
      EXPECT_NE(readme.find("tables/" + std::string(t) + ext), std::string::npos) << t << ext;
    }
  EXPECT_NE(Slurp(out / "r/tables/table2.tex").find("\\toprule"), std::string::npos);
  // The manifest names exactly what was written: every table of the registry that this run has
  // (no timing: the four untimed ones and misses), every data file, every figure with its inputs.
  const Json manifest = Json::parse(Slurp(out / "r/manifest.json"));
  std::vector<std::string> tables, figures;
  for (const Json& t : manifest["tables"]) tables.push_back(t["name"]);
  EXPECT_EQ(tables, (std::vector<std::string>{
                        "table1", "table2", "table3", "misses", "miss_reduction", "machine_misses",
                        "predicted_speedup", "prefetch", "kernels", "kernels_mean"}));
  for (const Json& d : manifest["data"])
    EXPECT_TRUE(std::filesystem::exists(out / ("r/" + d["file"].get<std::string>()))) << d;
  for (const Json& fig : manifest["figures"]) {
    figures.push_back(fig["name"]);
    for (const Json& in : fig["inputs"])
      EXPECT_TRUE(std::filesystem::exists(out / ("r/" + in.get<std::string>()))) << fig;
  }
  EXPECT_EQ(figures, (std::vector<std::string>{"figure1", "profile", "histograms", "miss-rates",
                                               "meshes", "smoothing", "orderings", "figure11",
                                               "machine-misses", "predicted-speedup", "kernels"}));
}

// The kernels part (the paper's conjecture): a row per mesh x kernel x ordering; the simulated
// sweep's accesses are the kernels' closed forms where they have one; misses never below the
// floor; the README answers kernel by kernel.
TEST(Report, KernelsPartCountsEveryAccessAndStaysAboveTheFloor) {
  Fixture f;
  ReportConfig c = f.Config();
  c.machine = "";
  c.kernels = {"laplacian", "assembly", "spmv", "untangle"};
  c.kernel_orderings = {"ori", "bfs", "rdr"};
  std::filesystem::path out = f.dir.path();
  RunReport(c, out / "k", Log{});
  const auto rows = Csv(out / "k/tables/kernels.csv");
  ASSERT_EQ(rows.size(), 2u * 4 * 3);
  for (const auto& r : rows) {
    const Mesh base = ReadMesh(r.at("mesh") == "ocean" ? f.meshes[0] : f.meshes[1]);
    const KernelInfo& k = ParseKernel(r.at("kernel"));
    const std::vector<uint64_t> refs = k.refs(base, ExactSweeps(1));
    if (!refs.empty() && r.at("kernel") != "laplacian") {  // the same in every ordering
      EXPECT_EQ(std::stoull(r.at("accesses")), refs[0])
          << r.at("kernel") << " " << r.at("ordering");
    }
    for (const char* lv : {"L1", "L2", "L3"})
      EXPECT_GE(std::stoull(r.at(std::string(lv) + "_misses")),
                std::stoull(r.at(std::string(lv) + "_floor")))
          << r.at("kernel") << " " << lv;
    EXPECT_EQ(r.at("ms_per_sweep"), "");  // not timed
  }
  // The Laplacian's rows come from Table 3's streams (the same traced sweeps): each equals the
  // kernels part's own simulation of that mesh in that ordering.
  for (size_t mi = 0; mi < 2; ++mi) {
    const Mesh base = ReadMesh(f.meshes[mi]);
    KernelRunsConfig kc;
    kc.kernels = {"laplacian"};
    kc.orderings = kc.labels = c.kernel_orderings;
    kc.timing = false;
    kc.traced_sweeps = c.validate_sweeps;
    kc.cache = c.cache;
    kc.line_bytes = c.line_bytes;
    std::vector<KernelRun> own;
    const std::string name = mi == 0 ? "ocean" : "carabiner";
    MeasureKernels(kc, name, base, &own, [](const std::string&) {});
    ASSERT_EQ(own.size(), 3u);
    for (const KernelRun& k : own) {
      int found = 0;
      for (const auto& r : rows) {
        if (r.at("mesh") != name || r.at("kernel") != "laplacian" || r.at("ordering") != k.ordering)
          continue;
        ++found;
        EXPECT_EQ(std::stoull(r.at("accesses")), k.accesses) << name << " " << k.ordering;
        const char* lv[] = {"L1", "L2", "L3"};
        for (size_t l = 0; l < 3; ++l) {
          EXPECT_EQ(std::stoull(r.at(std::string(lv[l]) + "_misses")), k.misses.at(l))
              << name << " " << k.ordering << " " << lv[l];
          EXPECT_EQ(std::stoull(r.at(std::string(lv[l]) + "_floor")), k.floor.at(l))
              << name << " " << k.ordering << " " << lv[l];
        }
        EXPECT_EQ(std::stoull(r.at("q50_lines")), k.q50) << name << " " << k.ordering;
        EXPECT_EQ(std::stoull(r.at("q90_lines")), k.q90) << name << " " << k.ordering;
      }
      EXPECT_EQ(found, 1) << name << " " << k.ordering;
    }
  }
  const std::string readme = Slurp(out / "k/README.md");
  for (const char* k : {"**laplacian**", "**assembly**", "**spmv**", "**untangle**"})
    EXPECT_NE(readme.find(k), std::string::npos) << k;
}

TEST(Report, SameConfigurationSameNonTimingFilesByteForByte) {
  Fixture f;
  testing::TempDir out;
  RunReport(f.Config(), out / "a", {});
  RunReport(f.Config(), out / "b", {});
  for (const char* file :
       {"tables/table1.csv", "tables/table2.csv", "tables/table2.tex", "tables/table3.csv",
        "tables/misses.csv", "tables/miss_reduction.md", "data/histogram.csv", "data/figure1.csv",
        "data/profile.csv", "data/misses.csv", "data/capacities.csv"})
    EXPECT_EQ(Slurp(out / ("a/" + std::string(file))), Slurp(out / ("b/" + std::string(file))))
        << file;
}

// Where the time went: the prior phases first, the report's own after, the figures' callback
// timed before README.md and run.json are written; the same phases in both.
TEST(Report, WhereTheTimeWentInTheReadmeAndRunJson) {
  Fixture f;
  testing::TempDir out;
  const std::string prior = out / "phases.txt";
  std::ofstream(prior) << "setup 0.5 0.25\nbuild 100 190\nmeshing 2 2\n";
  ReportConfig c = f.Config();
  c.prior_phases = prior;
  bool drawn = false;
  RunReport(c, out / "r", {}, [&] {
    drawn = true;
    EXPECT_TRUE(std::filesystem::exists(out / "r/manifest.json"));  // what the figures read
    EXPECT_FALSE(std::filesystem::exists(out / "r/README.md"));
  });
  EXPECT_TRUE(drawn);
  const Json run = Json::parse(Slurp(out / "r/run.json"));
  std::vector<std::string> names;
  for (const Json& p : run.at("phases")) names.push_back(p.at("phase"));
  ASSERT_GE(names.size(), 6u);
  EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 3),
            (std::vector<std::string>{"setup", "build", "meshing"}));
  for (const char* want :
       {"reading the meshes", "simulations (reuse distances, misses, many-core)",
        "reuse distances (Table 2, Figure 1, profiles)",
        "misses (Table 3: the simulator, the model)", "many-core simulation, 32 thread(s)",
        "other kernels (simulated and timed)", "other kernels: simulated", "tables and figure data",
        "figures (scripts/plot_report.py)"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  // The kernels part's simulated share, inside it (this config times nothing: no timed share);
  // the simulations' jobs, inside theirs, each kind's CPU its jobs' threads'.
  for (const Json& p : run.at("phases")) {
    const std::string name = p.at("phase");
    if (name == "other kernels: simulated" || name.rfind("reuse distances", 0) == 0 ||
        name.rfind("misses (Table 3", 0) == 0 || name.rfind("many-core simulation, ", 0) == 0) {
      EXPECT_EQ(p.at("note"), "inside the one above") << name;
      EXPECT_GT(p.at("cpu_s").get<double>(), 0) << name;
    }
  }
  EXPECT_EQ(std::find(names.begin(), names.end(), "other kernels: timed"), names.end());
  const std::string readme = Slurp(out / "r/README.md");
  EXPECT_NE(readme.find("## Where the time went"), std::string::npos);
  EXPECT_NE(readme.find("| build | 100.0 s | 190.0 s | 1.90 |"), std::string::npos);
  c.prior_phases = out / "absent.txt";  // refused before any work, the folder left empty
  EXPECT_THROW(RunReport(c, out / "s", {}), InputError);
  EXPECT_FALSE(std::filesystem::exists(out / "s/README.md"));
}

TEST(Report, PapersValuesOnlyBesideAMeshOfThePapersSize) {
  // Table 1 always shows the paper's sizes for its names; Table 2 and 3 only within 5%.
  Fixture f;
  testing::TempDir out;
  RunReport(f.Config(), out / "r", {});
  const auto t1 = Csv(out / "r/tables/table1.csv");
  ASSERT_EQ(t1.size(), 2u);
  EXPECT_EQ(t1[0].at("mesh"), "ocean");
  EXPECT_EQ(t1[0].at("paper_vertices"), "392674");
  EXPECT_EQ(t1[0].at("label"), "M6");
  const Mesh m = ReadMesh(f.meshes[0]);
  EXPECT_EQ(t1[0].at("vertices"), std::to_string(m.NumVertices()));
  EXPECT_EQ(t1[0].at("interior"), std::to_string(m.interior.size()));
}

// The many-core part: each machine.csv row is the simulator's warm sweep of that run, summed over
// the threads (checked against `simulate --machine` run here), one thread is one run for both
// placements, and the predicted speedups and gains are the means of the cycle ratios recomputed
// from machine.csv.
TEST(Report, ManyCorePartIsTheSimulatorsWarmSweepAndItsRatios) {
  Fixture f;
  testing::TempDir out;
  ReportConfig c = f.Config();
  c.machine_threads = {1, 2, 4};
  RunReport(c, out / "r", {});
  const auto rows = Csv(out / "r/data/machine.csv");
  auto find = [&](const std::string& mesh, const std::string& ord, const std::string& placement,
                  int p, const std::string& level, const std::string& prefetch = "off") {
    for (const auto& r : rows)
      if (r.at("mesh") == mesh && r.at("ordering") == ord && r.at("placement") == placement &&
          r.at("threads") == std::to_string(p) && r.at("level") == level &&
          r.at("prefetch") == prefetch)
        return r;
    ADD_FAILURE() << mesh << " " << ord << " " << placement << " " << p << " " << level;
    return std::map<std::string, std::string>{};
  };
  for (const auto& r : rows) {
    EXPECT_FALSE(r.at("threads") == "1" && r.at("placement") == "scatter");
    EXPECT_TRUE(r.at("prefetch") == "off" || r.at("threads") == "1");
  }
  // Against the simulator run directly: carabiner, bfs, 4 threads scattered.
  SimulateConfig sc;
  sc.inputs = {f.meshes[1]};
  sc.orderings = {"bfs"};
  sc.iterations = c.machine_sweeps;
  sc.threads = 4;
  sc.machine = "westmere-ex";
  sc.placements = {Placement::kScatter};
  sc.interleave = 1;
  const auto sims = RunMachineSimulate(sc, Log{}).sims;
  ASSERT_EQ(sims.size(), 1u);
  const MulticoreSimulation& sim = *sims[0];
  ThreadStats sum;
  double slowest = 0;
  for (int t = 0; t < sim.threads(); ++t) {
    const ThreadStats s = sim.SweepStats(t, sim.sweeps() - 1);
    sum += s;
    slowest = std::max(slowest, s.CyclesHigh(sim.machine()));
  }
  for (size_t i = 0; i < sum.levels.size(); ++i) {
    const auto r = find("carabiner", "bfs", "scatter", 4, sim.machine().levels[i].cache.name);
    EXPECT_EQ(r.at("accesses"), std::to_string(sum.levels[i].accesses));
    EXPECT_EQ(r.at("misses"), std::to_string(sum.levels[i].misses));
    EXPECT_EQ(r.at("served"), std::to_string(sum.levels[i].accesses - sum.levels[i].misses));
    EXPECT_EQ(r.at("coherence"), std::to_string(sum.levels[i].coherence));
    EXPECT_NEAR(std::stod(r.at("cycles_at_high_latency")), slowest, 1e-6 * slowest);
  }
  EXPECT_EQ(find("carabiner", "bfs", "scatter", 4, "memory_remote").at("accesses"),
            std::to_string(sum.memory_remote));
  EXPECT_GT(sum.memory_remote + sum.memory_local, 0u);  // the mesh was streamed cold
  EXPECT_GT(std::stoull(find("carabiner", "bfs", "compact", 1, "L1", "on").at("prefetches")), 0u);
  // Predicted speedups and gains: means over the meshes of cycle ratios, from machine.csv.
  auto cycles = [&](const std::string& mesh, const std::string& ord, const std::string& pl, int p,
                    const char* end) {
    return std::stod(find(mesh, ord, p == 1 ? "compact" : pl, p, "L1").at(end));
  };
  int checked = 0;
  for (const auto& r : Csv(out / "r/tables/predicted_speedup.csv")) {
    const std::string ord = r.at("ordering"), pl = r.at("placement");
    const int p = std::stoi(r.at("threads"));
    for (const char* end : {"cycles_at_low_latency", "cycles_at_high_latency"}) {
      const std::string suffix =
          std::string(end) == "cycles_at_low_latency" ? "_at_low_latency" : "_at_high_latency";
      double speedup = 0, gain = 0;
      for (const char* mesh : {"ocean", "carabiner"}) {
        const double cost = cycles(mesh, ord, pl, p, end);
        speedup += cycles(mesh, "ori", pl, 1, end) / cost / 2;
        gain += 100 * (1 - cost / cycles(mesh, "bfs", pl, p, end)) / 2;
      }
      EXPECT_NEAR(std::stod(r.at("speedup" + suffix)), speedup, 0.006) << ord << pl << p;
      if (ord != "bfs") {
        EXPECT_NEAR(std::stod(r.at("gain_vs_bfs_pct" + suffix)), gain, 0.06) << ord << pl << p;
      }
      ++checked;
    }
    if (ord == "ori" && p == 1) {
      EXPECT_EQ(r.at("speedup_at_low_latency"), "1.00");
    }
  }
  EXPECT_EQ(checked, 3 * 2 * 3 * 2);
}

TEST(Report, RejectsABadConfigurationBeforeAnyWork) {
  Fixture f;
  ReportConfig c = f.Config();
  c.orderings = {"no-such-ordering"};
  EXPECT_THROW(CheckReportConfig(c), std::invalid_argument);
  c = f.Config();
  c.meshes.push_back(f.meshes[0]);  // two meshes named ocean
  EXPECT_THROW(CheckReportConfig(c), std::invalid_argument);
  c = f.Config();
  c.threads = {0};
  EXPECT_THROW(CheckReportConfig(c), std::invalid_argument);
  c = f.Config();
  c.machine_threads = {33};  // beyond westmere-ex's 32 cores
  EXPECT_THROW(CheckReportConfig(c), std::invalid_argument);
  c = f.Config();
  c.prefetch_levels = "L9";
  EXPECT_THROW(CheckReportConfig(c), std::invalid_argument);
  c = f.Config();
  c.machine_sweeps = 1;  // no warm sweep
  EXPECT_THROW(CheckReportConfig(c), std::invalid_argument);
}

}  // namespace
}  // namespace meshreuse
