// Readers on small files (each format and numbering gives the same mesh), every broken input in
// tests/data/broken/EXPECTED (file, line, message), round trips, and atomic writes.
#include "core/mesh_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/quality.h"
#include "core/synthetic.h"
#include "core/triangle_runner.h"
#include "core/visit_order.h"
#include "tests/test_util.h"
#include "tracer/foreign_trace.h"
#include "tracer/trace_reader.h"

namespace meshreuse {
namespace {

namespace fs = std::filesystem;
using testing::DataPath;

void ExpectSameMesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.xy, b.xy);
  EXPECT_EQ(a.tri, b.tri);
  EXPECT_EQ(a.boundary, b.boundary);
  EXPECT_EQ(a.v2v.idx, b.v2v.idx);
}

TEST(Readers, AllFormatsGiveTheSameMesh) {
  const Mesh ref = testing::TwoInterior();
  EXPECT_DOUBLE_EQ(ref.xy[2 * 7], 3.25);
  EXPECT_EQ((std::vector<int32_t>(ref.tri.begin(), ref.tri.begin() + 6)),
            (std::vector<int32_t>{0, 1, 6, 1, 7, 6}));
  ExpectSameMesh(ref, ReadMesh(DataPath("two_interior0.node")));  // 0-based, attributes
  ExpectSameMesh(ref, ReadMesh(DataPath("two_interior.ele")));    // by the .ele name
  ExpectSameMesh(ref, ReadMesh(DataPath("two_interior")));        // by prefix
  ExpectSameMesh(ref, ReadMesh(DataPath("two_interior41.msh")));
  ExpectSameMesh(ref, ReadMesh(DataPath("two_interior41_bin.msh")));  // gmsh -bin wrote it
  std::vector<std::string> warnings;
  ExpectSameMesh(ref, ReadMesh(DataPath("two_interior22.msh"), &warnings));
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("skipped 3 elements that are not triangles"), std::string::npos);
  EXPECT_NE(warnings[1].find("dropped 1 vertices that no triangle uses (first: vertex 99"),
            std::string::npos)
      << warnings[1];
}

TEST(Readers, Gmsh41SkipsLinesAndKeepsTags) {
  std::vector<std::string> warnings;
  const RawMesh raw = ReadGmsh(DataPath("two_interior41.msh"));
  EXPECT_EQ(raw.vertex_tag.ToVector(), (std::vector<int64_t>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(raw.tri.size(), 24u);
  ASSERT_EQ(raw.warnings.size(), 1u);
  EXPECT_NE(raw.warnings[0].find("skipped 2 elements"), std::string::npos);
}

// A mesh Gmsh made (tests/data/plate.geo: a plate with a hole, several entities, points, lines
// and triangles), saved by Gmsh as 4.1 binary, 4.1 ASCII and 2.2 ASCII: the same triangles and
// tags, and the same coordinates to the 16 digits Gmsh writes in ASCII.
TEST(Readers, GmshBinaryEqualsGmshAscii) {
  const RawMesh bin = ReadGmsh(DataPath("plate_bin.msh"));
  EXPECT_EQ(bin.xy.size(), 2u * 995);
  EXPECT_EQ(bin.tri.size(), 3u * 1844);
  for (const char* ascii : {"plate41.msh", "plate22.msh"}) {
    SCOPED_TRACE(ascii);
    const RawMesh a = ReadGmsh(DataPath(ascii));
    ASSERT_EQ(a.xy.size(), bin.xy.size());
    for (size_t i = 0; i < a.xy.size(); ++i)  // Gmsh's ASCII has 16 significant digits
      ASSERT_NEAR(a.xy[i], bin.xy[i], 1e-15 * std::max(1.0, std::fabs(bin.xy[i]))) << i;
    EXPECT_EQ(a.tri, bin.tri);
    EXPECT_EQ(a.vertex_tag.ToVector(), bin.vertex_tag.ToVector());
    ASSERT_EQ(a.warnings.size(), 1u);
    ASSERT_EQ(bin.warnings.size(), 1u);
    EXPECT_EQ(a.warnings[0].substr(a.warnings[0].find("skipped")),
              bin.warnings[0].substr(bin.warnings[0].find("skipped")));
  }
  // Contiguous tags (Gmsh's own): one run, no per-vertex memory.
  EXPECT_EQ(bin.vertex_tag.runs(), 1u);
}

// Node tags of INT64_MAX then 1 (a run that would overflow), in Gmsh 2.2 ASCII and 4.1 binary:
// both read (UBSan in the sanitizer build checks the run index), to the same mesh.
TEST(Readers, NodeTagInt64MaxReads) {
  const RawMesh a = ReadGmsh(DataPath("tag_int64max22.msh"));
  const RawMesh b = ReadGmsh(DataPath("tag_int64max41_bin.msh"));
  EXPECT_EQ(a.vertex_tag.ToVector(), (std::vector<int64_t>{INT64_MAX, 1, 2, 3}));
  EXPECT_EQ(b.vertex_tag.ToVector(), a.vertex_tag.ToVector());
  EXPECT_EQ(a.tri, b.tri);
  EXPECT_EQ(a.xy, b.xy);
}

// One set of rules for Gmsh 4.1 ASCII and binary: the same small mesh written both ways, with a
// sparse tag range (accepted by both), a tag outside the header's range, an entity dimension of
// 5, and a range starting at 0 (each refused by both, with the same words).
std::string Ascii41(int64_t lo, int64_t hi, const std::vector<int64_t>& tags, int dim) {
  std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 " + std::to_string(lo) + " " +
                  std::to_string(hi) + "\n" + std::to_string(dim) + " 1 0 4\n";
  for (int64_t t : tags) s += std::to_string(t) + "\n";
  s += "0 0 0\n1 0 0\n0 1 0\n1 1 0\n$EndNodes\n$Elements\n1 2 1 2\n2 1 2 2\n";
  s += "1 " + std::to_string(tags[0]) + " " + std::to_string(tags[1]) + " " +
       std::to_string(tags[2]) + "\n2 " + std::to_string(tags[1]) + " " + std::to_string(tags[3]) +
       " " + std::to_string(tags[2]) + "\n$EndElements\n";
  return s;
}

std::string Binary41(int64_t lo, int64_t hi, const std::vector<int64_t>& tags, int32_t dim) {
  std::string s = "$MeshFormat\n4.1 1 8\n";
  auto put = [&](auto v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(int32_t{1});
  s += "\n$EndMeshFormat\n$Nodes\n";
  for (uint64_t v :
       {uint64_t{1}, uint64_t{4}, static_cast<uint64_t>(lo), static_cast<uint64_t>(hi)})
    put(v);
  put(dim), put(int32_t{1}), put(int32_t{0}), put(uint64_t{4});
  for (int64_t t : tags) put(static_cast<uint64_t>(t));
  for (double c : {0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.}) put(c);
  s += "\n$EndNodes\n$Elements\n";
  for (uint64_t v : {uint64_t{1}, uint64_t{2}, uint64_t{1}, uint64_t{2}}) put(v);
  put(int32_t{2}), put(int32_t{1}), put(int32_t{2}), put(uint64_t{2});
  for (int64_t v : {int64_t{1}, tags[0], tags[1], tags[2], int64_t{2}, tags[1], tags[3], tags[2]})
    put(static_cast<uint64_t>(v));
  s += "\n$EndElements\n";
  return s;
}

TEST(Readers, GmshAsciiAndBinaryFollowOneSetOfRules) {
  testing::TempDir dir;
  const int64_t big = int64_t{1} << 50;
  struct Case {
    int64_t lo, hi;
    std::vector<int64_t> tags;
    int dim;
    const char* error;  // nullptr: reads
  };
  const std::vector<Case> cases = {
      {1, 3 * big, {1, big, 2 * big, 3 * big}, 2, nullptr},
      {1, 10, {1, 2, 3, 11}, 2, "node tag 11 is outside the header's range 1..10"},
      {1, 4, {1, 2, 3, 4}, 5, "entity dimension 5 is not 0..3"},
      {0, 3, {0, 1, 2, 3}, 2, "the node tag range 0..3 is empty or starts below 1"},
  };
  for (const Case& c : cases) {
    const std::string a = dir / "a.msh", b = dir / "b.msh";
    std::ofstream(a, std::ios::binary) << Ascii41(c.lo, c.hi, c.tags, c.dim);
    std::ofstream(b, std::ios::binary) << Binary41(c.lo, c.hi, c.tags, c.dim);
    for (const std::string& f : {a, b}) {
      SCOPED_TRACE(f + (c.error ? std::string(": ") + c.error : ""));
      if (!c.error) {
        const RawMesh r = ReadGmsh(f);
        EXPECT_EQ(r.vertex_tag.ToVector(), c.tags);
        EXPECT_EQ(r.tri, (AlignedVector<int32_t>{0, 1, 2, 1, 3, 2}));
        continue;
      }
      try {
        ReadGmsh(f);
        ADD_FAILURE() << "read";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(c.error), std::string::npos) << e.what();
      }
    }
  }
}

struct BrokenCase {
  std::string file;
  int64_t line;
  std::string message;
  // mesh, trace, text, u32, u64, perm, visit, poly, summary (EXPECTED's 4th column); summaries
  // belong to reports/ and are read by tests/reports/chunk_summary_test.cc.
  std::string kind = "mesh";
};

void PrintTo(const BrokenCase& c, std::ostream* os) { *os << c.file << ":" << c.line; }

std::vector<BrokenCase> BrokenCases() {
  std::ifstream in(DataPath("broken/EXPECTED"));
  std::vector<BrokenCase> cases;
  for (std::string l; std::getline(in, l);) {
    if (l.empty() || l[0] == '#') continue;
    std::stringstream ss(l);
    BrokenCase c;
    std::getline(ss, c.file, '\t');
    std::string line;
    std::getline(ss, line, '\t');
    c.line = std::stoll(line);
    std::getline(ss, c.message, '\t');
    std::string kind;
    if (std::getline(ss, kind) && !kind.empty()) c.kind = kind;
    cases.push_back(c);
  }
  return cases;
}

std::vector<BrokenCase> CoreBrokenCases() {
  std::vector<BrokenCase> cases;
  for (BrokenCase& c : BrokenCases())
    if (c.kind != "summary") cases.push_back(std::move(c));
  return cases;
}

class BrokenInput : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenInput, FailsWithFileLineAndProblem) {
  const BrokenCase& c = GetParam();
  const std::string path = DataPath("broken/" + c.file);
  try {
    if (c.kind == "mesh") {
      ReadMesh(path);
    } else if (c.kind == "trace") {
      TraceReader r(path);
      std::vector<TraceRecord> batch;
      while (r.Next(&batch)) {
      }
    } else if (c.kind == "perm") {
      ComputeOrdering("file:" + path, testing::TwoInterior(), 1);
    } else if (c.kind == "visit") {
      ReadVisitOrder(path, testing::TwoInterior());
    } else if (c.kind == "poly") {
      if (FindProgram("triangle").empty()) GTEST_SKIP() << "Triangle is not installed";
      testing::TempDir out;
      TriangulateOptions o;
      o.target_vertices = 1000;
      TriangulatePoly(path, out / "g", o);
    } else {
      ReadForeignTrace(path, ParseTraceFormat(c.kind), [](uint64_t, uint32_t, bool, bool) {});
    }
    FAIL() << c.file << " was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path) << e.what();
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_NE(e.problem().find(c.message), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << c.message;
  }
}

INSTANTIATE_TEST_SUITE_P(Data, BrokenInput, ::testing::ValuesIn(CoreBrokenCases()),
                         [](const ::testing::TestParamInfo<BrokenCase>& i) {
                           std::string n = i.param.file;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

TEST(BrokenInput, ManifestIsComplete) {
  // Every broken file is named in EXPECTED (a .node/.ele pair counts once).
  std::set<std::string> listed;
  for (const BrokenCase& c : BrokenCases()) listed.insert(fs::path(c.file).stem().string());
  for (const auto& e : fs::directory_iterator(DataPath("broken"))) {
    if (e.path().filename() == "EXPECTED" || e.path().extension() == ".py") continue;
    EXPECT_TRUE(listed.count(e.path().stem().string())) << e.path() << " is not in EXPECTED";
  }
  EXPECT_GE(listed.size(), 45u);
}

using testing::TempDir;

TEST(Writers, TriangleRoundTripIsExact) {
  SyntheticOptions o;
  o.nx = 13, o.ny = 9, o.holes = 2, o.seed = 7;
  const Mesh m = BuildMesh(MakeSyntheticMesh(o));
  TempDir dir;
  const std::vector<std::string> files = WriteMesh(m, dir / "round");
  EXPECT_EQ(files, (std::vector<std::string>{dir / "round.node", dir / "round.ele"}));
  ExpectSameMesh(m, ReadMesh(dir / "round"));
}

TEST(Writers, VtkHasPointsCellsAndQuality) {
  const Mesh m = testing::TwoInterior();
  TempDir dir;
  WriteMesh(m, dir / "m.vtk");
  std::ifstream in(dir / "m.vtk");
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(all.rfind("# vtk DataFile Version 3.0\n", 0), 0u);
  EXPECT_NE(all.find("POINTS 8 double\n0 0 0\n2 0 0\n"), std::string::npos);
  EXPECT_NE(all.find("CELLS 8 32\n3 0 1 6\n"), std::string::npos);
  EXPECT_NE(all.find("CELL_TYPES 8\n5\n"), std::string::npos);
  EXPECT_NE(all.find("SCALARS vertex_quality double 1"), std::string::npos);
  EXPECT_NE(all.find("SCALARS boundary int 1"), std::string::npos);
}

TEST(Writers, AtomicWriteLeavesNothingOnFailure) {
  TempDir dir;
  EXPECT_THROW(WriteAtomically(dir / "x.txt",
                               [](std::FILE* f) {
                                 std::fputs("half", f);
                                 throw std::runtime_error("interrupted");
                               }),
               std::runtime_error);
  EXPECT_TRUE(fs::is_empty(dir.path()));
  WriteAtomically(dir / "x.txt", [](std::FILE* f) { std::fputs("whole", f); });
  std::ifstream in(dir / "x.txt");
  std::string s;
  in >> s;
  EXPECT_EQ(s, "whole");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(Writers, AnOutputInAMissingFolderIsRefused) {
  EXPECT_THROW(WriteMesh(testing::TwoInterior(), "/nonexistent-dir/m.vtk"), UsageError);
}

// Hostile inputs that cannot live in tests/data as files (issue 8's reproducers 6, 10, 14, 15).
// hostile inputs

TEST(HostileInput, ByteOrderMarkIsSkipped) {
  testing::TempDir tmp;
  for (const char* ext : {".node", ".ele"}) {
    std::ifstream in(DataPath(std::string("two_interior") + ext), std::ios::binary);
    std::ofstream(tmp / (std::string("bom") + ext), std::ios::binary)
        << "\xEF\xBB\xBF" << in.rdbuf();
  }
  const Mesh a = ReadMesh(tmp / "bom.node"), b = testing::TwoInterior();
  EXPECT_EQ(a.xy, b.xy);
  EXPECT_TRUE(std::equal(a.tri.begin(), a.tri.end(), b.tri.begin(), b.tri.end()));
}

TEST(HostileInput, DirectoriesAndDevicesAreRefusedByName) {
  testing::TempDir tmp;
  fs::create_directory(tmp / "dir.msh");
  fs::create_symlink("/dev/zero", tmp / "zero.node");
  fs::create_symlink("/dev/zero", tmp / "zero.ele");
  auto expect = [](const std::function<void()>& read, const std::string& path,
                   const std::string& what) {
    try {
      read();
      ADD_FAILURE() << path << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_NE(e.problem().find(what), std::string::npos) << e.what();
    }
  };
  expect([&] { ReadMesh(tmp / "dir.msh"); }, tmp / "dir.msh", "is a directory, not a file");
  expect([&] { ReadMesh(tmp / "zero.node"); }, tmp / "zero.node", "is a character device");
  expect([&] { ComputeOrdering("file:/dev/zero", testing::TwoInterior(), 1); }, "/dev/zero",
         "is a character device");
  for (const TraceFormat& f : TraceFormats())
    expect([&] { ReadForeignTrace(tmp.path().string(), f, [](uint64_t, uint32_t, bool, bool) {}); },
           tmp.path().string(), "is a directory, not a file");
  expect([&] { TraceReader r(tmp.path().string()); }, tmp.path().string(), "is a directory");
}

TEST(HostileInput, CoordinatesNearTheLimitStayFiniteEverywhere) {
  // The tiny mesh scaled to 1e149: accepted, quality finite, every ordering runs (UBSan checks
  // the float-to-int conversions of the space-filling curves in the sanitizer build).
  RawMesh raw = ReadRawMesh(DataPath("two_interior.node"));
  for (double& c : raw.xy) c = c * 1e149 - 2e149;
  Mesh m = BuildMesh(std::move(raw));
  const QualitySummary q = SummarizeVertexQuality(m);
  EXPECT_TRUE(std::isfinite(q.mean));
  EXPECT_GT(q.min, 0.0);
  for (const OrderingInfo& o : Orderings())
    if (!o.takes_argument()) {
      EXPECT_EQ(ComputeOrdering(o.name, m, 1).size(), m.NumVertices()) << o.name;
    }
}

}  // namespace
}  // namespace meshreuse
