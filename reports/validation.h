// The model's validation (meshreuse validate, DESIGN.md "Miss model", "Set-associative
// simulation"): for one mesh and each ordering, K traced sweeps streamed at once into the exact
// reuse-distance analysis (element and line) and the set-associative simulator, plus -- where PAPI
// counts here -- an untraced run of the same K sweeps with hardware counters. Per cache level, side
// by side: the fully associative model on elements (the paper's 66-byte nodes) and on lines, the
// simulation, the counters, their ratios, miss rates and the equation-2 cost. Then the paper's
// Table 3: misses per level (measured where counters exist, else simulated, and labelled so) and
// the inverse model's capacity for them, in elements and in lines.
// Sums over thread streams (each stream has private caches, as in the analyzer).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/cache_model.h"
#include "analysis/cache_sim.h"
#include "analysis/reuse_histogram.h"
#include "core/mesh.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "core/table.h"
#include "reports/output.h"
#include "reports/run_info.h"
#include "reports/stream_source.h"

namespace meshreuse {

struct ValidationConfig : StreamSource {
  // StreamSource: the mesh (inputs[0]; RunValidation takes it read), orderings, seed, sweeps
  // (default 2), threads, mode, triangle order.
  ValidationConfig() { orderings = {"ori", "bfs", "rdr"}, iterations = 2; }
  std::string mesh_name;  // for the tables
  CacheSpec cache;        // levels with associativity (the simulator needs it), latencies
  uint32_t element_bytes = 66, line_bytes = 64;
  // PAPI events for the levels, in level order (empty: no counters). Missing ones are simulated.
  std::vector<std::string> counter_events = {"PAPI_L1_DCM", "PAPI_L2_DCM", "PAPI_L3_TCM"};
  bool exclude_cold = false;  // Table 3's inverse model (cache_model.h)
};

struct LevelValidation {
  CacheLevel level;
  uint64_t element_capacity = 0, line_capacity = 0;  // of the model
  uint64_t model_element = 0, model_line = 0;        // fully associative LRU misses
  LevelStats simulated;
  bool measured = false;  // counters counted this level
  double counter = 0;     // their misses (sum over threads)
  // Table 3: the misses inverted (counter if measured, else simulated) and the capacities.
  uint64_t table3_misses = 0;
  uint64_t capacity_elements = 0, capacity_lines = 0;
  // No ordering can miss less (analysis/sweep_footprint.h): the sweeps' lines less what levels
  // 1..this one can hold between sweeps.
  uint64_t floor = 0;
};

struct OrderingValidation {
  std::string mesh, ordering;
  int32_t vertices = 0;
  int iterations = 0, threads = 1;
  uint64_t element_accesses = 0, line_accesses = 0, element_cold = 0, line_cold = 0;
  std::vector<std::vector<uint64_t>> sweep_lines;  // per thread, per sweep: distinct lines
  // Quantiles 0.5 and 0.9 of the line distances of every traced access, all streams together
  // (ReuseHistogram::Quantile; none without a finite distance): the kernels table's Laplacian
  // rows take them from here (reports/kernel_runs.h).
  std::optional<uint64_t> line_q50, line_q90;
  std::vector<LevelValidation> levels;
  std::vector<std::vector<std::vector<LevelStats>>> sweeps;  // simulated: [sweep][thread][level]
  // Equation 2 on the line model's and the simulator's misses; nullopt without latencies.
  std::optional<CostRange> cost_model, cost_simulated;
  std::string counters;  // "measured (PAPI ...)" or why not
};

// UsageError for what cannot run: orderings, levels without ways, the geometry, thread counts.
void CheckValidationConfig(const ValidationConfig& cfg);

std::vector<OrderingValidation> RunValidation(
    const Mesh& base, const ValidationConfig& cfg,
    const std::function<void(const std::string&)>& progress = {});

// One row per ordering x level: accesses reaching the level, misses of the element model, the line
// model, the simulator and the counters, cold misses, excess (simulated - cold), the ratios
// model_line / simulated and simulated / counter, local and global miss rates; the
// layout-independent floor on misses and the simulated misses above it.
Table ValidationTable(const std::vector<OrderingValidation>& r);
// Simulated misses per sweep: one row per ordering x sweep x level (sum over threads).
Table ValidationSweepTable(const std::vector<OrderingValidation>& r);
// The paper's Table 3: per ordering, misses per level (x10^3, per sweep) and the capacity the
// inverse model gives for them (x10^3 elements; lines too), with the paper's values beside ours
// for its nine meshes (carabiner ... wrench at the paper's size, within 5% of its vertex count;
// ori/bfs/rdr), "-" elsewhere.
Table Table3(const std::vector<OrderingValidation>& r);
// Equation 2 on the line model's and on the simulator's misses per ordering (empty cells without
// latencies).
Table ValidationCostTable(const std::vector<OrderingValidation>& r);
Json ValidationConfigJson(const ValidationConfig& cfg);
// What `validate` prints and writes: the validation, cost and Table 3 tables with Table 3's notes
// (--csv: the validation table; --json: the three as one object), and under --out validate.{csv,
// md,json}, cost.csv, table3.{csv,md}, sweeps.csv and run.json.
RunOutput ValidationOutput(const std::vector<OrderingValidation>& r, const ValidationConfig& cfg);
// Notes for the tables: where an inverse capacity is infinite, why.
std::vector<std::string> Table3Notes(const std::vector<OrderingValidation>& r, bool exclude_cold);

}  // namespace meshreuse
