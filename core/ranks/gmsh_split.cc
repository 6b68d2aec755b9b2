// Gmsh's partitioned split files read as one mesh; see gmsh_split.h.
#include "core/ranks/gmsh_split.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/output_file.h"

namespace meshreuse {

namespace {

// PREFIX_ and K of PREFIX_K.msh; false when the name has another shape.
bool SplitName(const std::string& path, std::string* prefix, int64_t* k) {
  if (path.size() < 7 || path.compare(path.size() - 4, 4, ".msh") != 0) return false;
  const size_t end = path.size() - 4;
  size_t b = end;
  while (b > 0 && path[b - 1] >= '0' && path[b - 1] <= '9') --b;
  if (b == end || b == 0 || path[b - 1] != '_' || end - b > 9 || path[b] == '0') return false;
  *prefix = path.substr(0, b);
  *k = std::stoll(path.substr(b, end - b));
  return true;
}

// The number after "$PartitionedEntities" in an ASCII file (-1: no such section in the file's
// first 16 MiB, where Gmsh writes it before the nodes, or a binary file, whose parts are then
// counted by their files alone). Reads at most 16 MiB whatever the file.
int64_t DeclaredParts(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(size_t{16} << 20, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const size_t fmt = head.find("$MeshFormat");
  if (fmt != std::string::npos) {  // "4.1 1 8": binary, its count a size_t (not checked)
    const size_t eol = head.find('\n', fmt);
    if (eol != std::string::npos && head.compare(eol + 1, 5, "4.1 1") == 0) return -1;
  }
  const size_t at = head.find("\n$PartitionedEntities");
  if (at == std::string::npos) return -1;
  const size_t num = head.find_first_not_of("\r\n", at + 22);
  if (num == std::string::npos || head[num] < '0' || head[num] > '9')
    throw InputError(path, 0, "$PartitionedEntities: no part count");
  int64_t parts = 0;
  for (size_t k = num; k < head.size() && head[k] >= '0' && head[k] <= '9' && parts < INT32_MAX;
       ++k)
    parts = parts * 10 + (head[k] - '0');
  return parts;
}

}  // namespace

bool IsGmshSplitPath(const std::string& path) {
  std::string prefix;
  int64_t k = 0;
  return SplitName(path, &prefix, &k) && FileExists(prefix + "1.msh");
}

GmshSplit ReadGmshSplit(const std::string& path) {
  std::string prefix;
  int64_t k = 0;
  if (!SplitName(path, &prefix, &k))
    throw InputError(path, 0, "not a part of a Gmsh split set (expected PREFIX_K.msh, K >= 1)");
  GmshSplit s;
  // The parts the named file declares ($PartitionedEntities) are the set: each must exist, and a
  // file past them (an older run's) is left out, said in a warning. Without a declaration the set
  // is the files PREFIX_1.msh, PREFIX_2.msh, ... that exist in a row.
  const int64_t declared = DeclaredParts(path);
  if (declared > INT32_MAX) throw InputError(path, 0, "$PartitionedEntities: too many parts");
  if (declared >= 1) {
    for (int64_t i = 1; i <= declared; ++i) {
      const std::string f = prefix + std::to_string(i) + ".msh";
      if (!FileExists(f))
        throw InputError(f, 0,
                         "cannot open: part " + std::to_string(i) + " of the " +
                             std::to_string(declared) + " that " + path +
                             " declares ($PartitionedEntities) is missing");
      s.files.push_back(f);
    }
    for (int64_t i = declared + 1; FileExists(prefix + std::to_string(i) + ".msh"); ++i)
      s.raw.warnings.push_back(prefix + std::to_string(i) + ".msh: left out: " + path +
                               " declares " + std::to_string(declared) +
                               " parts (a file of an older split?)");
  } else {
    for (int64_t i = 1; FileExists(prefix + std::to_string(i) + ".msh"); ++i) {
      if (i > INT32_MAX) throw InputError(path, 0, "too many part files");
      s.files.push_back(prefix + std::to_string(i) + ".msh");
    }
  }
  if (s.files.empty() || k > static_cast<int64_t>(s.files.size()))
    throw InputError(prefix + std::to_string(s.files.size() + 1) + ".msh", 0,
                     "cannot open: the split set " + prefix + "K.msh has no part " +
                         std::to_string(s.files.size() + 1));
  s.parts = static_cast<int32_t>(s.files.size());
  for (const std::string& f : s.files) {
    const int64_t d = DeclaredParts(f);
    if (d >= 0 && d != s.parts)
      throw InputError(
          f, 0,
          "$PartitionedEntities declares " + std::to_string(d) + " parts, but " +
              (declared >= 1 ? path + " declares " + std::to_string(s.parts)
                             : std::to_string(s.parts) + " part files " + prefix + "1.msh.." +
                                   std::to_string(s.parts) + ".msh exist"));
  }
  // Every part's nodes by tag; coordinates must agree where parts share a node.
  struct Node {
    int64_t tag;
    double x, y;
    int32_t first_part;
  };
  std::vector<Node> nodes;
  std::unordered_map<int64_t, size_t> at;  // tag -> index in nodes
  std::vector<RawMesh> raws;
  for (int32_t p = 0; p < s.parts; ++p) {
    raws.push_back(ReadGmsh(s.files[p]));
    const RawMesh& r = raws.back();
    for (const std::string& w : r.warnings) s.raw.warnings.push_back(w);
    for (int64_t v = 0; v < r.vertex_tag.size(); ++v) {
      const int64_t tag = r.vertex_tag.At(v);
      const double x = r.xy[2 * v], y = r.xy[2 * v + 1];
      const auto [it, fresh] = at.emplace(tag, nodes.size());
      if (fresh) {
        nodes.push_back({tag, x, y, p});
      } else if (std::memcmp(&nodes[it->second].x, &x, 8) != 0 ||
                 std::memcmp(&nodes[it->second].y, &y, 8) != 0) {
        throw InputError(s.files[p], r.vertex_line.At(v),
                         "node " + std::to_string(tag) + " has other coordinates than in " +
                             s.files[nodes[it->second].first_part]);
      }
    }
  }
  // Vertices in increasing tag order.
  std::vector<size_t> order(nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return nodes[a].tag < nodes[b].tag; });
  std::vector<int32_t> id(nodes.size());
  s.raw.xy.resize(2 * nodes.size());
  for (size_t i = 0; i < order.size(); ++i) {
    const Node& n = nodes[order[i]];
    id[order[i]] = static_cast<int32_t>(i);
    s.raw.xy[2 * i] = n.x, s.raw.xy[2 * i + 1] = n.y;
    s.raw.vertex_tag.Push(n.tag);
  }
  s.raw.vertex_file = s.raw.triangle_file = prefix + "K.msh";
  // Triangles in increasing element tag (the unsplit file's order); an element tag or a triangle
  // (as a set of corners) in two parts is a ghost copy.
  struct Tri {
    int64_t tag;
    std::array<int32_t, 3> c;
    int32_t part;
    int64_t line;
  };
  std::vector<Tri> tris;
  s.part.assign(nodes.size(), INT32_MAX);
  std::map<std::array<int32_t, 3>, int32_t> seen;  // sorted corners -> part
  for (int32_t p = 0; p < s.parts; ++p) {
    const RawMesh& r = raws[p];
    for (size_t t = 0; t < r.tri.size() / 3; ++t) {
      Tri x{r.triangle_tag.At(static_cast<int64_t>(t)),
            {},
            p,
            r.triangle_line.At(static_cast<int64_t>(t))};
      for (int j = 0; j < 3; ++j) x.c[j] = id[at.at(r.vertex_tag.At(r.tri[3 * t + j]))];
      std::array<int32_t, 3> key = x.c;
      std::sort(key.begin(), key.end());
      const auto [it, fresh] = seen.emplace(key, p);
      if (!fresh && it->second != p)
        throw InputError(s.files[p], x.line,
                         "a triangle also in " + s.files[it->second] +
                             ": ghost elements (gmsh -part_ghosts) are not read; split without "
                             "them");
      for (int j = 0; j < 3; ++j) s.part[x.c[j]] = std::min(s.part[x.c[j]], p);
      tris.push_back(x);
    }
  }
  std::stable_sort(tris.begin(), tris.end(),
                   [](const Tri& a, const Tri& b) { return a.tag < b.tag; });
  for (size_t t = 0; t < tris.size(); ++t) {
    if (t && tris[t].tag == tris[t - 1].tag)
      throw InputError(s.files[tris[t].part], tris[t].line,
                       "element " + std::to_string(tris[t].tag) + " is also in " +
                           s.files[tris[t - 1].part] + " (ghost elements are not read)");
    s.raw.tri.insert(s.raw.tri.end(), tris[t].c.begin(), tris[t].c.end());
    s.raw.triangle_tag.Push(tris[t].tag);
  }
  return s;
}

std::vector<std::string> WriteGmshSplit(const Mesh& m, const std::vector<int32_t>& part,
                                        int32_t parts, const std::string& prefix) {
  if (static_cast<int64_t>(part.size()) != m.NumVertices() || parts < 1)
    throw std::invalid_argument("WriteGmshSplit: a part per vertex and at least one part");
  const int32_t nt = m.NumTriangles();
  std::vector<std::vector<int32_t>> tris(parts);  // per part, increasing triangle id
  for (int32_t t = 0; t < nt; ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    const int32_t p = part[std::min(c[0], std::min(c[1], c[2]))];
    if (p < 0 || p >= parts) throw std::invalid_argument("WriteGmshSplit: a part out of range");
    tris[p].push_back(t);
  }
  std::vector<std::pair<std::string, std::function<void(std::FILE*)>>> files;
  std::vector<std::string> names;
  for (int32_t p = 0; p < parts; ++p) {
    names.push_back(prefix + std::to_string(p + 1) + ".msh");
    files.emplace_back(names.back(), [&, p](std::FILE* f) {
      std::vector<int32_t> nodes;
      for (int32_t t : tris[p])
        for (int k = 0; k < 3; ++k) nodes.push_back(m.tri[3 * int64_t{t} + k]);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      double lo[2] = {0, 0}, hi[2] = {0, 0};
      for (size_t i = 0; i < nodes.size(); ++i)
        for (int d = 0; d < 2; ++d) {
          const double x = m.xy[2 * int64_t{nodes[i]} + d];
          lo[d] = i ? std::min(lo[d], x) : x;
          hi[d] = i ? std::max(hi[d], x) : x;
        }
      std::fprintf(f, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
      // The model: one surface (entity 1) without bounding curves; part p + 1 is its piece.
      std::fprintf(f, "$Entities\n0 0 1 0\n1 %.17g %.17g 0 %.17g %.17g 0 0 0\n$EndEntities\n",
                   lo[0], lo[1], hi[0], hi[1]);
      // Part p + 1's surface: entity p + 2 (tags apart from the model's surface 1).
      std::fprintf(f,
                   "$PartitionedEntities\n%d\n0\n0 0 1 0\n%d 2 1 1 %d %.17g %.17g 0 %.17g %.17g 0 "
                   "0 0\n$EndPartitionedEntities\n",
                   parts, p + 2, p + 1, lo[0], lo[1], hi[0], hi[1]);
      const size_t n = nodes.size();
      std::fprintf(f, "$Nodes\n%d %zu %d %d\n", n ? 1 : 0, n, n ? nodes.front() + 1 : 0,
                   n ? nodes.back() + 1 : 0);
      if (n) {
        std::fprintf(f, "2 %d 0 %zu\n", p + 2, n);
        for (int32_t v : nodes) std::fprintf(f, "%d\n", v + 1);
        for (int32_t v : nodes)
          std::fprintf(f, "%.17g %.17g 0\n", m.xy[2 * int64_t{v}], m.xy[2 * int64_t{v} + 1]);
      }
      std::fprintf(f, "$EndNodes\n");
      const std::vector<int32_t>& ts = tris[p];
      std::fprintf(f, "$Elements\n%d %zu %d %d\n", ts.empty() ? 0 : 1, ts.size(),
                   ts.empty() ? 0 : ts.front() + 1, ts.empty() ? 0 : ts.back() + 1);
      if (!ts.empty()) {
        std::fprintf(f, "2 %d 2 %zu\n", p + 2, ts.size());
        for (int32_t t : ts)
          std::fprintf(f, "%d %d %d %d\n", t + 1, m.tri[3 * int64_t{t}] + 1,
                       m.tri[3 * int64_t{t} + 1] + 1, m.tri[3 * int64_t{t} + 2] + 1);
      }
      std::fprintf(f, "$EndElements\n");
    });
  }
  WriteAtomicallyAll(files);
  return names;
}

}  // namespace meshreuse
