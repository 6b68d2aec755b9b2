// The paper's numbers; see paper.h. Table 1, 2 and 3 are transcribed from the paper's LaTeX source
// (../shared/paper/), Figure 1's from its sub-captions.
#include "reports/paper.h"

#include <cmath>
#include <filesystem>
#include <map>

namespace meshreuse::paper {

std::optional<MeshSize> Table1(const std::string& name) {
  static const std::map<std::string, MeshSize> t = {
      {"carabiner", {"M1", 328082, 652920}}, {"crake", {"M2", 298898, 595638}},
      {"dialog", {"M3", 306824, 611620}},    {"lake", {"M4", 375288, 747676}},
      {"riverflow", {"M5", 332699, 661615}}, {"ocean", {"M6", 392674, 783040}},
      {"stress", {"M7", 312763, 622868}},    {"valve", {"M8", 300985, 599368}},
      {"wrench", {"M9", 386757, 771097}}};
  const auto it = t.find(name);
  if (it == t.end()) return std::nullopt;
  return it->second;
}

std::optional<Quantiles> Table2(const std::string& name, const std::string& ordering) {
  using Q = std::array<uint64_t, 4>;
  static const std::map<std::string, std::pair<uint64_t, std::map<std::string, Q>>> t = {
      {"carabiner",
       {15566520,
        {{"ori", {8, 52, 1168, 1924021}},
         {"bfs", {1, 11, 99, 1923989}},
         {"rdr", {1, 4, 6, 1942}}}}},
      {"crake",
       {14226264,
        {{"ori", {8, 43, 642, 1767468}}, {"bfs", {1, 11, 80, 1767488}}, {"rdr", {1, 4, 6, 3903}}}}},
      {"dialog",
       {14614336,
        {{"ori", {7, 39, 306, 1819234}},
         {"bfs", {1, 10, 79, 1803850}},
         {"rdr", {1, 5, 11, 6198}}}}},
      {"lake",
       {17850952,
        {{"ori", {7, 38, 270, 2224176}}, {"bfs", {1, 10, 72, 2224069}}, {"rdr", {1, 4, 5, 8774}}}}},
      {"riverflow",
       {15758200,
        {{"ori", {7, 37, 1430, 1963783}},
         {"bfs", {1, 10, 69, 1969058}},
         {"rdr", {1, 4, 6, 5429}}}}},
      {"ocean",
       {18719512,
        {{"ori", {7, 38, 3866, 2312947}},
         {"bfs", {1, 10, 76, 2339305}},
         {"rdr", {1, 5, 9, 6122}}}}},
      {"stress",
       {14862888,
        {{"ori", {7, 44, 358, 1817752}}, {"bfs", {1, 10, 91, 1817758}}, {"rdr", {1, 4, 6, 4809}}}}},
      {"valve",
       {14301320,
        {{"ori", {7, 40, 646, 1780959}}, {"bfs", {1, 10, 75, 1780916}}, {"rdr", {1, 4, 6, 7256}}}}},
      {"wrench",
       {18429528,
        {{"ori", {7, 42, 376, 2290783}}, {"bfs", {1, 10, 89, 2290734}}, {"rdr", {1, 4, 6, 6487}}}}},
  };
  const auto m = t.find(name);
  if (m == t.end()) return std::nullopt;
  const auto o = m->second.second.find(ordering);
  if (o == m->second.second.end()) return std::nullopt;
  return Quantiles{o->second, m->second.first};
}

std::optional<std::array<double, 6>> Table3(const std::string& name, const std::string& ordering) {
  static const std::map<std::pair<std::string, std::string>, std::array<double, 6>> t = {
      {{"carabiner", "ori"}, {106, 50.6, 19.9, 13.2, 21.3, 330}},
      {{"carabiner", "bfs"}, {84, 30.2, 7.94, 10.2, 21.2, 1060}},
      {{"carabiner", "rdr"}, {73.9, 4.82, 0, 1.6, 1.88, 1.94}},
      {{"crake", "ori"}, {95.3, 43.4, 17.4, 24.6, 40.9, 198}},
      {{"crake", "bfs"}, {72.6, 26.7, 7.07, 18.3, 39.2, 986}},
      {{"crake", "rdr"}, {68.3, 9.3, 0, 3.4, 3.77, 3.9}},
      {{"dialog", "ori"}, {91.7, 31.9, 16.3, 59, 87.7, 108}},
      {{"dialog", "bfs"}, {74.1, 16.2, 4.55, 53.2, 89.3, 157}},
      {{"dialog", "rdr"}, {74, 14.3, 0, 5.84, 6.05, 6.2}},
      {{"lake", "ori"}, {111, 44.7, 20.7, 62.2, 95.9, 143}},
      {{"lake", "bfs"}, {89.8, 22.7, 6.72, 56.1, 96.1, 219}},
      {{"lake", "rdr"}, {94.7, 10.9, 0, 8.42, 8.65, 8.77}},
      {{"riverflow", "ori"}, {99.8, 51.4, 19.8, 30.4, 66.8, 863}},
      {{"riverflow", "bfs"}, {81.6, 31.8, 8.08, 20.3, 67.6, 1290}},
      {{"riverflow", "rdr"}, {75.4, 11.5, 0, 4.73, 5.27, 5.43}},
      {{"ocean", "ori"}, {131, 41.3, 21.9, 63.3, 300, 1050}},
      {{"ocean", "bfs"}, {102, 21, 6.57, 41.6, 770, 1830}},
      {{"ocean", "rdr"}, {89.8, 10.6, 0, 5.83, 5.99, 6.12}},
      {{"stress", "ori"}, {96.6, 54.6, 19.4, 71.5, 91.7, 130}},
      {{"stress", "bfs"}, {76.7, 35.3, 8.42, 59.1, 87.6, 137}},
      {{"stress", "rdr"}, {72.2, 12.3, 0, 4.36, 4.66, 4.81}},
      {{"valve", "ori"}, {92.6, 31.9, 16.9, 37.3, 77.6, 186}},
      {{"valve", "bfs"}, {76.3, 15.4, 5.17, 28.6, 110, 1040}},
      {{"valve", "rdr"}, {67, 10.1, 0, 6.68, 7.17, 7.26}},
      {{"wrench", "ori"}, {117, 57.1, 21.8, 75.3, 105, 148}},
      {{"wrench", "bfs"}, {93.8, 35.1, 8.38, 62.9, 103, 170}},
      {{"wrench", "rdr"}, {86, 12.7, 0, 5.69, 6.31, 6.49}},
  };
  const auto it = t.find({name, ordering});
  if (it == t.end()) return std::nullopt;
  return it->second;
}

std::optional<Figure1Caption> Figure1(const std::string& ordering) {
  if (ordering == "random") return Figure1Caption{90000, 2.18, 10.28};
  if (ordering == "ori") return Figure1Caption{4450, 0.71, 7.6};
  if (ordering == "bfs") return Figure1Caption{2910, 0.59, 6.59};
  return std::nullopt;
}

bool Sized(const std::string& name, int64_t vertices) {
  const auto t = Table1(name);
  return t && std::fabs(static_cast<double>(vertices - t->vertices)) <= 0.05 * t->vertices;
}

}  // namespace meshreuse::paper
