// ReadMeasured; see measured.h.
#include "reports/measured.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/text_file.h"

namespace meshreuse {

namespace {

// One CSV line's cells (RFC 4180 quoting, as core/table.cc writes it).
std::vector<std::string> Cells(std::string_view line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        out.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

std::string MachineBeside(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const std::string run =
      (slash == std::string::npos ? "" : path.substr(0, slash + 1)) + "run.json";
  std::ifstream f(run);
  if (!f) return path;
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.contains("machine") || !j["machine"].is_object()) return path;
  const nlohmann::json& m = j["machine"];
  std::string s = m.value("cpu", std::string("?"));
  if (m.contains("cores") && m["cores"].is_number_integer())
    s += ", " + std::to_string(m["cores"].get<int>()) + " cores";
  return s + " (" + path + ")";
}

}  // namespace

MeasuredSpeedups ReadMeasured(const std::string& path) {
  TextFile f(path, '\0');
  MeasuredSpeedups m;
  m.source = path;
  std::string_view line;
  if (!f.NextDataLine(&line))
    f.Fail("empty: expected the compare.csv of `meshreuse compare --out`");
  const std::vector<std::string> head = Cells(line);
  auto column = [&](const char* name) {
    for (size_t i = 0; i < head.size(); ++i)
      if (head[i] == name) return i;
    f.Fail(std::string("no column ") + name +
           ": expected the compare.csv of `meshreuse compare --out` (mesh, ordering, threads, "
           "speedup_vs_ori1, ...)");
  };
  const size_t c_mesh = column("mesh"), c_ord = column("ordering"), c_threads = column("threads"),
               c_speedup = column("speedup_vs_ori1");
  std::map<std::pair<std::string, int>, std::pair<double, int>> sum;
  while (f.NextDataLine(&line)) {
    const std::vector<std::string> cells = Cells(line);
    if (cells.size() != head.size())
      f.Fail(std::to_string(cells.size()) + " cells where the header has " +
             std::to_string(head.size()));
    if (cells[c_mesh].empty()) f.Fail("no mesh");
    const int64_t threads = f.ParseInt(cells[c_threads], "a thread count");
    if (threads < 1 || threads > 1 << 20) f.Fail("a thread count out of range");
    if (cells[c_speedup].empty()) continue;  // no reference (ori x1) in that run
    const double s = f.ParseDouble(cells[c_speedup], "a speedup");
    if (!(s > 0)) f.Fail("a speedup that is not positive");
    auto& [total, n] = sum[{cells[c_ord], static_cast<int>(threads)}];
    total += s;
    ++n;
  }
  if (sum.empty()) f.Fail("no speedups (compare ran without ori on one thread?)");
  for (const auto& [key, v] : sum) m.mean[key] = {v.first / v.second, v.second};
  m.machine = MachineBeside(path);
  return m;
}

}  // namespace meshreuse
