// Shared CLI helpers; see common.h.
#include "cli/common.h"

#include <unistd.h>

#include <boost/program_options/errors.hpp>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/commands.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "reports/run_info.h"
#include "reports/table.h"

namespace meshreuse::cli {

Mesh LoadMesh(const std::string& path, const Progress& progress) {
  progress.Say("reading " + path);
  std::vector<std::string> warnings;
  Mesh m = ReadMesh(path, &warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "meshreuse: warning: %s\n", w.c_str());
  progress.Say("read " + Grouped(m.NumVertices()) + " vertices, " + Grouped(m.NumTriangles()) +
               " triangles");
  return m;
}

void WriteText(const std::string& path, const std::string& text) {
  WriteAtomically(path, [&](std::FILE* f) { std::fputs(text.c_str(), f); });
}

std::vector<std::string> SplitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

void CheckOrderings(const std::vector<std::string>& specs) {
  if (specs.empty()) throw boost::program_options::error("no ordering given");
  for (const std::string& s : specs) try {
      CheckOrderingSpec(s);
    } catch (const std::invalid_argument& e) {
      throw boost::program_options::error(e.what());
    }
}

std::string RunJsonHeader(const std::string& tool) {
  return "  \"tool\": " + JsonString(tool) +
         ",\n  \"command\": " + CommandLineJson(FullCommandLine()) +
         ",\n  \"git_revision\": " + JsonString(GitRevision()) + ",\n  \"build\": " + BuildJson() +
         ",\n  \"time_utc\": " + JsonString(UtcTimestamp()) + ",\n  \"machine\": " + MachineJson() +
         ",\n";
}

bool IsMesh(const std::string& p) {
  auto ends = [&](const std::string& x) {
    return p.size() >= x.size() && p.compare(p.size() - x.size(), x.size(), x) == 0;
  };
  return ends(".node") || ends(".ele") || ends(".msh") || std::filesystem::exists(p + ".node");
}

void AddTriangleOrderOption(po::options_description& desc, std::string* value) {
  desc.add_options()("triangle-order", po::value(value)->default_value("sorted"),
                     "sorted: triangles follow the new vertex order (every ordering alike, ori "
                     "too); file: the file's triangle order (with ori: the file as is, the "
                     "paper's ORI)");
}

TriangleOrder TriangleOrderOption(const std::string& value) {
  try {
    return ParseTriangleOrder(value);
  } catch (const std::invalid_argument& e) {
    throw po::error(e.what());
  }
}

Mesh LayOut(const std::string& path, const std::string& ordering, uint64_t seed,
            TriangleOrder triangles, const Progress& progress) {
  Mesh m = LoadMesh(path, progress);
  if (ordering == "ori" && triangles == TriangleOrder::kFile) return m;
  progress.Say("laying out in " + ordering + " order, triangles " + TriangleOrderName(triangles));
  ApplyPermutationInPlace(&m, ComputeOrdering(ordering, m, seed), triangles);
  return m;
}

}  // namespace meshreuse::cli

namespace meshreuse::cli {

void CheckWritable(const std::string& path) {
  const std::filesystem::path p(path);
  const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw po::error("cannot write '" + path + "': '" + dir.string() + "' is not a folder");
  if (std::filesystem::is_directory(p, ec))
    throw po::error("cannot write '" + path + "': it is a folder");
}

void CheckOneFormat(const po::variables_map& vm) {
  std::string given;
  int n = 0;
  for (const char* f : {"json", "csv", "markdown"})
    if (vm.count(f)) given += std::string(n++ ? " and --" : "--") + f;
  if (n > 1) throw po::error(given + " exclude each other: give one");
}

void PrepareOutDir(const std::string& dir, bool must_be_empty) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::path p = fs::path(dir); !p.empty(); p = p.parent_path()) {
    if (fs::exists(p, ec)) {
      if (!fs::is_directory(p, ec))
        throw po::error("cannot write to '" + dir + "': '" + p.string() + "' is not a folder");
      break;
    }
    if (p == p.parent_path()) break;
  }
  fs::create_directories(dir, ec);
  if (ec) throw po::error("cannot make the folder '" + dir + "': " + ec.message());
  if (::access(dir.c_str(), W_OK) != 0)
    throw po::error("cannot write to the folder '" + dir + "': permission denied");
  if (must_be_empty && !fs::is_empty(dir, ec))
    throw po::error("the folder '" + dir +
                    "' is not empty (a previous run's files would mix "
                    "with this one's): give a new folder");
}

std::vector<int> ParseThreadList(const std::string& s) {
  std::vector<int> out;
  for (const std::string& t : SplitList(s)) {
    size_t used = 0;
    int v = 0;
    try {
      v = std::stoi(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != t.size()) throw po::error("--threads takes numbers, found '" + t + "'");
    if (v < 1 || v > 1024) throw po::error("--threads must be between 1 and 1024");
    out.push_back(v);
  }
  if (out.empty()) throw po::error("--threads is empty");
  return out;
}

}  // namespace meshreuse::cli
