// RunCompare and its tables; see compare.h.
#include "reports/compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

#include "analysis/papi_counters.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "reports/run_info.h"

namespace meshreuse {

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

std::vector<CompareRow> RunCompare(const CompareConfig& cfg,
                                   const std::function<void(const std::string&)>& progress,
                                   const std::function<void(const std::string&)>& warn) {
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  std::vector<CompareRow> rows;
  const size_t per_mesh = cfg.orderings.size() * cfg.threads.size() * cfg.repeat;
  const size_t total_runs = per_mesh * cfg.meshes.size();
  size_t runs_done = 0;
  const auto start = Clock::now();
  for (size_t mi = 0; mi < cfg.meshes.size(); ++mi) {
    const std::string& path = cfg.meshes[mi];
    say("mesh " + std::to_string(mi + 1) + "/" + std::to_string(cfg.meshes.size()) + ": reading " +
        path);
    std::vector<std::string> warnings;
    const Mesh base = ReadMesh(path, &warnings);
    if (warn)
      for (const std::string& w : warnings) warn(w);
    // Memory: the base mesh, one working copy and a permutation per ordering (4 bytes a vertex),
    // not a reordered mesh per ordering. Before each run the working copy is reordered from the
    // base (ApplyPermutationInto, into the same arrays), which also restores the start.
    std::vector<std::vector<int32_t>> perms;
    std::vector<std::vector<double>> apply_ms(cfg.orderings.size());
    Mesh work;
    const size_t first_row = rows.size();
    for (const std::string& spec : cfg.orderings) {
      // The working copy goes first: the ordering's and the span's scratch memory then never
      // adds to two meshes, and the first apply of each ordering allocates, as a fresh reorder
      // would.
      work = Mesh();
      auto t0 = Clock::now();
      Permutation p = ComputeOrdering(spec, base, cfg.seed);
      const double order_s = Since(t0);
      const EdgeSpan span = MeasureEdgeSpan(base, p);
      t0 = Clock::now();
      ApplyPermutationInto(base, p, cfg.triangle_order, &work);
      const double apply_s = Since(t0);
      std::vector<int32_t> new_to_old = p.new_to_old();
      perms.push_back(std::move(new_to_old));
      say("  " + spec + ": ordering " + Fixed(1e3 * order_s, 1) + " ms, apply " +
          Fixed(1e3 * apply_s, 1) + " ms");
      for (int t : cfg.threads) {
        CompareRow r;
        r.mesh = path, r.ordering = spec, r.threads = t;
        r.vertices = base.NumVertices(), r.triangles = base.NumTriangles();
        r.order_seconds = order_s, r.apply_first_seconds = apply_s;
        r.span = span;
        rows.push_back(std::move(r));
      }
    }
    for (int round = 0; round < cfg.repeat; ++round) {
      size_t k = first_row;
      for (size_t oi = 0; oi < cfg.orderings.size(); ++oi)
        for (int t : cfg.threads) {
          CompareRow& r = rows[k++];
          {
            const Permutation p = Permutation::FromNewToOld(perms[oi]);
            const auto t0 = Clock::now();
            ApplyPermutationInto(base, p, cfg.triangle_order, &work);
            apply_ms[oi].push_back(Since(t0));
          }
          Mesh& m = work;
          SmoothOptions o = cfg.smooth;
          o.threads = t;
          std::unique_ptr<PapiCounters> papi;
          if (!cfg.counter_events.empty()) {
            papi = std::make_unique<PapiCounters>(cfg.counter_events, t);
            if (papi->available()) o.region = papi.get();
          }
          const SmoothResult res = Smooth(m, o);
          if (papi && papi->available()) {
            if (!papi->error().empty())
              throw std::runtime_error("counters failed: " + papi->error());
            r.counter_events = papi->events();
            r.counters.push_back(papi->Sum());
          }
          r.sweeps.push_back(static_cast<int>(res.sweeps.size()));
          r.total_seconds.push_back(res.seconds);
          for (const SweepRecord& s : res.sweeps) r.sweep_seconds.push_back(s.seconds);
          if (round == 0) r.final_quality = res.quality_after;
          ++runs_done;
          const double el = Since(start);
          say("  round " + std::to_string(round + 1) + "/" + std::to_string(cfg.repeat) + " " +
              r.ordering + " x" + std::to_string(t) + ": " + std::to_string(res.sweeps.size()) +
              " sweeps, " + Fixed(res.seconds, 3) + " s  [" + std::to_string(runs_done) + "/" +
              std::to_string(total_runs) + " runs, ~" +
              Duration(el / runs_done * (total_runs - runs_done)) + " left]");
        }
    }
    // Medians and the paper's ratios, within this mesh.
    std::map<std::pair<std::string, int>, double> t_of;
    for (size_t i = first_row; i < rows.size(); ++i) {
      CompareRow& r = rows[i];
      r.apply_seconds = Median(apply_ms[(i - first_row) / cfg.threads.size()]);
      for (size_t e = 0; e < r.counter_events.size(); ++e) {
        std::vector<double> v;
        for (const auto& round : r.counters) v.push_back(static_cast<double>(round[e]));
        r.counter_medians.push_back(Median(v));
      }
      rows[i].median_total = Median(rows[i].total_seconds);
      rows[i].median_sweep = Median(rows[i].sweep_seconds);
      t_of[{rows[i].ordering, rows[i].threads}] = rows[i].median_total;
    }
    const auto ori1 = t_of.find({"ori", 1});
    for (size_t i = first_row; i < rows.size(); ++i) {
      CompareRow& r = rows[i];
      r.speedup_vs_ori1 = ori1 != t_of.end() ? ori1->second / r.median_total : NAN;
      const auto bfs = t_of.find({"bfs", r.threads});
      r.gain_vs_bfs = bfs != t_of.end() ? (bfs->second - r.median_total) / bfs->second : NAN;
    }
  }
  return rows;
}

namespace {
std::string SweepRange(const std::vector<int>& s) {
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  return *lo == *hi ? std::to_string(*lo) : std::to_string(*lo) + "-" + std::to_string(*hi);
}
std::string OrDash(double v, int decimals) { return std::isfinite(v) ? Fixed(v, decimals) : ""; }
}  // namespace

Table CompareTable(const std::vector<CompareRow>& rows) {
  std::vector<std::string> head = {"mesh",
                                   "ordering",
                                   "threads",
                                   "sweeps",
                                   "final_quality",
                                   "order_ms",
                                   "apply_ms",
                                   "apply_first_ms",
                                   "span_median",
                                   "span_p90",
                                   "median_ms_per_sweep",
                                   "median_total_s",
                                   "speedup_vs_ori1",
                                   "gain_vs_bfs_%"};
  std::vector<std::string> events;  // counters recorded in any row, in first-seen order
  for (const CompareRow& r : rows)
    for (const std::string& e : r.counter_events)
      if (std::find(events.begin(), events.end(), e) == events.end()) events.push_back(e);
  for (const std::string& e : events) head.push_back(e);
  Table t(head);
  for (const CompareRow& r : rows) {
    std::vector<std::string> row = {r.mesh,
                                    r.ordering,
                                    std::to_string(r.threads),
                                    SweepRange(r.sweeps),
                                    Fixed(r.final_quality, 6),
                                    Fixed(1e3 * r.order_seconds, 1),
                                    Fixed(1e3 * r.apply_seconds, 1),
                                    Fixed(1e3 * r.apply_first_seconds, 1),
                                    std::to_string(r.span.median),
                                    std::to_string(r.span.p90),
                                    Fixed(1e3 * r.median_sweep, 3),
                                    Fixed(r.median_total, 3),
                                    OrDash(r.speedup_vs_ori1, 3),
                                    OrDash(100 * r.gain_vs_bfs, 1)};
    for (const std::string& e : events) {
      const auto it = std::find(r.counter_events.begin(), r.counter_events.end(), e);
      row.push_back(it == r.counter_events.end()
                        ? ""
                        : Fixed(r.counter_medians[it - r.counter_events.begin()], 0));
    }
    t.AddRow(row);
  }
  return t;
}

CounterNote ProbeCounters(const std::vector<std::string>& events) {
  const PapiCounters probe(events, 1);
  return {probe.available(), probe.reason()};
}

Table CompareSummaryTable(const std::vector<CompareRow>& rows) {
  // Per mesh, the median totals by (ordering, threads); then means over meshes.
  std::map<std::pair<std::string, std::string>, double> t;  // (mesh, ordering@threads)
  auto key = [](const std::string& o, int p) { return o + "@" + std::to_string(p); };
  std::vector<std::pair<std::string, int>> cells;
  for (const CompareRow& r : rows) {
    t[{r.mesh, key(r.ordering, r.threads)}] = r.median_total;
    if (std::find(cells.begin(), cells.end(), std::make_pair(r.ordering, r.threads)) == cells.end())
      cells.emplace_back(r.ordering, r.threads);
  }
  std::vector<std::string> meshes;
  for (const CompareRow& r : rows)
    if (std::find(meshes.begin(), meshes.end(), r.mesh) == meshes.end()) meshes.push_back(r.mesh);
  Table out({"ordering", "threads", "meshes", "speedup_vs_ori1", "T_ori/T", "T_bfs/T",
             "gain_vs_ori_%", "gain_vs_bfs_%"});
  for (const auto& [ord, p] : cells) {
    double speed = 0, vs_ori = 0, vs_bfs = 0, g_ori = 0, g_bfs = 0;
    int n_speed = 0, n_ori = 0, n_bfs = 0;
    for (const std::string& m : meshes) {
      const auto self = t.find({m, key(ord, p)});
      if (self == t.end()) continue;
      const double T = self->second;
      if (auto o1 = t.find({m, key("ori", 1)}); o1 != t.end()) speed += o1->second / T, ++n_speed;
      if (auto op = t.find({m, key("ori", p)}); op != t.end())
        vs_ori += op->second / T, g_ori += (op->second - T) / op->second, ++n_ori;
      if (auto bp = t.find({m, key("bfs", p)}); bp != t.end())
        vs_bfs += bp->second / T, g_bfs += (bp->second - T) / bp->second, ++n_bfs;
    }
    auto mean = [](double s, int n, double scale) {
      return n ? OrDash(scale * s / n, 3) : std::string();
    };
    out.AddRow({ord, std::to_string(p), std::to_string(meshes.size()), mean(speed, n_speed, 1),
                mean(vs_ori, n_ori, 1), mean(vs_bfs, n_bfs, 1), mean(g_ori, n_ori, 100),
                mean(g_bfs, n_bfs, 100)});
  }
  return out;
}

std::string CompareJson(const std::vector<CompareRow>& rows) {
  std::string s = "[";
  for (size_t i = 0; i < rows.size(); ++i) {
    const CompareRow& r = rows[i];
    auto list = [](const auto& v) {
      std::string o = "[";
      for (size_t k = 0; k < v.size(); ++k) o += (k ? ", " : "") + JsonNumber(double(v[k]));
      return o + "]";
    };
    s += std::string(i ? ",\n    " : "\n    ") + "{\"mesh\": " + JsonString(r.mesh) +
         ", \"ordering\": " + JsonString(r.ordering) +
         ", \"threads\": " + std::to_string(r.threads) +
         ", \"vertices\": " + std::to_string(r.vertices) +
         ", \"triangles\": " + std::to_string(r.triangles) +
         ", \"order_seconds\": " + JsonNumber(r.order_seconds) +
         ", \"apply_seconds\": " + JsonNumber(r.apply_seconds) +
         ", \"apply_first_seconds\": " + JsonNumber(r.apply_first_seconds) +
         ", \"edge_span\": {\"median\": " + std::to_string(r.span.median) +
         ", \"p90\": " + std::to_string(r.span.p90) + ", \"p99\": " + std::to_string(r.span.p99) +
         ", \"max\": " + std::to_string(r.span.max) + ", \"mean\": " + JsonNumber(r.span.mean) +
         "}" + ", \"sweeps\": " + list(r.sweeps) + ", \"total_seconds\": " + list(r.total_seconds) +
         ", \"median_total_seconds\": " + JsonNumber(r.median_total) +
         ", \"median_seconds_per_sweep\": " + JsonNumber(r.median_sweep) +
         ", \"final_quality\": " + JsonNumber(r.final_quality) +
         ", \"speedup_vs_ori1\": " + JsonNumber(r.speedup_vs_ori1) +
         ", \"gain_vs_bfs\": " + JsonNumber(r.gain_vs_bfs) + ", \"counters\": " +
         [&] {
           if (r.counter_events.empty()) return std::string("null");
           std::string c = "{";
           for (size_t e = 0; e < r.counter_events.size(); ++e) {
             std::vector<long long> per;
             for (const auto& round : r.counters) per.push_back(round[e]);
             c += std::string(e ? ", " : "") + JsonString(r.counter_events[e]) +
                  ": {\"median\": " + JsonNumber(r.counter_medians[e]) +
                  ", \"per_round\": " + list(per) + "}";
           }
           return c + "}";
         }() +
         "}";
  }
  return s + "\n  ]";
}

}  // namespace meshreuse
