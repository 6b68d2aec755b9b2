// Speedups measured elsewhere (`report --measured FILE.csv`): the compare.csv that `meshreuse
// compare --out DIR` writes on another machine (a 16-core node, say), read back so that the
// report can draw those points beside the many-core prediction, past this machine's cores. Per
// ordering x thread count the mean over the file's meshes of Speedup(p) = T_ori(1) / T_ord(p)
// (its speedup_vs_ori1 column: every mesh's own reference); the machine named from the run.json
// beside the file when there is one (its CPU and cores), else by the file's path.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace meshreuse {

struct MeasuredSpeedups {
  std::string source;   // the file
  std::string machine;  // "Intel Xeon ..., 16 cores", or the file's path
  // (ordering, threads) -> the mean speedup over the meshes that have it, and how many.
  std::map<std::pair<std::string, int>, std::pair<double, int>> mean;
};

// Reads FILE (InputError naming the file, line and problem: not a compare.csv, a cell that is not
// a number). A quoted cell (compare quotes a path with a comma) is read as compare wrote it.
MeasuredSpeedups ReadMeasured(const std::string& path);

}  // namespace meshreuse
