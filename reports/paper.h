// The paper's published numbers (Aupy, Park, Raghavan, "Locality-Aware Laplacian Mesh Smoothing"),
// so every table can show them beside ours. Values are copied from the paper's text and tables;
// its figures are images without numbers, so only what the text states is here (the averaged
// speedups, miss reductions and gains). A paper value is shown beside ours only for a mesh of the
// paper's name within 5% of its vertex count (a 20,000-vertex carabiner is not the paper's).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace meshreuse::paper {

struct MeshSize {
  std::string label;  // M1..M9
  int32_t vertices, triangles;
};
std::optional<MeshSize> Table1(const std::string& name);

// Table 2: reuse-distance quantiles 50/75/90/100% of the first sweep, and its accesses (one
// figure per mesh in the paper: the same for every ordering).
struct Quantiles {
  std::array<uint64_t, 4> q;
  uint64_t accesses;
};
std::optional<Quantiles> Table2(const std::string& name, const std::string& ordering);

// Table 3 (x10^3): misses L1, L2, L3, then the inverse model's capacities L1, L2, L3 (elements).
std::optional<std::array<double, 6>> Table3(const std::string& name, const std::string& ordering);

// Figure 1 (ocean, first sweep): average reuse distance, L1 miss rate (%) and execution time (s).
struct Figure1Caption {
  double mean_distance, l1_miss_percent, seconds;
};
std::optional<Figure1Caption> Figure1(const std::string& ordering);  // random, ori, bfs

// Text: RDR's average one-core speedup over ORI and BFS; its fewer misses per level (%) than ORI
// and BFS on one core; the reordering's cost in ORI sweeps.
constexpr double kRdrSpeedupVsOri = 1.39, kRdrSpeedupVsBfs = 1.19;
constexpr std::array<double, 3> kRdrFewerMissesVsOri = {25, 71, 84};
constexpr std::array<double, 3> kRdrFewerMissesVsBfs = {6.3, 51, 65};
constexpr double kRdrCostSweeps = 1.0;
// Gain of RDR over ORI is 20-30% depending on the core count, 10-30% over BFS (Figure 8's text).
constexpr std::array<double, 2> kRdrGainVsOri = {20, 30}, kRdrGainVsBfs = {10, 30};

// Within 5% of the paper's vertex count for a mesh of that name.
bool Sized(const std::string& name, int64_t vertices);

}  // namespace meshreuse::paper
