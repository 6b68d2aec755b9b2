// Gmsh .msh ASCII, versions 2.2 and 4.1 (binary 4.1: gmsh_binary_io.cc)
// (https://gmsh.info/doc/texinfo/gmsh.html, "MSH file format"). Only $MeshFormat, $Nodes and
// $Elements are read; other sections are skipped to their $End line. Triangles are element type 2
// (3 nodes) and 9 (6 nodes: the corners come first); other element types (points, lines, quads,
// volumes) are skipped and counted in a warning. Node tags are arbitrary positive integers and are
// mapped to 0-based ids in file order; z (and 4.1's parametric coordinates) must be numbers and are
// then ignored, as are element tags and physical tags, which must be integers. Counts are checked
// against the bytes that follow before anything is reserved for them, and all arithmetic on them is
// overflow-free, so memory follows the file. WriteGmsh writes 4.1 ASCII, which Gmsh, meshio and
// this reader read back to the same bits.
#include <algorithm>
#include <cstdio>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/input_file.h"
#include "core/mesh_io.h"
#include "core/output_file.h"
#include "core/progress.h"
#include "core/text_file.h"

namespace meshreuse {

namespace {

class GmshReader {
 public:
  explicit GmshReader(const std::string& path) : f_(path, '\0') {
    raw_.vertex_file = raw_.triangle_file = path;
  }

  RawMesh Read() {
    std::string_view line;
    bool have_format = false, have_nodes = false, have_elements = false;
    while (f_.NextDataLine(&line)) {
      if (line.empty() || line[0] != '$')
        f_.Fail("expected a section such as $Nodes, found '" + std::string(line.substr(0, 40)) +
                "'");
      const std::string name(line.substr(1));
      if (name == "MeshFormat") {
        ReadFormat();
        have_format = true;
      } else if (name == "Nodes" || name == "Elements") {
        if (!have_format) f_.Fail("$" + name + " before $MeshFormat");
        if (name == "Nodes") {
          if (have_nodes) f_.Fail("a second $Nodes section");
          v4_ ? ReadNodes4() : ReadNodes2();
          have_nodes = true;
        } else {
          if (!have_nodes) f_.Fail("$Elements before $Nodes");
          if (have_elements) f_.Fail("a second $Elements section");
          v4_ ? ReadElements4() : ReadElements2();
          have_elements = true;
        }
        ExpectEnd(name);
      } else {
        SkipSection(name);
      }
    }
    if (!have_format) f_.Fail("not a Gmsh file: no $MeshFormat section");
    if (!have_nodes) f_.Fail("no $Nodes section");
    if (!have_elements) f_.Fail("no $Elements section");
    if (skipped_ > 0)
      raw_.warnings.push_back(f_.path() + ": skipped " + std::to_string(skipped_) +
                              " elements that are not triangles");
    return std::move(raw_);
  }

 private:
  std::string_view Line(const char* what) {
    std::string_view line;
    if (!f_.NextDataLine(&line))
      f_.Fail(std::string("file ends inside ") + what + " (truncated file or wrong count)");
    return line;
  }
  // A line of the i-th of n items a section's count announced: the section must not end first.
  std::string_view Item(const char* section, int64_t i, int64_t n, const char* items) {
    const std::string_view line = Line(section);
    if (line.size() > 4 && line.substr(0, 4) == "$End")
      f_.Fail(std::string(line) + " after " + std::to_string(i) + " of the " + std::to_string(n) +
              " " + items + " the count announces (wrong count or truncated section)");
    return line;
  }
  int Split(std::string_view line, std::string_view* tok) {
    return Tokens(line).Split(tok, kMaxCols);
  }

  void ReadFormat() {
    std::string_view tok[kMaxCols];
    const int n = Split(Line("$MeshFormat"), tok);
    if (n < 3) f_.Fail("$MeshFormat should read 'version file-type data-size'");
    const std::string version(tok[0]);
    if (version == "4.1") {
      v4_ = true;
    } else if (version == "2.2" || version == "2.1" || version == "2") {
      v4_ = false;
    } else {
      f_.Fail("unsupported .msh version " + version + " (supported: 2.2 and 4.1 ASCII)");
    }
    if (f_.ParseInt(tok[1], "the file type") != 0)
      f_.Fail("binary .msh " + version + " is not supported; save it as binary 4.1 or as ASCII");
    ExpectEnd("MeshFormat");
  }

  void ExpectEnd(const std::string& name) {
    const std::string_view line = Line(("$" + name).c_str());
    if (line != "$End" + name)
      f_.Fail("expected $End" + name + ", found '" + std::string(line.substr(0, 40)) +
              "' (more entries than the section's count?)");
  }

  void SkipSection(const std::string& name) {
    std::string_view line;
    while (f_.NextDataLine(&line))
      if (line == "$End" + name) return;
    f_.Fail("section $" + name + " has no $End" + name + " (truncated file)");
  }

  int64_t Count(std::string_view tok, const char* what) {
    const int64_t n = f_.ParseInt(tok, what);
    if (n < 0) f_.Fail(std::string(what) + " is negative");
    return n;
  }

  void AddNode(int64_t tag, std::string_view x, std::string_view y, std::string_view z) {
    if (tag < 1) f_.Fail("node tag " + std::to_string(tag) + " is below 1");
    f_.ParseDouble(z, "the z coordinate");
    if (!tag_to_id_.emplace(tag, static_cast<int32_t>(raw_.vertex_tag.size())).second)
      f_.Fail("node " + std::to_string(tag) + " is defined twice");
    if (raw_.vertex_tag.size() >= INT32_MAX) f_.Fail("too many nodes");
    raw_.xy.push_back(f_.ParseDouble(x, "the x coordinate"));
    raw_.xy.push_back(f_.ParseDouble(y, "the y coordinate"));
    raw_.vertex_tag.Push(tag);
    raw_.vertex_line.Push(f_.line());
  }

  void ReadNodes2() {
    std::string_view tok[kMaxCols];
    if (Split(Line("$Nodes"), tok) != 1) f_.Fail("expected the number of nodes");
    const int64_t n = Count(tok[0], "the number of nodes");
    tag_to_id_.reserve(f_.Reservable(n, 8));  // "1 0 0 0\n"
    for (int64_t i = 0; i < n; ++i) {
      if (Split(Item("$Nodes", i, n, "nodes"), tok) != 4)
        f_.Fail("a node line should read 'tag x y z'");
      AddNode(f_.ParseInt(tok[0], "the node tag"), tok[1], tok[2], tok[3]);
    }
  }

  void ReadNodes4() {
    std::string_view tok[kMaxCols];
    if (Split(Line("$Nodes"), tok) != 4)
      f_.Fail("expected 'numEntityBlocks numNodes minNodeTag maxNodeTag'");
    const int64_t blocks = Count(tok[0], "the number of entity blocks");
    const int64_t total = Count(tok[1], "the number of nodes");
    // The rules of the binary reader (gmsh_binary_io.cc): tags from 1, within this range.
    const int64_t min_tag = f_.ParseInt(tok[2], "the smallest node tag");
    const int64_t max_tag = f_.ParseInt(tok[3], "the largest node tag");
    if (total > 0 && (min_tag < 1 || max_tag < min_tag))
      f_.Fail("the node tag range " + std::to_string(min_tag) + ".." + std::to_string(max_tag) +
              " is empty or starts below 1");
    tag_to_id_.reserve(f_.Reservable(total, 8));  // a tag line and an "x y z" line
    std::vector<int64_t> tags;
    for (int64_t b = 0; b < blocks; ++b) {
      if (Split(Item("$Nodes", b, blocks, "entity blocks"), tok) != 4)
        f_.Fail("expected 'entityDim entityTag parametric numNodesInBlock'");
      const int64_t dim = f_.ParseInt(tok[0], "the entity dimension");
      if (dim < 0 || dim > 3) f_.Fail("entity dimension " + std::to_string(dim) + " is not 0..3");
      f_.ParseInt(tok[1], "the entity tag");
      const bool parametric = f_.ParseInt(tok[2], "the parametric flag") != 0;
      const int64_t n = Count(tok[3], "the number of nodes in the block");
      tags.clear();
      tags.reserve(f_.Reservable(n, 8));
      for (int64_t i = 0; i < n; ++i) {
        if (Split(Item("$Nodes", i, n, "nodes of the block"), tok) != 1)
          f_.Fail("expected one node tag per line");
        tags.push_back(f_.ParseInt(tok[0], "the node tag"));
        if (tags.back() < min_tag || tags.back() > max_tag)
          f_.Fail("node tag " + std::to_string(tags.back()) + " is outside the header's range " +
                  std::to_string(min_tag) + ".." + std::to_string(max_tag));
      }
      for (int64_t i = 0; i < n; ++i) {
        const int cols = Split(Line("$Nodes"), tok);
        if (cols < 3 || (!parametric && cols != 3) || cols > kMaxCols)
          f_.Fail("a node coordinate line should read 'x y z'" +
                  std::string(parametric ? " followed by parameters" : ""));
        for (int c = 3; c < cols; ++c) f_.ParseDouble(tok[c], "a parametric coordinate");
        AddNode(tags[i], tok[0], tok[1], tok[2]);
      }
    }
    if (static_cast<int64_t>(raw_.vertex_tag.size()) != total)
      f_.Fail("the blocks hold " + std::to_string(raw_.vertex_tag.size()) +
              " nodes, the section header says " + std::to_string(total));
  }

  // `nodes` are the element's node tags; corners of a triangle are the first three.
  void AddElement(int64_t tag, int64_t type, const std::string_view* nodes, int n_nodes) {
    if (type != 2 && type != 9) {
      for (int k = 0; k < n_nodes; ++k) f_.ParseInt(nodes[k], "a node tag");
      ++skipped_;
      return;
    }
    const int need = type == 2 ? 3 : 6;
    if (n_nodes != need)
      f_.Fail("a triangle of type " + std::to_string(type) + " needs " + std::to_string(need) +
              " nodes, found " + std::to_string(n_nodes));
    for (int k = 0; k < 3; ++k) {
      const int64_t tag = f_.ParseInt(nodes[k], "a node tag");
      const auto it = tag_to_id_.find(tag);
      if (it == tag_to_id_.end())
        f_.Fail("triangle refers to node " + std::to_string(tag) + ", which does not exist");
      raw_.tri.push_back(it->second);
    }
    if (raw_.tri.size() / 3 > static_cast<size_t>(INT32_MAX)) f_.Fail("too many triangles");
    raw_.triangle_line.Push(f_.line());
    raw_.triangle_tag.Push(tag);
  }

  void ReadElements2() {
    std::string_view tok[kMaxCols];
    if (Split(Line("$Elements"), tok) != 1) f_.Fail("expected the number of elements");
    const int64_t n = Count(tok[0], "the number of elements");
    for (int64_t i = 0; i < n; ++i) {
      const int cols = Split(Item("$Elements", i, n, "elements"), tok);
      if (cols > kMaxCols) f_.Fail("element line too long");
      if (cols < 3) f_.Fail("an element line should read 'tag type ntags tags... nodes...'");
      const int64_t tag = f_.ParseInt(tok[0], "the element tag");
      const int64_t type = f_.ParseInt(tok[1], "the element type");
      const int64_t ntags = Count(tok[2], "the number of tags");
      if (ntags > cols - 3)  // no arithmetic on the file's count before it is bounded
        f_.Fail("the element line is shorter than its " + std::to_string(ntags) + " tags");
      for (int64_t k = 0; k < ntags; ++k) f_.ParseInt(tok[3 + k], "an element tag");
      AddElement(tag, type, tok + 3 + ntags, static_cast<int>(cols - 3 - ntags));
    }
  }

  void ReadElements4() {
    std::string_view tok[kMaxCols];
    if (Split(Line("$Elements"), tok) != 4)
      f_.Fail("expected 'numEntityBlocks numElements minElementTag maxElementTag'");
    const int64_t blocks = Count(tok[0], "the number of entity blocks");
    const int64_t total = Count(tok[1], "the number of elements");
    f_.ParseInt(tok[2], "the smallest element tag");
    f_.ParseInt(tok[3], "the largest element tag");
    int64_t seen = 0;
    for (int64_t b = 0; b < blocks; ++b) {
      if (Split(Item("$Elements", b, blocks, "entity blocks"), tok) != 4)
        f_.Fail("expected 'entityDim entityTag elementType numElementsInBlock'");
      f_.ParseInt(tok[0], "the entity dimension");
      f_.ParseInt(tok[1], "the entity tag");
      const int64_t type = f_.ParseInt(tok[2], "the element type");
      const int64_t n = Count(tok[3], "the number of elements in the block");
      for (int64_t i = 0; i < n; ++i) {
        const int cols = Split(Item("$Elements", i, n, "elements of the block"), tok);
        if (cols > kMaxCols) f_.Fail("element line too long");
        if (cols < 2) f_.Fail("an element line should read 'tag node...'");
        AddElement(f_.ParseInt(tok[0], "the element tag"), type, tok + 1, cols - 1);
      }
      if (n > total - seen)  // each block's count is bounded before it is added
        f_.Fail("the blocks hold more elements than the section header's " + std::to_string(total));
      seen += n;
    }
    if (seen != total)
      f_.Fail("the blocks hold " + std::to_string(seen) + " elements, the section header says " +
              std::to_string(total));
  }

  TextFile f_;
  RawMesh raw_;
  bool v4_ = false;
  int64_t skipped_ = 0;
  std::unordered_map<int64_t, int32_t> tag_to_id_;
};

}  // namespace

// Binary files start "$MeshFormat\n4.1 1 ": those go to the binary reader, the rest (ASCII, or a
// binary version we do not read, which the ASCII reader names) here.
RawMesh ReadGmsh(const std::string& path) {
  if (path != "-") {
    InputFile f(path);
    char head[32] = {};
    const size_t n = f.Read(head, sizeof head - 1);
    const std::string h(head, n);
    for (const char* start : {"$MeshFormat\n4.1 1 ", "$MeshFormat\r\n4.1 1 "})
      if (h.rfind(start, 0) == 0) return ReadGmshBinary(path);
  }
  return GmshReader(path).Read();
}

void WriteGmsh(const Mesh& m, const std::string& path) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  for (int32_t v = 0; v < nv; ++v)
    for (int d = 0; d < 2; ++d) {
      const double c = m.xy[2 * int64_t{v} + d];
      lo[d] = v == 0 ? c : std::min(lo[d], c);
      hi[d] = v == 0 ? c : std::max(hi[d], c);
    }
  const uint64_t total = 2 * static_cast<uint64_t>(nv) + static_cast<uint64_t>(nt);
  WriteAtomically(path, [&](std::FILE* f) {
    std::fprintf(f, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    // One surface (tag 1), its bounding box, no physical tags and no bounding curves.
    std::fprintf(f, "$Entities\n0 0 1 0\n1 %.17g %.17g 0 %.17g %.17g 0 0 0\n$EndEntities\n", lo[0],
                 lo[1], hi[0], hi[1]);
    std::fprintf(f, "$Nodes\n1 %d 1 %d\n2 1 0 %d\n", nv, nv, nv);
    for (int32_t v = 0; v < nv; ++v) {
      std::fprintf(f, "%d\n", v + 1);
      if ((v & 0xffff) == 0) ReportProgress(static_cast<uint64_t>(v), total);
    }
    for (int32_t v = 0; v < nv; ++v) {
      std::fprintf(f, "%.17g %.17g 0\n", m.xy[2 * int64_t{v}], m.xy[2 * int64_t{v} + 1]);
      if ((v & 0xffff) == 0) ReportProgress(static_cast<uint64_t>(nv) + v, total);
    }
    std::fprintf(f, "$EndNodes\n$Elements\n1 %d 1 %d\n2 1 2 %d\n", nt, nt, nt);
    for (int32_t t = 0; t < nt; ++t) {
      std::fprintf(f, "%d %d %d %d\n", t + 1, m.tri[3 * int64_t{t}] + 1,
                   m.tri[3 * int64_t{t} + 1] + 1, m.tri[3 * int64_t{t} + 2] + 1);
      if ((t & 0xffff) == 0) ReportProgress(2 * static_cast<uint64_t>(nv) + t, total);
    }
    std::fprintf(f, "$EndElements\n");
  });
}

}  // namespace meshreuse
