// Triangle's .node and .ele files (https://www.cs.cmu.edu/~quake/triangle.node.html and
// triangle.ele.html). '#' starts a comment. .node: "<#vertices> <dim=2> <#attributes> <#markers>"
// then "<id> <x> <y> [attributes] [marker]"; .ele: "<#triangles> <3 or 6> <#attributes>" then
// "<id> <n1> <n2> <n3> [<n4> <n5> <n6>] [attributes]". Ids are consecutive from 0 or 1; the .ele
// refers to the .node's ids. We check every count, column and id, so a wrong file fails at its
// line rather than producing a wrong mesh: attributes must be numbers, markers integers, the extra
// nodes of quadratic triangles existing vertices (they are then ignored: the corners are the first
// three). A header's count is checked against the bytes that follow before anything is allocated
// for it (a vertex line needs at least 6 bytes, a triangle line 8), so memory follows the file.
// The two files are parsed on two threads.
#include <atomic>
#include <cstdio>
#include <exception>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/progress.h"
#include "core/text_file.h"

namespace meshreuse {

namespace {

struct Header {
  int64_t v[4];
  int n;
};

Header ReadHeader(TextFile& f, int min_fields, int max_fields, const char* what) {
  std::string_view line;
  if (!f.NextDataLine(&line)) f.Fail(std::string("empty file: expected the ") + what + " header");
  std::string_view tok[kMaxCols];
  const int n = Tokens(line).Split(tok, kMaxCols);
  if (n < min_fields || n > max_fields)
    f.Fail(std::string("the ") + what + " header should have " + std::to_string(min_fields) +
           (min_fields == max_fields ? "" : " to " + std::to_string(max_fields)) +
           " fields, found " + std::to_string(n));
  Header h{{0, 0, 0, 0}, n};
  static const char* const kNames[] = {"the count", "the second header field",
                                       "the third header field", "the fourth header field"};
  for (int i = 0; i < n; ++i) {
    h.v[i] = f.ParseInt(tok[i], kNames[i]);
    if (h.v[i] < 0) f.Fail(std::string(kNames[i]) + " is negative");
  }
  return h;
}

// Items are numbered consecutively from 0 or 1 (the first one fixes `base`); returns the number.
int64_t CheckSequenceNumber(const TextFile& f, std::string_view tok, int64_t i, int64_t* base,
                            const std::string& item) {
  const int64_t id = f.ParseInt(tok, ("the " + item + " number").c_str());
  if (i == 0) {
    if (id != 0 && id != 1)
      f.Fail(item + " numbers must start at 0 or 1, found " + std::string(tok));
    *base = id;
  } else if (id != *base + i) {
    f.Fail(item + " number " + std::string(tok) + " is out of sequence (expected " +
           std::to_string(*base + i) + ")");
  }
  return id;
}

void ExpectEnd(TextFile& f, int64_t count, const char* items) {
  std::string_view line;
  if (f.NextDataLine(&line))
    f.Fail(std::string("more ") + items + " lines than the header's count of " +
           std::to_string(count));
}

// The .ele, on its own thread: it needs from the .node only the vertex count and numbering base,
// known once the .node's header and first vertex are read. `stop` is set when the .node failed.
void ReadEle(const std::string& node_path, const std::string& ele_path, int64_t nv, int64_t base,
             const std::atomic<bool>& stop, RawMesh* out, std::string* pair_mark) {
  RawMesh& raw = *out;
  TextFile ele(ele_path);
  std::string_view line, tok[kMaxCols];
  const Header eh = ReadHeader(ele, 1, 3, ".ele");
  const int64_t nt = eh.v[0];
  if (nt == 0) ele.Fail("the header says the file has no triangles");
  if (nt > INT32_MAX) ele.Fail("too many triangles for 32-bit ids");
  const int64_t per = eh.n >= 2 ? eh.v[1] : 3;
  if (per != 3 && per != 6)
    ele.Fail("nodes per triangle must be 3 or 6, found " + std::to_string(per));
  const int64_t eattr = eh.n >= 3 ? eh.v[2] : 0;
  if (eattr > kMaxCols - 7)
    ele.Fail("too many attribute columns (" + std::to_string(eattr) + "; at most " +
             std::to_string(kMaxCols - 7) + ")");
  const int64_t ecols = 1 + per + eattr;
  const int64_t tfits = ele.Reservable(nt, 8);  // "1 1 2 3\n"
  raw.tri.reserve(3 * tfits);
  int64_t tbase = 0;
  for (int64_t t = 0; t < nt; ++t) {
    if ((t & 0xFFFF) == 0 && stop.load(std::memory_order_relaxed)) return;
    if (!ele.NextDataLine(&line))
      ele.Fail("file ends after " + std::to_string(t) + " of the " + std::to_string(nt) +
               " triangles the header announces (truncated file or wrong count)");
    const int n = Tokens(line).Split(tok, kMaxCols);
    if (n != ecols)
      ele.Fail("expected " + std::to_string(ecols) + " columns (id, " + std::to_string(per) +
               " vertices, " + std::to_string(eattr) + " attributes), found " + std::to_string(n));
    CheckSequenceNumber(ele, tok[0], t, &tbase, "triangle");
    for (int k = 0; k < per; ++k) {  // quadratic triangles: the corners are the first three
      const int64_t c = ele.ParseInt(tok[1 + k], k < 3 ? "a triangle corner" : "a triangle node");
      if (c < base || c >= base + nv)
        ele.Fail("triangle " + std::string(tok[0]) + " refers to vertex " +
                 std::string(tok[1 + k]) + ", which does not exist (" + node_path +
                 " has vertices " + std::to_string(base) + ".." + std::to_string(base + nv - 1) +
                 ")");
      if (k < 3) raw.tri.push_back(static_cast<int32_t>(c - base));
    }
    for (int64_t a = 0; a < eattr; ++a) ele.ParseDouble(tok[1 + per + a], "an attribute");
    raw.triangle_line.Push(ele.line());
  }
  ExpectEnd(ele, nt, "triangle");
  *pair_mark = ele.pair_mark();
}

// Runs ReadEle on a thread; joins it (asking it to stop) on every way out of the .node's reader.
class EleThread {
 public:
  void Start(const std::string& node_path, const std::string& ele_path, int64_t nv, int64_t base) {
    thread_ = std::thread([=] {
      try {
        ReadEle(node_path, ele_path, nv, base, stop_, &raw_, &pair_mark_);
      } catch (...) {
        error_ = std::current_exception();
      }
    });
  }
  RawMesh Join() {
    thread_.join();
    if (error_) std::rethrow_exception(error_);
    return std::move(raw_);
  }
  const std::string& pair_mark() const { return pair_mark_; }
  ~EleThread() {
    if (thread_.joinable()) {
      stop_ = true;
      thread_.join();
    }
  }

 private:
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::exception_ptr error_;
  RawMesh raw_;
  std::string pair_mark_;
};

}  // namespace

RawMesh ReadTriangleFiles(const std::string& node_path, const std::string& ele_path) {
  RawMesh raw;
  raw.vertex_file = node_path;
  raw.triangle_file = ele_path;

  // --- .node
  TextFile node(node_path);
  const Header nh = ReadHeader(node, 1, 4, ".node");
  const int64_t nv = nh.v[0];
  if (nv == 0) node.Fail("the header says the file has no vertices");
  if (nv > INT32_MAX) node.Fail("too many vertices for 32-bit ids");
  if (nh.n >= 2 && nh.v[1] != 2)
    node.Fail("dimension is " + std::to_string(nh.v[1]) + ", only 2D meshes are supported");
  const int64_t nattr = nh.n >= 3 ? nh.v[2] : 0;
  const int64_t nmark = nh.n >= 4 ? nh.v[3] : 0;
  if (nmark > 1) node.Fail("the number of boundary markers must be 0 or 1");
  if (nattr > kMaxCols - 4)  // checked before any arithmetic on it
    node.Fail("too many attribute columns (" + std::to_string(nattr) + "; at most " +
              std::to_string(kMaxCols - 4) + ")");
  const int64_t cols = 3 + nattr + nmark;
  const int64_t fits = node.Reservable(nv, 6);  // "1 0 0\n": containers grow as lines come
  raw.xy.reserve(2 * fits);
  int64_t base = 0;
  std::string_view line, tok[kMaxCols];
  // The .ele is read on a second thread from the first vertex on (its ids are checked against the
  // numbering base that line fixes); its errors are reported only if the .node has none, as when
  // the files were read one after the other.
  EleThread ele;
  for (int64_t i = 0; i < nv; ++i) {
    if (!node.NextDataLine(&line))
      node.Fail("file ends after " + std::to_string(i) + " of the " + std::to_string(nv) +
                " vertices the header announces (truncated file or wrong count)");
    const int n = Tokens(line).Split(tok, kMaxCols);
    if (n != cols)
      node.Fail("expected " + std::to_string(cols) + " columns (id, x, y, " +
                std::to_string(nattr) + " attributes, " + std::to_string(nmark) +
                " markers), found " + std::to_string(n));
    const int64_t id = CheckSequenceNumber(node, tok[0], i, &base, "vertex");
    raw.xy.push_back(node.ParseDouble(tok[1], "the x coordinate"));
    raw.xy.push_back(node.ParseDouble(tok[2], "the y coordinate"));
    for (int64_t a = 0; a < nattr; ++a) node.ParseDouble(tok[3 + a], "an attribute");
    if (nmark) node.ParseInt(tok[3 + nattr], "the boundary marker");
    raw.vertex_line.Push(node.line());
    raw.vertex_tag.Push(id);
    if (i == 0) ele.Start(node_path, ele_path, nv, base);
  }
  ExpectEnd(node, nv, "vertex");
  RawMesh tris = ele.Join();  // the .ele's error, if any, now that the .node has none
  // Written as a pair by meshreuse: both files carry one mark; different marks (or one without)
  // mean the two were not written together (a disk full between them, two writers of a prefix).
  if (!node.pair_mark().empty() || !ele.pair_mark().empty()) {
    if (node.pair_mark() != ele.pair_mark())
      throw InputError(ele_path, 0,
                       "does not belong with " + node_path + ": meshreuse wrote them as a pair " +
                           "marked '" + node.pair_mark() + "' and '" + ele.pair_mark() +
                           "' (written at different times; write the mesh again)");
  }
  raw.tri = std::move(tris.tri);
  raw.triangle_line = std::move(tris.triangle_line);
  return raw;
}

void WriteTriangleFiles(const Mesh& m, const std::string& prefix) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  // As a unit: a .node never lands beside an .ele it was not written with. Both carry one mark,
  // the counts and a hash of the arrays, which the reader compares (a pair from two runs differs).
  uint64_t h = 1469598103934665603ull;  // FNV-1a over the coordinates' and corners' bytes
  auto mix = [&h](const void* p, size_t n) {
    for (size_t i = 0; i < n; ++i)
      h = (h ^ static_cast<const unsigned char*>(p)[i]) * 1099511628211ull;
  };
  mix(m.xy.data(), m.xy.size() * sizeof(double));
  mix(m.tri.data(), m.tri.size() * sizeof(int32_t));
  char mark[96];
  std::snprintf(mark, sizeof mark, "# meshreuse pair %d vertices %d triangles %016llx\n", nv, nt,
                static_cast<unsigned long long>(h));
  WriteAtomicallyAll({{prefix + ".node",
                       [&](std::FILE* f) {
                         std::fprintf(f, "%d 2 0 1\n", nv);
                         for (int32_t v = 0; v < nv; ++v) {
                           std::fprintf(f, "%d %.17g %.17g %d\n", v + 1, m.xy[2 * int64_t{v}],
                                        m.xy[2 * int64_t{v} + 1], int{m.boundary[v]});
                           if ((v & 0xffff) == 0)
                             ReportProgress(static_cast<uint64_t>(v),
                                            static_cast<uint64_t>(nv) + static_cast<uint64_t>(nt));
                         }
                         std::fprintf(f, "# written by meshreuse\n%s", mark);
                       }},
                      {prefix + ".ele", [&](std::FILE* f) {
                         std::fprintf(f, "%d 3 0\n", nt);
                         for (int32_t t = 0; t < nt; ++t) {
                           std::fprintf(f, "%d %d %d %d\n", t + 1, m.tri[3 * int64_t{t}] + 1,
                                        m.tri[3 * int64_t{t} + 1] + 1,
                                        m.tri[3 * int64_t{t} + 2] + 1);
                           if ((t & 0xffff) == 0)
                             ReportProgress(static_cast<uint64_t>(nv) + t,
                                            static_cast<uint64_t>(nv) + static_cast<uint64_t>(nt));
                         }
                         std::fprintf(f, "# written by meshreuse\n%s", mark);
                       }}});
}

}  // namespace meshreuse
