// Shared CLI helpers; see common.h.
#include "cli/common.h"

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
         ",\n  \"git_revision\": " + JsonString(GitRevision()) +
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

}  // namespace meshreuse::cli
