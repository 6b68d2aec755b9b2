// Gmsh .msh 4.1 binary (`gmsh -bin`; https://gmsh.info/doc/texinfo/gmsh.html, "MSH file format"):
// "$MeshFormat\n4.1 1 8\n", a 4-byte integer 1 (which tells the byte order: only little-endian,
// the writer's own on every platform Gmsh ships for, is read), then "\n$EndMeshFormat\n". In
// $Nodes and $Elements every count and tag is a size_t (8 bytes, the header's data size) and every
// other integer 4 bytes; coordinates are doubles. $Nodes: numEntityBlocks numNodes minNodeTag
// maxNodeTag, then per block entityDim entityTag parametric (ints) numNodesInBlock, the block's
// node tags, then its coordinates (x y z, and entityDim parameters when parametric). $Elements:
// numEntityBlocks numElements minElementTag maxElementTag, then per block entityDim entityTag
// elementType (ints) numElementsInBlock, then per element its tag and its node tags. Other
// sections ($Entities, $PhysicalNames, ...) are skipped to their "$End" line.
// The same checks as the ASCII reader (gmsh_io.cc): triangles are types 2 and 9 (corners first),
// other types are skipped and counted (their node count comes from Gmsh's table; a type not in it
// is an error, since the block could not be stepped over), tags must exist and be unique. Every
// count is checked against the bytes left before anything is reserved for it, so memory follows
// the file; errors name the byte offset. Node tags map to ids through a direct array when the
// header's tag range is at most 4 entries per node (Gmsh's own files: one), else a hash table.
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/input_file.h"
#include "core/mesh_io.h"
#include "core/progress.h"

namespace meshreuse {

namespace {

// Nodes per element of each Gmsh element type (gmsh's GmshDefines.h / MElement), 0: unknown.
int NodesOfType(int64_t type) {
  static const int kNodes[] = {0,  2,  3,  4,  4,  8,  6,  5,  3,  6,  9,  10, 27, 18,
                               14, 1,  8,  20, 15, 13, 9,  10, 12, 15, 15, 21, 4,  5,
                               6,  20, 35, 56, 34, 52, 20, 22, 16, 25, 23, 35};
  return type >= 0 && type < static_cast<int64_t>(sizeof kNodes / sizeof kNodes[0]) ? kNodes[type]
                                                                                    : 0;
}

class GmshBinaryReader {
 public:
  explicit GmshBinaryReader(const std::string& path) : f_(path) {
    raw_.vertex_file = raw_.triangle_file = path;
  }

  RawMesh Read() {
    bool have_nodes = false, have_elements = false;
    std::string line;
    if (!Line(&line) || line != "$MeshFormat") Fail("not a Gmsh file: no $MeshFormat section");
    Format();
    while (Line(&line)) {
      if (line.empty()) continue;
      if (line[0] != '$') Fail("expected a section such as $Nodes, found '" + Cut(line) + "'");
      const std::string name = line.substr(1);
      if (name == "Nodes") {
        if (have_nodes) Fail("a second $Nodes section");
        Nodes();
        have_nodes = true;
      } else if (name == "Elements") {
        if (!have_nodes) Fail("$Elements before $Nodes");
        if (have_elements) Fail("a second $Elements section");
        Elements();
        have_elements = true;
      } else {
        Skip(name);
        continue;
      }
      End(name);
    }
    if (!have_nodes) Fail("no $Nodes section");
    if (!have_elements) Fail("no $Elements section");
    if (skipped_ > 0)
      raw_.warnings.push_back(f_.path() + ": skipped " + std::to_string(skipped_) +
                              " elements that are not triangles");
    return std::move(raw_);
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(f_.path(), 0, "byte " + std::to_string(offset_) + ": " + what);
  }
  static std::string Cut(const std::string& s) { return s.substr(0, 40); }

  // Buffered bytes: Get(n) returns a pointer to the next n bytes (n <= kBlock) or fails.
  static constexpr size_t kBlock = size_t{1} << 20;
  bool Fill(size_t need) {
    if (end_ - pos_ >= need) return true;
    std::memmove(buf_.data(), buf_.data() + pos_, end_ - pos_);
    end_ -= pos_;
    pos_ = 0;
    if (buf_.size() < kBlock) buf_.resize(kBlock);
    while (end_ < need) {
      const size_t got = f_.Read(buf_.data() + end_, buf_.size() - end_);
      if (got == 0) return false;
      end_ += got;
      read_ += got;
      ReportProgress(read_, f_.size() > 0 ? static_cast<uint64_t>(f_.size()) : 0);
    }
    return true;
  }
  const char* Get(size_t n, const char* what) {
    if (!Fill(n)) Fail(std::string("file ends inside ") + what + " (truncated file)");
    const char* p = buf_.data() + pos_;
    pos_ += n;
    offset_ += static_cast<int64_t>(n);
    return p;
  }
  int64_t Size(const char* what) {  // a size_t count or tag
    uint64_t v;
    std::memcpy(&v, Get(8, what), 8);
    if (v > static_cast<uint64_t>(INT64_MAX)) Fail(std::string(what) + " is beyond 2^63");
    return static_cast<int64_t>(v);
  }
  int32_t Int(const char* what) {
    int32_t v;
    std::memcpy(&v, Get(4, what), 4);
    return v;
  }
  double Double(const char* what) {
    double v;
    std::memcpy(&v, Get(8, what), 8);
    return v;
  }
  // A text line (section names, the format line), without its newline; false at the end.
  bool Line(std::string* out) {
    out->clear();
    for (;;) {
      if (!Fill(1)) return !out->empty();
      const char c = buf_[pos_++];
      ++offset_;
      if (c == '\n') break;
      if (out->size() >= 256) Fail("expected a section line, found binary data");
      out->push_back(c);
    }
    if (!out->empty() && out->back() == '\r') out->pop_back();
    return true;
  }
  // The bytes that can still follow (for pipes: unknown, a large bound).
  int64_t Left() const { return f_.size() < 0 ? INT64_MAX : f_.size() - offset_; }
  // A count of items at least `bytes` each, checked against what the file still holds.
  int64_t Count(const char* what, int64_t bytes) {
    const int64_t n = Size(what);
    if (n > Left() / bytes)
      Fail(std::string(what) + " " + std::to_string(n) + " exceeds what the file holds");
    return n;
  }

  void Format() {
    std::string line;
    if (!Line(&line)) Fail("file ends inside $MeshFormat");
    if (line != "4.1 1 8")
      Fail("expected '4.1 1 8' (binary MSH 4.1, 8-byte size_t) in $MeshFormat, found '" +
           Cut(line) + "'");
    const int32_t one = Int("the byte-order mark");
    if (one != 1)
      Fail(one == 0x01000000 ? "big-endian binary .msh is not supported"
                             : "bad byte-order mark in $MeshFormat (a corrupt file)");
    End("MeshFormat");
  }

  void End(const std::string& name) {
    std::string line;
    while (Line(&line) && line.empty()) {
    }
    if (line != "$End" + name)
      Fail("expected $End" + name + ", found '" + Cut(line) + "' (a count that does not match?)");
  }

  // Steps over a section we do not read: to the first line "$End<name>".
  void Skip(const std::string& name) {
    const std::string end = "$End" + name;
    size_t matched = 0;
    last_ = '\n';  // the section's name line has just ended  // bytes of "\n$End<name>" matched so
                   // far, after a newline
    for (;;) {
      if (!Fill(1)) Fail("section $" + name + " has no " + end + " (truncated file)");
      const char c = buf_[pos_++];
      ++offset_;
      if (matched == end.size()) {
        if (c == '\n' || c == '\r') {
          if (c == '\r' && Fill(1) && buf_[pos_] == '\n') ++pos_, ++offset_;
          return;
        }
        matched = 0;
      }
      if (matched < end.size() && c == end[matched] && (matched > 0 || last_ == '\n'))
        ++matched;
      else
        matched = 0;
      last_ = c;
    }
  }

  int32_t IdOf(int64_t tag) {
    if (dense_) {
      const int64_t k = tag - min_tag_;
      return k >= 0 && k < static_cast<int64_t>(dense_ids_.size()) ? dense_ids_[k] : -1;
    }
    const auto it = tag_to_id_.find(tag);
    return it == tag_to_id_.end() ? -1 : it->second;
  }

  void Nodes() {
    const int64_t blocks = Count("the number of entity blocks", 20);
    const int64_t total = Count("the number of nodes", 32);  // a tag and three coordinates
    const int64_t min_tag = Size("the smallest node tag");
    const int64_t max_tag = Size("the largest node tag");
    if (total > INT32_MAX) Fail("too many nodes for 32-bit ids");
    // The rules of the ASCII reader (gmsh_io.cc): tags from 1, within the header's range; a
    // sparse range is kept in a hash map, a dense one in an array.
    if (total > 0 && (min_tag < 1 || max_tag < min_tag))
      Fail("the node tag range " + std::to_string(min_tag) + ".." + std::to_string(max_tag) +
           " is empty or starts below 1");
    min_tag_ = min_tag;
    dense_ = total == 0 || (max_tag - min_tag) / 4 <= total;
    if (dense_) dense_ids_.assign(total ? static_cast<size_t>(max_tag - min_tag + 1) : 0, -1);
    raw_.xy.reserve(2 * static_cast<size_t>(total));
    std::vector<int64_t> tags;
    int64_t seen = 0;
    for (int64_t b = 0; b < blocks; ++b) {
      const int32_t dim = Int("the entity dimension");
      Int("the entity tag");
      const int32_t parametric = Int("the parametric flag");
      const int64_t n = Count("the number of nodes in the block", 32);
      if (dim < 0 || dim > 3) Fail("entity dimension " + std::to_string(dim) + " is not 0..3");
      if (n > total - seen) Fail("the blocks hold more nodes than the section header's count");
      seen += n;
      tags.resize(static_cast<size_t>(n));
      for (int64_t i = 0; i < n; ++i) tags[i] = Size("a node tag");
      const int params = parametric ? dim : 0;
      for (int64_t i = 0; i < n; ++i) {
        const int64_t tag = tags[i];
        const int32_t id = static_cast<int32_t>(raw_.vertex_tag.size());
        if (tag < min_tag || tag > max_tag)
          Fail("node tag " + std::to_string(tag) + " is outside the header's range " +
               std::to_string(min_tag) + ".." + std::to_string(max_tag));
        if (dense_) {
          int32_t& slot = dense_ids_[tag - min_tag];
          if (slot >= 0) Fail("node " + std::to_string(tag) + " is defined twice");
          slot = id;
        } else if (!tag_to_id_.emplace(tag, id).second) {
          Fail("node " + std::to_string(tag) + " is defined twice");
        }
        const double x = Double("a coordinate"), y = Double("a coordinate");
        Double("a coordinate");  // z, ignored (2D)
        for (int k = 0; k < params; ++k) Double("a parametric coordinate");
        if (!std::isfinite(x) || !std::isfinite(y))
          Fail("node " + std::to_string(tag) + " has a non-finite coordinate");
        raw_.xy.push_back(x);
        raw_.xy.push_back(y);
        raw_.vertex_tag.Push(tag);
      }
    }
    if (seen != total)
      Fail("the blocks hold " + std::to_string(seen) + " nodes, the section header says " +
           std::to_string(total));
  }

  void Elements() {
    const int64_t blocks = Count("the number of entity blocks", 20);
    const int64_t total = Count("the number of elements", 16);  // a tag and one node
    Size("the smallest element tag");
    Size("the largest element tag");
    int64_t seen = 0;
    for (int64_t b = 0; b < blocks; ++b) {
      Int("the entity dimension");
      Int("the entity tag");
      const int32_t type = Int("the element type");
      const int per = NodesOfType(type);
      if (per == 0) Fail("element type " + std::to_string(type) + " is not a Gmsh element type");
      const int64_t n = Count("the number of elements in the block", 8 * (1 + per));
      if (n > total - seen) Fail("the blocks hold more elements than the section header's count");
      seen += n;
      const bool triangle = type == 2 || type == 9;
      // Grown geometrically: an exact reserve per block reallocated the whole array for every
      // block (80,000 one-triangle blocks took 15 s).
      if (triangle && raw_.tri.size() + 3 * static_cast<size_t>(n) > raw_.tri.capacity())
        raw_.tri.reserve(
            std::max(raw_.tri.size() + 3 * static_cast<size_t>(n), 2 * raw_.tri.capacity()));
      for (int64_t i = 0; i < n; ++i) {
        const int64_t element_tag = Size("an element tag");
        if (triangle) raw_.triangle_tag.Push(element_tag);
        for (int k = 0; k < per; ++k) {
          const int64_t tag = Size("a node tag");
          const int32_t id = IdOf(tag);
          if (id < 0)
            Fail((triangle ? "triangle" : "element") + std::string(" refers to node ") +
                 std::to_string(tag) + ", which does not exist");
          if (triangle && k < 3) raw_.tri.push_back(id);
        }
        if (!triangle) ++skipped_;
      }
      if (raw_.tri.size() / 3 > static_cast<size_t>(INT32_MAX)) Fail("too many triangles");
    }
    if (seen != total)
      Fail("the blocks hold " + std::to_string(seen) + " elements, the section header says " +
           std::to_string(total));
  }

  InputFile f_;
  std::string buf_;
  size_t pos_ = 0, end_ = 0;
  uint64_t read_ = 0;  // bytes of the file read so far (progress)
  int64_t offset_ = 0;
  char last_ = '\n';
  RawMesh raw_;
  int64_t skipped_ = 0;
  bool dense_ = true;
  int64_t min_tag_ = 0;
  std::vector<int32_t> dense_ids_;
  std::unordered_map<int64_t, int32_t> tag_to_id_;
};

}  // namespace

RawMesh ReadGmshBinary(const std::string& path) { return GmshBinaryReader(path).Read(); }

}  // namespace meshreuse
