// What the report measured, handed to every output builder (report_outputs.h): the meshes, the
// first sweep's histograms and Figure 1's bins, the profile rows, the validation (Table 3, miss
// rates) and the timed rows. Builders only read it.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/multicore_sim.h"
#include "analysis/reuse_histogram.h"
#include "core/table.h"
#include "reports/compare.h"
#include "reports/kernel_runs.h"
#include "reports/machine_runs.h"
#include "reports/measured.h"
#include "reports/report.h"
#include "reports/speedup.h"
#include "reports/validation.h"

namespace meshreuse {

struct ReportMesh {
  std::string path, name;  // name: the file's stem, how every table names the mesh
  double weight = 0;       // its file's bytes: the progress estimate's unit
  int32_t vertices = 0, triangles = 0, interior = 0;
};

struct FirstSweep {  // Table 2 and the histogram of one mesh x ordering
  std::string mesh, ordering;
  int32_t vertices = 0;
  ReuseHistogram hist;
};

struct Figure1Data {
  std::string ordering;
  uint64_t accesses = 0, cold = 0;
  double mean = 0, model_l1_rate = 0;
  std::vector<std::vector<uint64_t>> bins;  // [time bin][distance bin]; the last: cold
};

struct ReportData {
  ReportConfig cfg;
  std::vector<std::string> orderings;  // the configured orderings' labels, as tables name them
  std::vector<ReportMesh> meshes;
  std::vector<FirstSweep> first;                    // the configured orderings only
  std::vector<Figure1Data> fig1;                    // in the configured panel order
  Table profile{{}};                                // ReuseAnalysis::ProfileColumns(), or empty
  Table drawing{{}}, smoothing{{}}, positions{{}};  // pictures.h
  std::vector<std::string> notes;                   // said at the top of the results README
  Table histogram{{}};                              // ReuseAnalysis::HistogramColumns()
  std::vector<OrderingValidation> validation;
  std::vector<CompareRow> timing;            // empty without timing
  std::vector<MachineRun> machine;           // empty without the many-core part
  std::optional<MeasuredSpeedups> measured;  // --measured
  std::vector<KernelRun> kernels;            // the kernels part, empty without it
  // The run of (mesh, ordering, placement, threads, prefetch), or nullptr.
  const MachineRun* Machine(const std::string& mesh, const std::string& ordering,
                            const std::string& placement, int threads, bool prefetch = false) const;
  Noise noise;  // the machine while it timed
  // Per cache level, "measured" or "simulated"; and the counters' line for run.json and README.
  std::map<std::string, std::string> sources;
  std::string counters;

  // The timed row of a mesh (by name) x ordering x thread count, or nullptr.
  const CompareRow* Time(const std::string& mesh, const std::string& ordering, int threads) const;
  const ReportMesh* Mesh(const std::string& name) const;
  bool Has(const std::string& ordering) const;  // among the configured orderings (labels)
};

}  // namespace meshreuse

namespace meshreuse::report {

// Cell helpers shared by the builders: integers in full; fixed decimals with no "-0.0"; empty (a
// missing value) for NaN.
inline std::string Int(uint64_t v) { return std::to_string(v); }
std::string Num(double v, int decimals);
inline std::string Pct(double v) { return Num(v, 1); }
double Ratio(double a, double b);           // a / b, NaN unless b > 0
double Mean(const std::vector<double>& v);  // of the finite values, NaN when none

// The last traced sweep of a validation run at level i, summed over threads (the miss rates use
// it: warm caches, as in the paper's runs to convergence): its misses (counters, which cover all
// sweeps, divided by the sweep count), and the stats and the sweep's accesses into `sum`,
// `line_accesses`.
double LastSweepMisses(const OrderingValidation& v, size_t level, LevelStats* sum,
                       uint64_t* line_accesses);

// "faster", "slower", "not distinguishable" for a speedup (a gain with `gain`); "" when unknown.
std::string VerdictCell(const Spread& s, bool gain = false);

}  // namespace meshreuse::report

namespace meshreuse::report {

// Distance bins of Figure 1: 0, then four per power of two (bin b >= 1 holds
// [2^((b-1)/4), 2^(b/4)) rounded to integers).
constexpr int kDistanceBinsPerOctave = 4;
int DistanceBin(uint64_t d);
uint64_t DistanceBinLo(int b);

}  // namespace meshreuse::report
