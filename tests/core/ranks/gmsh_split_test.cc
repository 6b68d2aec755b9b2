// Gmsh split sets (core/ranks/gmsh_split.h) against Gmsh itself: tests/data/plate_split_{1,2,3}.msh
// are Gmsh 4.8.4's `gmsh plate.geo -2 -part 3 -part_split -format msh41 -o plate_split.msh`, and
// the same run without -part writes tests/data/plate41.msh byte for byte. The merged set is that
// mesh (same coordinates bit for bit, same triangles, same ids: plate41's node tags increase in
// file order); each vertex's part is the lowest part holding one of its triangles, checked against
// each file read on its own; broken sets are refused by name.
#include "core/ranks/gmsh_split.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/ranks/partition.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {
using namespace testing;

std::set<std::array<int32_t, 3>> TriangleSet(const Mesh& m) {
  std::set<std::array<int32_t, 3>> s;
  for (int32_t t = 0; t < m.NumTriangles(); ++t) {
    std::array<int32_t, 3> c = {m.tri[3 * t], m.tri[3 * t + 1], m.tri[3 * t + 2]};
    std::sort(c.begin(), c.end());
    s.insert(c);
  }
  return s;
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadGmshSplit(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GmshSplit, TheMergedSetIsTheUnsplitMeshWithGmshsParts) {
  const Mesh whole = ReadMesh(DataPath("plate41.msh"));
  for (const char* any : {"plate_split_1.msh", "plate_split_3.msh"}) {
    GmshSplit s = ReadGmshSplit(DataPath(any));
    ASSERT_EQ(s.parts, 3);
    ASSERT_EQ(s.files.size(), 3u);
    EXPECT_EQ(s.files[1], DataPath("plate_split_2.msh"));
    const std::vector<int32_t> part = s.part;
    BuildReport report;
    const Mesh m = BuildMesh(std::move(s.raw), &report);
    ASSERT_TRUE(report.kept.empty());
    ASSERT_EQ(m.NumVertices(), whole.NumVertices());
    EXPECT_EQ(std::memcmp(m.xy.data(), whole.xy.data(), 8 * m.xy.size()), 0);
    EXPECT_EQ(TriangleSet(m), TriangleSet(whole));
    EXPECT_TRUE(std::equal(m.tri.begin(), m.tri.end(), whole.tri.begin(), whole.tri.end()))
        << "triangles in the unsplit file's order (increasing element tag)";
    EXPECT_EQ(m.boundary, whole.boundary);
    // The parts, by a naive reference: each file on its own, its tags, the lowest part per node.
    std::vector<int32_t> want(m.NumVertices(), INT32_MAX);
    std::vector<int64_t> per_part(3, 0);
    for (int32_t p = 0; p < 3; ++p) {
      const RawMesh r = ReadGmsh(DataPath("plate_split_" + std::to_string(p + 1) + ".msh"));
      per_part[p] = static_cast<int64_t>(r.tri.size() / 3);
      for (int32_t c : r.tri) {
        const int64_t tag = r.vertex_tag.At(c);  // plate41's tags are 1..995 in id order
        want[tag - 1] = std::min(want[tag - 1], p);
      }
    }
    EXPECT_EQ(part, want);
    EXPECT_EQ(per_part, (std::vector<int64_t>{614, 615, 615}));
    for (int32_t p = 0; p < 3; ++p) EXPECT_GT(std::count(part.begin(), part.end(), p), 200);
  }
}

// Written and read back: the same mesh, vertex for vertex and triangle for triangle, and each
// vertex in the lowest part of its triangles, a triangle being in its smallest corner's part.
TEST(GmshSplit, WrittenSetsReadBackAsTheMesh) {
  TempDir dir;
  std::vector<Mesh> meshes;
  meshes.push_back(ReadMesh(DataPath("plate41.msh")));
  for (Mesh& m : MeshCorpus()) meshes.push_back(std::move(m));
  int i = 0;
  for (const Mesh& m : meshes)
    for (int32_t P : {1, 2, 3}) {
      if (P > m.NumVertices()) continue;
      const std::vector<int32_t> part = HilbertRangeParts(m, P);
      const std::string prefix = dir / ("m" + std::to_string(i++) + "_");
      const std::vector<std::string> files = WriteGmshSplit(m, part, P, prefix);
      ASSERT_EQ(files.size(), static_cast<size_t>(P));
      GmshSplit s = ReadGmshSplit(files.back());
      ASSERT_EQ(s.parts, P);
      std::vector<int32_t> want(m.NumVertices(), INT32_MAX);
      for (int32_t t = 0; t < m.NumTriangles(); ++t) {
        const int32_t* c = &m.tri[3 * t];
        const int32_t p = part[std::min(c[0], std::min(c[1], c[2]))];
        for (int k = 0; k < 3; ++k) want[c[k]] = std::min(want[c[k]], p);
      }
      EXPECT_EQ(s.part, want);
      const Mesh back = BuildMesh(std::move(s.raw));
      ASSERT_EQ(back.NumVertices(), m.NumVertices());
      EXPECT_EQ(std::memcmp(back.xy.data(), m.xy.data(), 8 * m.xy.size()), 0);
      EXPECT_TRUE(std::equal(back.tri.begin(), back.tri.end(), m.tri.begin(), m.tri.end()));
    }
}

TEST(GmshSplit, BrokenSetsAreRefusedByName) {
  TempDir dir;
  auto copy = [&](int from, const std::string& to) {
    std::filesystem::copy_file(DataPath("plate_split_" + std::to_string(from) + ".msh"), dir / to,
                               std::filesystem::copy_options::overwrite_existing);
  };
  // Two of three parts: the files say 3, and the missing one is named.
  copy(1, "a_1.msh");
  copy(2, "a_2.msh");
  EXPECT_NE(ErrorOf(dir / "a_2.msh")
                .find((dir / "a_3.msh") + ": cannot open: part 3 of the 3 that " + (dir / "a_2.msh") +
                      " declares"),
            std::string::npos)
      << ErrorOf(dir / "a_2.msh");
  // A shared node moved in part 3.
  copy(1, "b_1.msh");
  copy(2, "b_2.msh");
  {
    std::ifstream in(DataPath("plate_split_3.msh"));
    std::string text((std::istreambuf_iterator<char>(in)), {});
    // Node 43 (0.65, 0) lies on parts 1 and 3's boundary (plate_split_1.msh's point entity 16).
    const size_t at = text.find("\n0.65 0 0\n");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 10, "\n0.65 1e-9 0\n");
    std::ofstream(dir / "b_3.msh") << text;
  }
  const std::string moved = ErrorOf(dir / "b_1.msh");
  EXPECT_NE(moved.find("node 43 has other coordinates than in " + (dir / "b_1.msh")),
            std::string::npos)
      << moved;
  // A triangle in two parts (part 1 twice).
  copy(1, "c_1.msh");
  copy(1, "c_2.msh");
  copy(3, "c_3.msh");
  EXPECT_NE(ErrorOf(dir / "c_3.msh").find("ghost elements"), std::string::npos);
  // Not a split set's name; a part beyond the set.
  EXPECT_NE(ErrorOf(DataPath("plate41.msh")).find("not a part of a Gmsh split set"),
            std::string::npos);
  EXPECT_NE(ErrorOf(DataPath("plate_split_4.msh")).find("has no part 4"), std::string::npos);
  EXPECT_TRUE(IsGmshSplitPath(DataPath("plate_split_2.msh")));
  EXPECT_FALSE(IsGmshSplitPath(DataPath("plate41.msh")));
}

}  // namespace
}  // namespace meshreuse
