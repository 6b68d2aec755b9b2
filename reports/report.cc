// The paper's experiment as one run; see report.h. Tables are built from cells so CSV, Markdown,
// LaTeX and JSON show the same digits; an empty cell is a missing value (table.h).
#include "reports/report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "analysis/papi_counters.h"
#include "analysis/reuse_histogram.h"
#include "analysis/stack_distance.h"
#include "analysis/trace_analysis.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "reports/compare.h"
#include "reports/paper.h"
#include "reports/run_info.h"
#include "reports/table.h"
#include "reports/validation.h"

namespace meshreuse {

namespace {

using Clock = std::chrono::steady_clock;
using SayFn = std::function<void(const std::string&)>;

// The element stream into one exact stream analysis (its stack, histogram and, when enabled, its
// profile), and for Figure 1 optionally every distance in order.
struct ElementSink {
  static constexpr bool kEnabled = true;
  StreamAnalysis* analysis;
  std::vector<uint32_t>* series = nullptr;  // kColdMark for a first touch
  static constexpr uint32_t kColdMark = std::numeric_limits<uint32_t>::max();
  void Bind(const ArrayLayout&) {}
  void BeginSweep(int) {}
  void Access(int, const MemRef& r) {
    if (r.element == AccessKind::kNone) return;
    const uint64_t d = analysis->AddExact(static_cast<uint32_t>(r.vertex));
    if (series) series->push_back(d == StackDistance::kCold ? kColdMark : static_cast<uint32_t>(d));
  }
};

SmoothOptions Sweeps(int k) {
  SmoothOptions o;
  o.max_iters = k;
  o.tol = -std::numeric_limits<double>::infinity();  // exactly k sweeps
  return o;
}

std::string Int(uint64_t v) { return std::to_string(v); }
std::string Num(double v, int decimals) {
  if (!std::isfinite(v)) return "";
  std::string s = Fixed(v, decimals);
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);  // no "-0.0"
  return s;
}
std::string Pct(double v) { return Num(v, 1); }
double Ratio(double a, double b) { return b > 0 ? a / b : NAN; }
double Mean(const std::vector<double>& v) {
  double s = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) s += x, ++n;
  return n ? s / n : NAN;
}

// Progress with the elapsed time and an estimate of what remains, from work units done so far
// (units: vertices x sweeps of each step, weighted by its measured cost per access).
class Steps {
 public:
  Steps(const SayFn& say, double total) : say_(say), total_(total), t0_(Clock::now()) {}
  void Say(const std::string& what) const {
    if (!say_) return;
    const double el = std::chrono::duration<double>(Clock::now() - t0_).count();
    std::string left = "?";
    if (done_ > 0 && done_ < total_) left = Duration(el / done_ * (total_ - done_));
    if (done_ >= total_) left = "0s";
    say_(what + " [" + Duration(el) + " elapsed, ~" + left + " left]");
  }
  void Done(double units) { done_ += units; }

 private:
  SayFn say_;
  double total_, done_ = 0;
  Clock::time_point t0_;
};

struct MeshRun {
  std::string path, name;
  double weight = 0;  // its file's bytes: the progress estimate's unit (work grows with vertices)
  int32_t vertices = 0, triangles = 0, interior = 0;  // once read
};

struct FirstSweep {  // Table 2 and the histogram of one mesh x ordering
  std::string mesh, ordering;
  int32_t vertices = 0;
  ReuseHistogram hist;
};

struct Figure1Data {
  std::string ordering;
  uint64_t accesses = 0, cold = 0;
  double mean = NAN, model_l1_rate = NAN;
  std::vector<std::vector<uint64_t>> bins;  // [time bin][distance bin]
};

// Distance bins of Figure 1: 0, then four per power of two (bin b >= 1 holds
// [2^((b-1)/4), 2^(b/4)) rounded to integers), the last one for cold accesses.
constexpr int kDistanceBinsPerOctave = 4;
int DistanceBin(uint64_t d) {
  if (d == 0) return 0;
  return 1 +
         static_cast<int>(std::floor(std::log2(static_cast<double>(d)) * kDistanceBinsPerOctave));
}
uint64_t DistanceBinLo(int b) {
  return b == 0 ? 0
                : static_cast<uint64_t>(std::ceil(std::exp2((b - 1.0) / kDistanceBinsPerOctave)));
}

// CSV keeps every digit; Markdown and LaTeX round full-precision cells for reading (table.h).
void WriteTable(const std::string& dir, const std::string& name, const Table& t,
                const std::string& caption) {
  WriteAtomically(dir + "/" + name + ".csv", [&](std::FILE* f) { std::fputs(t.Csv().c_str(), f); });
  WriteAtomically(dir + "/" + name + ".md",
                  [&](std::FILE* f) { std::fputs(t.Markdown().c_str(), f); });
  WriteAtomically(dir + "/" + name + ".tex",
                  [&](std::FILE* f) { std::fputs(t.Latex(caption, "tab:" + name).c_str(), f); });
}

void WriteFile(const std::string& path, const std::string& text) {
  WriteAtomically(path, [&](std::FILE* f) { std::fputs(text.c_str(), f); });
}

std::string Levels(const std::vector<CacheLevel>& levels) {
  std::string s;
  for (const CacheLevel& l : levels)
    s += (s.empty() ? "" : ", ") + l.name + " " + std::to_string(l.bytes / 1024) + " KiB " +
         std::to_string(l.ways) + "-way";
  return s;
}

// An ordering spec for one mesh: "{mesh}" in it (file:perms/{mesh}.perm) becomes the mesh's
// name, so one spec names a permutation file per mesh.
std::string ForMesh(const std::string& spec, const std::string& mesh) {
  std::string s = spec;
  for (size_t at; (at = s.find("{mesh}")) != std::string::npos;) s.replace(at, 6, mesh);
  return s;
}
std::vector<std::string> ForMesh(const std::vector<std::string>& specs, const std::string& mesh) {
  std::vector<std::string> out;
  for (const std::string& s : specs) out.push_back(ForMesh(s, mesh));
  return out;
}

}  // namespace

void CheckReportConfig(const ReportConfig& cfg) {
  if (cfg.meshes.empty()) throw std::invalid_argument("no mesh given");
  if (cfg.orderings.empty()) throw std::invalid_argument("no ordering given");
  for (const std::string& m : cfg.meshes) {
    for (const std::string& o : cfg.orderings) {
      const std::string spec = ForMesh(o, paper::ShortName(m));
      CheckOrderingSpec(spec);
      if (spec.rfind("file:", 0) == 0 && !std::filesystem::is_regular_file(spec.substr(5)))
        throw std::invalid_argument("ordering " + o + ": no permutation file '" + spec.substr(5) +
                                    "' for mesh " + paper::ShortName(m));
    }
    for (const std::string& o : cfg.figure1_orderings)
      CheckOrderingSpec(ForMesh(o, paper::ShortName(m)));
  }
  std::set<std::string> names;
  for (const std::string& m : cfg.meshes)
    if (!names.insert(paper::ShortName(m)).second)
      throw std::invalid_argument("two meshes are named '" + paper::ShortName(m) +
                                  "': the tables name meshes by their file's stem");
  if (cfg.threads.empty()) throw std::invalid_argument("no thread count given");
  for (int p : cfg.threads)
    if (p < 1 || p > 255) throw std::invalid_argument("thread counts must be 1..255");
  if (cfg.repeat < 1 || cfg.repeat > 1000) throw std::invalid_argument("repeat must be 1..1000");
  if (cfg.validate_sweeps < 1 || cfg.validate_sweeps > 1000)
    throw std::invalid_argument("validation sweeps must be 1..1000");
  if (cfg.profile_sweeps < 1 || cfg.profile_sweeps > 1000)
    throw std::invalid_argument("profile sweeps must be 1..1000");
  if (cfg.figure1_time_bins < 1 || cfg.figure1_time_bins > 100000)
    throw std::invalid_argument("figure 1 time bins must be 1..100000");
}

std::vector<FigureSpec> ReportFigures(const ReportConfig& cfg) {
  std::vector<FigureSpec> f;
  std::set<std::string> names;
  for (const std::string& m : cfg.meshes) names.insert(paper::ShortName(m));
  if (names.count(cfg.figure1_mesh))
    f.push_back({"figure1", "reuse distance of every access of the first sweep on " +
                                cfg.figure1_mesh + " (random, ORI, BFS)"});
  if (names.count(cfg.profile_mesh))
    f.push_back({"profile", "reuse-distance profile over " + std::to_string(cfg.profile_sweeps) +
                                " sweeps of " + cfg.profile_mesh + ", one panel per ordering"});
  f.push_back({"histograms", "first-sweep reuse-distance histograms with the cache capacities"});
  f.push_back({"miss-rates", "L1/L2/L3 miss rates per mesh and ordering"});
  if (cfg.timing) {
    f.push_back({"time", "execution time to convergence per mesh and ordering, one thread"});
    f.push_back({"speedup", "Speedup(p) = T_ori(1) / T_ord(p) per mesh"});
    f.push_back({"speedup-mean", "mean Speedup(p) over the meshes"});
    f.push_back({"gain", "Gain(p) against ORI and BFS per mesh"});
  }
  if (cfg.label == "scale")
    f.push_back({"scale", "time per vertex per sweep and simulated misses per access vs size"});
  return f;
}

std::string RunReport(const ReportConfig& in_cfg, const std::string& out_dir, const SayFn& progress,
                      const SayFn& warn) {
  ReportConfig cfg = in_cfg;
  if (cfg.levels.empty()) cfg.levels = ParseCacheSpec("westmere-ex");
  CheckReportConfig(cfg);
  namespace fs = std::filesystem;
  const std::string tables = out_dir + "/tables", data = out_dir + "/data";
  fs::create_directories(tables);
  fs::create_directories(data);
  fs::create_directories(out_dir + "/figures");

  // Each mesh is read once, when its turn comes; the work is estimated from the files' sizes.
  std::vector<MeshRun> meshes;
  for (const std::string& p : cfg.meshes) {
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(p, ec);
    meshes.push_back({p, paper::ShortName(p), ec ? 1.0 : static_cast<double>(bytes)});
  }
  // Work units: file bytes x sweeps, each sweep weighted by its cost relative to a timed sweep,
  // measured on the nine meshes and at 10^7 vertices: a traced sweep into the analyzer costs 12-20
  // timed sweeps, into the analyzer and the simulator 70-130; a run to convergence takes about 65
  // sweeps.
  constexpr double kAnalysis = 15, kSimulation = 100, kSweepsToConverge = 65;
  double p_sum = 0;
  for (int p : cfg.threads) p_sum += 1.0 / p;
  double total = 0;
  const double no = static_cast<double>(cfg.orderings.size());
  for (const MeshRun& m : meshes) {
    const double v = m.weight;
    total += v * no * kAnalysis;                          // Table 2
    total += v * no * kSimulation * cfg.validate_sweeps;  // Table 3
    if (m.name == cfg.profile_mesh) total += v * no * kAnalysis * cfg.profile_sweeps;
    if (m.name == cfg.figure1_mesh)
      for (const std::string& o : cfg.figure1_orderings)
        if (std::find(cfg.orderings.begin(), cfg.orderings.end(), o) == cfg.orderings.end())
          total += v * kAnalysis;
    if (cfg.timing) total += v * no * cfg.repeat * kSweepsToConverge * p_sum;
  }
  Steps steps(progress, total);

  // Per mesh: Table 1's row; Table 2, the histograms, Figure 1 and the profile (the exact analyzer
  // on the element stream); Table 3 and the miss rates (the simulator, or counters).
  Table t1({"label", "mesh", "vertices", "triangles", "interior", "paper_vertices",
            "paper_triangles", "vertices_vs_paper_pct"});
  std::vector<OrderingValidation> val;
  std::vector<FirstSweep> first;
  std::vector<Figure1Data> fig1;
  Table prof({"mesh", "ordering", "iteration", "step", "accesses", "cold", "mean_distance"});
  const uint64_t c1 = cfg.levels[0].bytes / cfg.element_bytes;
  for (MeshRun& mr : meshes) {
    std::vector<std::string> warnings;
    const Mesh base = ReadMesh(mr.path, &warnings);
    if (warn)
      for (const std::string& w : warnings) warn(mr.path + ": " + w);
    mr.vertices = base.NumVertices(), mr.triangles = base.NumTriangles();
    mr.interior = static_cast<int32_t>(base.interior.size());
    const auto p1 = paper::Table1(mr.name);
    t1.AddRow({p1 ? p1->label : "", mr.name, Int(mr.vertices), Int(mr.triangles), Int(mr.interior),
               p1 ? Int(p1->vertices) : "", p1 ? Int(p1->triangles) : "",
               p1 ? Num(100.0 * (mr.vertices - p1->vertices) / p1->vertices, 1) : ""});
    std::vector<std::string> ords = cfg.orderings;
    if (mr.name == cfg.figure1_mesh)
      for (const std::string& o : cfg.figure1_orderings)
        if (std::find(ords.begin(), ords.end(), o) == ords.end()) ords.push_back(o);
    for (const std::string& ord : ords) {
      const bool in_tables =
          std::find(cfg.orderings.begin(), cfg.orderings.end(), ord) != cfg.orderings.end();
      const bool in_fig1 = mr.name == cfg.figure1_mesh &&
                           std::find(cfg.figure1_orderings.begin(), cfg.figure1_orderings.end(),
                                     ord) != cfg.figure1_orderings.end();
      steps.Say("reuse distances: " + mr.name + " " + ord + ", first sweep");
      Mesh m = ApplyPermutation(base, ComputeOrdering(ForMesh(ord, mr.name), base, cfg.seed),
                                cfg.triangle_order);
      const bool profile = in_tables && mr.name == cfg.profile_mesh;
      std::optional<Mesh> start;  // the laid-out mesh before the sweep, for the profile's run
      if (profile) start = m.Clone();
      FirstSweep fs1{mr.name, ord, mr.vertices, {}};
      std::vector<uint32_t> series;
      {
        StreamAnalysis a(static_cast<uint64_t>(mr.vertices));
        ElementSink sink{&a, in_fig1 ? &series : nullptr};
        Smooth(m, Sweeps(1), sink);
        fs1.hist = std::move(a.hist);
      }
      steps.Done(mr.weight * kAnalysis);
      if (in_fig1) {
        Figure1Data f;
        f.ordering = ord;
        f.accesses = series.size();
        f.cold = fs1.hist.cold();
        f.mean = fs1.hist.mean();
        f.model_l1_rate = Ratio(static_cast<double>(fs1.hist.cold() + fs1.hist.CountAtLeast(c1)),
                                static_cast<double>(fs1.hist.accesses()));
        const int tb = cfg.figure1_time_bins;
        const int db = DistanceBin(std::max<uint64_t>(1, static_cast<uint64_t>(mr.vertices))) + 2;
        f.bins.assign(tb, std::vector<uint64_t>(db, 0));
        for (size_t i = 0; i < series.size(); ++i) {
          const size_t t =
              static_cast<size_t>((static_cast<unsigned __int128>(i) * tb) / series.size());
          const uint32_t d = series[i];
          ++f.bins[t][d == ElementSink::kColdMark ? db - 1 : DistanceBin(d)];
        }
        fig1.push_back(std::move(f));
      }
      if (profile) {
        steps.Say("reuse-distance profile: " + mr.name + " " + ord + ", " +
                  std::to_string(cfg.profile_sweeps) + " sweeps");
        Mesh pm = std::move(*start);
        StreamAnalysis a(static_cast<uint64_t>(mr.vertices));
        a.profile =
            ReuseProfile(std::vector<uint64_t>(cfg.profile_sweeps, AccessesPerSweep(pm)[0]), 100);
        ElementSink sink{&a};
        Smooth(pm, Sweeps(cfg.profile_sweeps), sink);
        for (const ReuseProfile::Step& s : a.profile.steps())
          prof.AddRow({mr.name, ord, Int(s.iteration), Int(s.step), Int(s.accesses), Int(s.cold),
                       s.accesses > s.cold ? JsonNumber(s.mean()) : ""});
        steps.Done(mr.weight * kAnalysis * cfg.profile_sweeps);
      }
      if (in_tables) first.push_back(std::move(fs1));
    }

    ValidationConfig vc;
    vc.mesh_name = mr.name;
    vc.seed = cfg.seed;
    vc.iterations = cfg.validate_sweeps;
    vc.triangle_order = cfg.triangle_order;
    vc.levels = cfg.levels;
    vc.element_bytes = cfg.element_bytes, vc.line_bytes = cfg.line_bytes;
    vc.counter_events = cfg.counter_events;
    steps.Say("misses (Table 3): " + mr.name + ", " + std::to_string(cfg.orderings.size()) +
              " orderings x " + std::to_string(cfg.validate_sweeps) + " traced sweeps");
    // One ordering at a time, so progress moves with each.
    const std::vector<std::string> specs = ForMesh(cfg.orderings, mr.name);
    for (size_t k = 0; k < specs.size(); ++k) {
      vc.orderings = {specs[k]};
      std::vector<OrderingValidation> vs =
          RunValidation(base, vc, [&](const std::string& s) { steps.Say(s); });
      vs[0].ordering = cfg.orderings[k];  // the spec as given, {mesh} and all
      val.push_back(std::move(vs[0]));
      steps.Done(mr.weight * kSimulation * cfg.validate_sweeps);
    }
  }
  WriteTable(tables, "table1", t1, "Input mesh configuration (the paper's Table 1)");

  Table t2({"mesh", "ordering", "q50", "q75", "q90", "q100", "accesses", "mean", "cold",
            "paper_q50", "paper_q75", "paper_q90", "paper_q100", "paper_accesses",
            "accesses_vs_paper"});
  Table hist({"mesh", "ordering", "lo", "hi", "count"});
  for (const FirstSweep& f : first) {
    std::vector<std::string> row = {f.mesh, f.ordering};
    const bool finite = f.hist.finite() > 0;
    for (double q : {0.5, 0.75, 0.9, 1.0}) row.push_back(finite ? Int(f.hist.Quantile(q)) : "");
    row.push_back(Int(f.hist.accesses()));
    row.push_back(finite ? JsonNumber(f.hist.mean()) : "");
    row.push_back(Int(f.hist.cold()));
    const auto p = paper::Table2(f.mesh, f.ordering);
    const bool has = p && paper::Sized(f.mesh, f.vertices);
    for (int i = 0; i < 4; ++i) row.push_back(has ? Int(p->q[i]) : "");
    row.push_back(has ? Int(p->accesses) : "");
    row.push_back(has ? Num(static_cast<double>(f.hist.accesses()) / p->accesses, 3) : "");
    t2.AddRow(row);
    for (const ReuseHistogram::Bin& b : f.hist.Binned(1))
      if (b.count) hist.AddRow({f.mesh, f.ordering, Int(b.lo), Int(b.hi), Int(b.count)});
    if (f.hist.cold()) hist.AddRow({f.mesh, f.ordering, "cold", "cold", Int(f.hist.cold())});
  }
  WriteTable(tables, "table2", t2,
             "Reuse distances of the first sweep (element stream, distinct vertices): quantiles "
             "and accesses (the paper's Table 2)");
  WriteFile(data + "/histogram.csv", hist.Csv());
  if (prof.Rows()) WriteFile(data + "/profile.csv", prof.Csv());
  {
    Table caps({"level", "bytes", "ways", "elements", "lines"});
    for (const CacheLevel& l : cfg.levels)
      caps.AddRow({l.name, Int(l.bytes), Int(l.ways), Int(l.bytes / cfg.element_bytes),
                   Int(l.bytes / cfg.line_bytes)});
    WriteFile(data + "/capacities.csv", caps.Csv());
  }
  // Figure 1's panels in its configured order (the paper's: random, ORI, BFS).
  auto fig1_rank = [&](const Figure1Data& f) {
    return std::find(cfg.figure1_orderings.begin(), cfg.figure1_orderings.end(), f.ordering) -
           cfg.figure1_orderings.begin();
  };
  std::stable_sort(fig1.begin(), fig1.end(), [&](const Figure1Data& a, const Figure1Data& b) {
    return fig1_rank(a) < fig1_rank(b);
  });
  if (!fig1.empty()) {
    Table f1({"ordering", "time_bin", "distance_lo", "distance_hi", "count"});
    for (const Figure1Data& f : fig1) {
      const int db = f.bins.empty() ? 0 : static_cast<int>(f.bins[0].size());
      for (size_t t = 0; t < f.bins.size(); ++t)
        for (int b = 0; b < db; ++b)
          if (f.bins[t][b]) {
            const bool cold = b == db - 1;
            f1.AddRow({f.ordering, Int(t), cold ? "cold" : Int(DistanceBinLo(b)),
                       cold ? "cold" : Int(DistanceBinLo(b + 1) - 1), Int(f.bins[t][b])});
          }
    }
    WriteFile(data + "/figure1.csv", f1.Csv());
  }

  const Table t3 = Table3(val);
  WriteTable(tables, "table3", t3,
             "Estimated misses per sweep ($\\times 10^3$) and the inverse model's capacities "
             "($\\times 10^3$ elements; lines) (the paper's Table 3)");
  // Miss rates of the last traced sweep (the caches warm, as in the paper's runs to convergence;
  // counters, which cover all sweeps, are divided by the sweep count).
  Table misses({"mesh", "ordering", "level", "source", "accesses", "misses", "cold",
                "local_miss_rate", "global_miss_rate"});
  // [ordering][level] -> per mesh misses, for the reductions
  std::map<std::string, std::map<std::string, std::vector<double>>> per_mesh;
  std::map<std::string, std::string> sources;
  for (const OrderingValidation& v : val) {
    const size_t last = v.sweeps.empty() ? 0 : v.sweeps.size() - 1;
    uint64_t line_accesses = 0;
    if (!v.sweeps.empty())
      for (const auto& th : v.sweeps[last]) line_accesses += th.empty() ? 0 : th[0].accesses;
    for (size_t i = 0; i < v.levels.size(); ++i) {
      const LevelValidation& l = v.levels[i];
      LevelStats s;
      if (!v.sweeps.empty())
        for (const auto& th : v.sweeps[last]) s += th[i];
      const double m = l.measured ? l.counter / v.iterations : static_cast<double>(s.misses);
      const char* src = l.measured ? "measured" : "simulated";
      sources[l.level.name] = src;
      misses.AddRow({v.mesh, v.ordering, l.level.name, src, Int(s.accesses), JsonNumber(m),
                     l.measured ? "" : Int(s.cold),
                     JsonNumber(Ratio(m, static_cast<double>(s.accesses))),
                     JsonNumber(Ratio(m, static_cast<double>(line_accesses)))});
      per_mesh[v.ordering][l.level.name].push_back(m);
    }
  }
  WriteFile(data + "/misses.csv", misses.Csv());
  WriteTable(tables, "misses", misses,
             "Misses of the last traced sweep per level (simulated unless measured)");

  // Fewer misses than ori and bfs, per level: the mean over meshes of 1 - m_ord / m_ref.
  Table red({"ordering", "level", "source", "fewer_vs_ori_pct", "paper_fewer_vs_ori_pct",
             "diff_vs_ori_points", "fewer_vs_bfs_pct", "paper_fewer_vs_bfs_pct",
             "diff_vs_bfs_points"});
  for (const std::string& ord : cfg.orderings)
    for (size_t i = 0; i < cfg.levels.size(); ++i) {
      const std::string& ln = cfg.levels[i].name;
      auto fewer = [&](const std::string& ref) {
        if (!per_mesh.count(ref) || ref == ord) return static_cast<double>(NAN);
        const auto& a = per_mesh[ord][ln];
        const auto& b = per_mesh[ref][ln];
        std::vector<double> r;
        for (size_t k = 0; k < a.size() && k < b.size(); ++k)
          r.push_back(b[k] > 0 ? 100.0 * (1 - a[k] / b[k]) : NAN);
        return Mean(r);
      };
      const bool paper_row = ord == "rdr" && cfg.levels.size() == 3;
      const double fo = fewer("ori"), fb = fewer("bfs");
      const double po = paper_row ? paper::kRdrFewerMissesVsOri[i] : NAN;
      const double pb = paper_row ? paper::kRdrFewerMissesVsBfs[i] : NAN;
      if (!std::isfinite(fo) && !std::isfinite(fb)) continue;
      red.AddRow({ord, ln, sources[ln], Pct(fo), Num(po, 1), Num(fo - po, 1), Pct(fb), Num(pb, 1),
                  Num(fb - pb, 1)});
    }
  WriteTable(tables, "miss_reduction", red,
             "Fewer misses per level than ORI and BFS (mean over the meshes, \\%), one thread");

  // Timing: RunCompare over orderings x threads, a mesh at a time (each mesh's orderings may name
  // its own permutation file).
  std::vector<CompareRow> rows;
  if (cfg.timing) {
    CompareConfig cc;
    cc.threads = cfg.threads;
    cc.repeat = cfg.repeat;
    cc.seed = cfg.seed;
    cc.smooth = cfg.smooth;
    cc.triangle_order = cfg.triangle_order;
    for (size_t mi = 0; mi < meshes.size(); ++mi) {
      const MeshRun& m = meshes[mi];
      cc.meshes = {m.path};
      cc.orderings = ForMesh(cfg.orderings, m.name);
      const std::string where = "timing [" + std::to_string(mi + 1) + "/" +
                                std::to_string(meshes.size()) + "] " + m.name + ": ";
      std::vector<CompareRow> mesh_rows =
          RunCompare(cc, [&](const std::string& s) { steps.Say(where + s); }, {});
      for (CompareRow& r : mesh_rows) {
        const size_t k =
            std::find(cc.orderings.begin(), cc.orderings.end(), r.ordering) - cc.orderings.begin();
        if (k < cfg.orderings.size()) r.ordering = cfg.orderings[k];
        rows.push_back(std::move(r));
      }
      steps.Done(m.weight * no * cfg.repeat * kSweepsToConverge * p_sum);
    }
    const auto fig1_mesh = std::find_if(
        meshes.begin(), meshes.end(), [&](const MeshRun& m) { return m.name == cfg.figure1_mesh; });
    std::vector<std::string> extra;
    for (const std::string& o : cfg.figure1_orderings)
      if (std::find(cfg.orderings.begin(), cfg.orderings.end(), o) == cfg.orderings.end())
        extra.push_back(o);
    if (fig1_mesh != meshes.end() && !extra.empty()) {
      CompareConfig fc = cc;
      fc.meshes = {fig1_mesh->path};
      fc.orderings = ForMesh(extra, fig1_mesh->name);
      fc.threads = {1};
      steps.Say("timing Figure 1's other orderings on " + fig1_mesh->name);
      for (CompareRow& r : RunCompare(fc, {}, {})) rows.push_back(std::move(r));
    }
  }
  auto T = [&](const std::string& mesh, const std::string& ord, int p) -> const CompareRow* {
    for (const CompareRow& r : rows)
      if (paper::ShortName(r.mesh) == mesh && r.ordering == ord && r.threads == p) return &r;
    return nullptr;
  };
  if (!fig1.empty()) {
    Table f1s({"ordering", "accesses", "cold", "mean_distance", "model_l1_miss_rate_pct", "seconds",
               "paper_mean_distance", "paper_l1_miss_rate_pct", "paper_seconds"});
    for (const Figure1Data& f : fig1) {
      const CompareRow* r = T(cfg.figure1_mesh, f.ordering, 1);
      const auto p = paper::Figure1(f.ordering);
      f1s.AddRow({f.ordering, Int(f.accesses), Int(f.cold), JsonNumber(f.mean),
                  Num(100 * f.model_l1_rate, 3), r ? JsonNumber(r->median_total) : "",
                  p ? JsonNumber(p->mean_distance) : "", p ? JsonNumber(p->l1_miss_percent) : "",
                  p ? JsonNumber(p->seconds) : ""});
    }
    WriteFile(data + "/figure1_summary.csv", f1s.Csv());
  }

  Table time(
      {"mesh", "ordering", "sweeps", "total_s", "sweep_ms", "speedup_vs_ori", "speedup_vs_bfs"});
  Table sum1({"ordering", "meshes", "speedup_vs_ori", "paper_speedup_vs_ori", "diff_vs_ori",
              "speedup_vs_bfs", "paper_speedup_vs_bfs", "diff_vs_bfs"});
  Table scal(
      {"mesh", "ordering", "threads", "total_s", "speedup", "gain_vs_ori_pct", "gain_vs_bfs_pct"});
  Table scalm({"ordering", "threads", "mean_speedup", "mean_gain_vs_ori_pct",
               "paper_gain_vs_ori_pct_low", "paper_gain_vs_ori_pct_high", "mean_gain_vs_bfs_pct",
               "paper_gain_vs_bfs_pct_low", "paper_gain_vs_bfs_pct_high"});
  Table cost({"mesh", "ordering", "order_ms", "apply_ms", "apply_first_ms", "ori_sweep_ms",
              "order_sweeps", "apply_sweeps", "paper_order_sweeps"});
  if (cfg.timing) {
    for (const MeshRun& m : meshes)
      for (const std::string& ord : cfg.orderings) {
        const CompareRow* r = T(m.name, ord, 1);
        if (!r) continue;
        const CompareRow* o = T(m.name, "ori", 1);
        const CompareRow* b = T(m.name, "bfs", 1);
        time.AddRow({m.name, ord, Int(r->sweeps.empty() ? 0 : r->sweeps[0]),
                     JsonNumber(r->median_total), Num(1e3 * r->median_sweep, 3),
                     Num(o ? o->median_total / r->median_total : NAN, 3),
                     Num(b ? b->median_total / r->median_total : NAN, 3)});
        const double ori_sweep = o ? o->median_sweep : NAN;
        cost.AddRow({m.name, ord, Num(1e3 * r->order_seconds, 3), Num(1e3 * r->apply_seconds, 3),
                     Num(1e3 * r->apply_first_seconds, 3), Num(1e3 * ori_sweep, 3),
                     Num(Ratio(r->order_seconds, ori_sweep), 2),
                     Num(Ratio(r->apply_seconds, ori_sweep), 2),
                     ord == "rdr" ? Num(paper::kRdrCostSweeps, 0) : ""});
      }
    for (const std::string& ord : cfg.orderings) {
      std::vector<double> so, sb;
      for (const MeshRun& m : meshes) {
        const CompareRow* r = T(m.name, ord, 1);
        if (!r) continue;
        const CompareRow* o = T(m.name, "ori", 1);
        const CompareRow* b = T(m.name, "bfs", 1);
        const double vo = o ? o->median_total / r->median_total : NAN;
        const double vb = b ? b->median_total / r->median_total : NAN;
        so.push_back(vo), sb.push_back(vb);
      }
      const bool p = ord == "rdr";
      const double mo = Mean(so), mb = Mean(sb);
      sum1.AddRow({ord, Int(so.size()), Num(mo, 3), p ? Num(paper::kRdrSpeedupVsOri, 2) : "",
                   p ? Num(mo - paper::kRdrSpeedupVsOri, 3) : "", Num(mb, 3),
                   p ? Num(paper::kRdrSpeedupVsBfs, 2) : "",
                   p ? Num(mb - paper::kRdrSpeedupVsBfs, 3) : ""});
      for (int th : cfg.threads) {
        std::vector<double> sp, go, gb;
        for (const MeshRun& m : meshes) {
          const CompareRow* r = T(m.name, ord, th);
          if (!r) continue;
          const CompareRow* o1 = T(m.name, "ori", 1);
          const CompareRow* op = T(m.name, "ori", th);
          const CompareRow* bp = T(m.name, "bfs", th);
          const double s = o1 ? o1->median_total / r->median_total : NAN;
          const double g1 = op && ord != "ori"
                                ? 100 * (op->median_total - r->median_total) / op->median_total
                                : NAN;
          const double g2 = bp && ord != "bfs"
                                ? 100 * (bp->median_total - r->median_total) / bp->median_total
                                : NAN;
          sp.push_back(s), go.push_back(g1), gb.push_back(g2);
          scal.AddRow(
              {m.name, ord, Int(th), JsonNumber(r->median_total), Num(s, 3), Pct(g1), Pct(g2)});
        }
        scalm.AddRow({ord, Int(th), Num(Mean(sp), 3), Pct(Mean(go)),
                      p ? Num(paper::kRdrGainVsOri[0], 0) : "",
                      p ? Num(paper::kRdrGainVsOri[1], 0) : "", Pct(Mean(gb)),
                      p ? Num(paper::kRdrGainVsBfs[0], 0) : "",
                      p ? Num(paper::kRdrGainVsBfs[1], 0) : ""});
      }
    }
    WriteTable(tables, "time", time,
               "Execution time to convergence on one thread, and the speedups against ORI and BFS");
    WriteTable(tables, "speedup", sum1,
               "Mean one-thread speedup over the meshes against ORI and BFS");
    WriteTable(tables, "scaling", scal,
               "Speedup(p) = $T_{ori}(1)/T_{ord}(p)$ and Gain(p) against ORI and BFS");
    WriteTable(tables, "scaling_mean", scalm, "Mean Speedup(p) and Gain(p) over the meshes");
    WriteTable(tables, "reorder_cost", cost,
               "Cost of reordering in ORI sweeps (one thread): computing the ordering and "
               "applying it");
    WriteFile(out_dir + "/data/compare.json", "{\"rows\": " + CompareJson(rows) + "}\n");
  }

  // run.json
  std::string counters = "simulated";
  for (const auto& [lvl, src] : sources)
    if (src == "measured") counters = "measured";
  if (counters == "simulated") {
    const CounterNote note = ProbeCounters(cfg.counter_events);
    counters += cfg.counter_events.empty() ? std::string(" (no counters asked for)")
                                           : " (" + note.note + ")";
  } else if (!val.empty()) {
    counters = val[0].counters;
  }
  {
    std::string ms, os, ts, fo;
    for (const std::string& m : cfg.meshes) ms += (ms.empty() ? "" : ", ") + JsonString(m);
    for (const std::string& o : cfg.orderings) os += (os.empty() ? "" : ", ") + JsonString(o);
    for (int p : cfg.threads) ts += (ts.empty() ? "" : ", ") + std::to_string(p);
    for (const std::string& o : cfg.figure1_orderings)
      fo += (fo.empty() ? "" : ", ") + JsonString(o);
    std::string j = "{\n  \"tool\": \"meshreuse report\",\n";
    j += "  \"command\": " + CommandLineJson(cfg.command_line) + ",\n";
    j += "  \"build\": " + BuildJson() + ",\n";
    j += "  \"time\": " + JsonString(UtcTimestamp()) + ",\n";
    j += "  \"machine\": " + MachineJson() + ",\n";
    j += "  \"configuration\": {\"label\": " + JsonString(cfg.label) + ", \"meshes\": [" + ms +
         "], \"orderings\": [" + os + "], \"threads\": [" + ts +
         "], \"repeat\": " + std::to_string(cfg.repeat) +
         ", \"seed\": " + std::to_string(cfg.seed) + ", \"tol\": " + JsonNumber(cfg.smooth.tol) +
         ", \"max_iters\": " + std::to_string(cfg.smooth.max_iters) +
         ", \"triangle_order\": " + JsonString(TriangleOrderName(cfg.triangle_order)) +
         ", \"caches\": " + JsonString(Levels(cfg.levels)) +
         ", \"element_bytes\": " + std::to_string(cfg.element_bytes) +
         ", \"line_bytes\": " + std::to_string(cfg.line_bytes) +
         ", \"validate_sweeps\": " + std::to_string(cfg.validate_sweeps) +
         ", \"profile_sweeps\": " + std::to_string(cfg.profile_sweeps) +
         ", \"figure1_mesh\": " + JsonString(cfg.figure1_mesh) + ", \"figure1_orderings\": [" + fo +
         "], \"profile_mesh\": " + JsonString(cfg.profile_mesh) +
         ", \"timing\": " + (cfg.timing ? "true" : "false") + "},\n";
    j += "  \"counters\": " + JsonString(counters) + "\n}\n";
    WriteFile(out_dir + "/run.json", j);
  }

  // The results README: every table (ours | paper | difference) and every figure.
  std::string r = "# meshreuse report" + (cfg.label.empty() ? "" : " (" + cfg.label + ")") + "\n\n";
  r += "Made by `meshreuse report` (" + GitRevision() + ", " + UtcTimestamp() + ") on " +
       std::to_string(meshes.size()) + " mesh(es), orderings ";
  for (size_t i = 0; i < cfg.orderings.size(); ++i) r += (i ? ", " : "") + cfg.orderings[i];
  r += "; threads";
  for (int p : cfg.threads) r += " " + std::to_string(p);
  r += "; " + std::to_string(cfg.repeat) + " round(s), seed " + std::to_string(cfg.seed) +
       ". Configuration, machine and build: [run.json](run.json). Caches: " + Levels(cfg.levels) +
       "; misses are **" + counters +
       "**. Every table is also in `tables/` as CSV, Markdown and LaTeX (booktabs); an empty "
       "cell is a value the paper does not give (or not for a mesh of its size).\n\n";
  auto section = [&](const std::string& title, const std::string& name, const Table& t,
                     const std::string& note) {
    r += "## " + title + "\n\n" + note + (note.empty() ? "" : "\n\n") + t.Markdown() +
         "\nFiles: [csv](tables/" + name + ".csv), [md](tables/" + name + ".md), [tex](tables/" +
         name + ".tex)\n\n";
  };
  section("Table 1: meshes", "table1", t1,
          "Our meshes are Triangle meshes of shipped shapes drawn after the paper's names, at its "
          "vertex counts (the paper's meshes are not public).");
  section("Table 2: reuse distances of the first sweep", "table2", t2,
          "Distinct vertices between two touches of a vertex record (66-byte elements, the "
          "paper's model), first sweep. The paper's column is shown for a mesh within 5% of its "
          "size. Our meshes are other meshes of the same size. Our accesses are the vertex-record "
          "touches of Algorithm 1 (2 + deg + 3 tris per visit; the project README, \"Access\"); "
          "the paper counts about twice as many, and its ORI and BFS 100% quantiles (1.9 million "
          "on a 328,082-vertex mesh) exceed its vertex counts, so its distances count something "
          "finer than vertex records. Ours cannot exceed the vertex count.");
  section("Table 3: estimated misses and capacities", "table3", t3,
          "Misses per sweep over the traced sweeps (" + counters +
              "), and the capacity the inverse model gives for them. The traced sweeps start "
              "from empty caches, so the first sweep's cold misses are counted; the miss rates "
              "and reductions below use the last sweep. The paper measured whole runs with PAPI "
              "on Westmere-EX, whose prefetchers our simulator does not model.");
  section("Fewer misses than ORI and BFS", "miss_reduction", red,
          "Per level, the mean over meshes of 1 - misses(ordering) / misses(reference), from the "
          "last traced sweep (warm caches). The paper's numbers are for RDR on one core.");
  if (cfg.timing) {
    section("Execution time", "time", time,
            "Median over " + std::to_string(cfg.repeat) +
                " interleaved rounds of the time to convergence (tol " +
                JsonNumber(cfg.smooth.tol) + "), one thread; speedups within each mesh.");
    section("Speedup against ORI and BFS (one thread)", "speedup", sum1,
            "The mean over meshes of T_ref(1) / T_ord(1). The paper: RDR 1.39x over ORI, 1.19x "
            "over BFS, on its nine meshes.");
    section("Speedup(p) and Gain(p)", "scaling_mean", scalm,
            "Speedup(p) = T_ori(1) / T_ord(p); Gain(p) = (T_ref(p) - T_ord(p)) / T_ref(p). The "
            "paper gives its gains as ranges over 1-32 cores (RDR: 20-30% over ORI, 10-30% over "
            "BFS). Per mesh: [tables/scaling.md](tables/scaling.md).");
    section("Reordering cost", "reorder_cost", cost,
            "Computing the ordering and applying it, in median ORI sweeps of the same mesh. The "
            "paper: RDR costs about one ORI sweep.");
  }
  r += "## Figures\n\nMade by `scripts/plot_report.py` from `data/` and `tables/` (PNG and "
       "PDF in `figures/`).\n\n";
  for (const FigureSpec& f : ReportFigures(cfg))
    r += "- **" + f.name + "**: " + f.title + " ([pdf](figures/" + f.name + ".pdf))\n\n  ![" +
         f.name + "](figures/" + f.name + ".png)\n";
  WriteFile(out_dir + "/README.md", r);
  steps.Say("tables written to " + out_dir);
  return out_dir + "/README.md";
}

}  // namespace meshreuse
