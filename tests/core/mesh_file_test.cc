// The distributed mesh file (core/mesh_file.h): what is written is what the mesh holds, section by
// section against the mesh's own arrays and a literal size formula; reads of ranges and scattered
// elements equal element-by-element reads; and every damaged file is refused by name -- truncated,
// trailing bytes, another magic, a damaged header, a block whose bytes changed (only when a read
// touches it), a table from another mesh, a folder -- while a damage mended with fresh hashes
// reaches BuildMesh's checks.
#include "core/mesh_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/synthetic.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {
using namespace testing;

int64_t Pad8(int64_t n) { return (n + 7) / 8 * 8; }
int64_t DataEnd(int64_t v, int64_t t) {
  return 128 + 16 * v + Pad8(v) + 8 * (v + 1) + 2 * Pad8(12 * t);
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

Mesh Bigger() {
  SyntheticOptions o;
  o.nx = 90, o.ny = 70, o.holes = 2, o.graded = true, o.seed = 5;
  return BuildMesh(MakeSyntheticMesh(o));
}

TEST(MeshFile, SectionsAreTheMeshsArraysAndTheSizeIsTheLayouts) {
  TempDir dir;
  std::vector<Mesh> meshes = MeshCorpus();
  meshes.push_back(Bigger());
  for (const Mesh& m : meshes) {
    const std::string p = dir / "m.mrm";
    WriteMeshFile(m, p);
    const int64_t v = m.NumVertices(), t = m.NumTriangles();
    const int64_t end = DataEnd(v, t);
    const int64_t blocks = (end - 128 + 4095) / 4096, pages = (blocks + 511) / 512;
    EXPECT_EQ(static_cast<int64_t>(ReadBytes(p).size()), end + 8 * blocks + 8 * pages);
    MeshFile f(p);
    ASSERT_EQ(f.vertices(), v);
    ASSERT_EQ(f.triangles(), t);
    std::vector<double> xy(2 * v);
    std::vector<uint8_t> boundary(v);
    std::vector<int64_t> off(v + 1);
    std::vector<int32_t> v2t(3 * t), tri(3 * t);
    f.Read(MeshFile::kXy, 0, v, xy.data());
    f.Read(MeshFile::kBoundary, 0, v, boundary.data());
    f.Read(MeshFile::kV2tOff, 0, v + 1, off.data());
    f.Read(MeshFile::kV2t, 0, 3 * t, v2t.data());
    f.Read(MeshFile::kTri, 0, t, tri.data());
    EXPECT_EQ(std::memcmp(xy.data(), m.xy.data(), 16 * v), 0);
    EXPECT_EQ(boundary, m.boundary);
    EXPECT_TRUE(std::equal(off.begin(), off.end(), m.v2t.off.begin()));
    EXPECT_TRUE(std::equal(v2t.begin(), v2t.end(), m.v2t.idx.begin()));
    EXPECT_TRUE(std::equal(tri.begin(), tri.end(), m.tri.begin()));
    // The serial reader: the same mesh, bit for bit.
    const Mesh back = ReadMesh(p);
    EXPECT_EQ(std::memcmp(back.xy.data(), m.xy.data(), 16 * v), 0);
    EXPECT_TRUE(std::equal(back.tri.begin(), back.tri.end(), m.tri.begin(), m.tri.end()));
    EXPECT_EQ(back.boundary, m.boundary);
    EXPECT_TRUE(
        std::equal(back.v2v.idx.begin(), back.v2v.idx.end(), m.v2v.idx.begin(), m.v2v.idx.end()));
  }
}

TEST(MeshFile, RehashingAWrittenFileChangesNothing) {
  TempDir dir;
  const std::string p = dir / "m.mrm";
  WriteMeshFile(Bigger(), p);
  const std::string b = ReadBytes(p);
  EXPECT_TRUE(RehashMeshFile(b) == b);
  std::string x = b;
  x[200] ^= 1;
  EXPECT_FALSE(RehashMeshFile(x) ==
               x);  // the damaged block's hash, the page's, the id, the header's
  const Mesh m = Bigger();
  const size_t end = static_cast<size_t>(DataEnd(m.NumVertices(), m.NumTriangles()));
  EXPECT_TRUE(RehashMeshFile(x).compare(128, end - 128, x, 128, end - 128) == 0)
      << "only hashes change: the data stays";
}

TEST(MeshFile, RangesAndScatteredReadsEqualElementReads) {
  TempDir dir;
  const Mesh m = Bigger();
  const std::string p = dir / "m.mrm";
  WriteMeshFile(m, p);
  MeshFile f(p);
  std::mt19937_64 rng(3);
  for (int s = 0; s < MeshFile::kSections; ++s) {
    const auto sec = static_cast<MeshFile::Section>(s);
    const int64_t n = f.Elements(sec), eb = f.ElementBytes(sec);
    std::vector<char> all(static_cast<size_t>(n * eb));
    f.Read(sec, 0, n, all.data());
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<int64_t> at;
      const int k = 1 + static_cast<int>(rng() % 200);
      for (int i = 0; i < k; ++i) at.push_back(static_cast<int64_t>(rng() % n));
      std::sort(at.begin(), at.end());
      std::vector<char> got(at.size() * eb), one(eb);
      f.ReadAt(sec, at, got.data());
      for (size_t i = 0; i < at.size(); ++i) {
        f.Read(sec, at[i], 1, one.data());
        EXPECT_EQ(std::memcmp(got.data() + i * eb, one.data(), eb), 0);
        EXPECT_EQ(std::memcmp(got.data() + i * eb, all.data() + at[i] * eb, eb), 0);
      }
      const int64_t first = static_cast<int64_t>(rng() % n);
      const int64_t count = static_cast<int64_t>(rng() % (n - first + 1));
      std::vector<char> range(static_cast<size_t>(count * eb));
      f.Read(sec, first, count, range.data());
      if (count) {
        EXPECT_EQ(std::memcmp(range.data(), all.data() + first * eb, count * eb), 0);
      }
    }
  }
}

// Runs of elements (a scattered part's runs of consecutive ids): what each run's elements are,
// empty and adjoining runs included; no more bytes read than reading each run alone (blocks that
// runs share are read once).
TEST(MeshFile, RunsEqualElementReadsAndReadEachBlockOnce) {
  TempDir dir;
  const Mesh m = Bigger();
  const std::string p = dir / "m.mrm";
  WriteMeshFile(m, p);
  std::mt19937_64 rng(5);
  for (int s = 0; s < MeshFile::kSections; ++s) {
    const auto sec = static_cast<MeshFile::Section>(s);
    MeshFile whole(p);
    const int64_t n = whole.Elements(sec), eb = whole.ElementBytes(sec);
    std::vector<char> all(static_cast<size_t>(n * eb));
    whole.Read(sec, 0, n, all.data());
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<int64_t> first, end;
      int64_t at = static_cast<int64_t>(rng() % 50);
      while (at < n) {
        const int64_t len = std::min<int64_t>(n - at, static_cast<int64_t>(rng() % 40));
        first.push_back(at), end.push_back(at + len);
        at += len + static_cast<int64_t>(rng() % 3 == 0 ? 0 : rng() % 300);
      }
      std::vector<char> want;
      for (size_t i = 0; i < first.size(); ++i)
        want.insert(want.end(), all.begin() + first[i] * eb, all.begin() + end[i] * eb);
      MeshFile f(p);
      const uint64_t before = f.bytes_read();
      std::vector<char> got(want.size() + 1);
      f.ReadRuns(sec, first, end, got.data());
      EXPECT_EQ(std::memcmp(got.data(), want.data(), want.size()), 0) << s << " " << trial;
      MeshFile g(p);
      const uint64_t g0 = g.bytes_read();
      for (size_t i = 0; i < first.size(); ++i)
        if (end[i] > first[i]) g.Read(sec, first[i], end[i] - first[i], got.data());
      EXPECT_LE(f.bytes_read() - before, g.bytes_read() - g0) << s << " " << trial;
    }
    // One run of everything, and runs that misbehave.
    MeshFile f(p);
    std::vector<char> got(all.size() + 1);
    f.ReadRuns(sec, {0}, {n}, got.data());
    EXPECT_EQ(std::memcmp(got.data(), all.data(), all.size()), 0);
    EXPECT_THROW(f.ReadRuns(sec, {5, 2}, {6, 3}, got.data()), std::logic_error);
    EXPECT_THROW(f.ReadRuns(sec, {0}, {n + 1}, got.data()), std::logic_error);
    EXPECT_THROW(f.ReadRuns(sec, {3}, {2}, got.data()), std::logic_error);
  }
}

TEST(MeshFile, DamagedFilesAreRefusedByName) {
  TempDir dir;
  const Mesh m = Bigger();
  const std::string good = dir / "good.mrm", bad = dir / "bad.mrm";
  WriteMeshFile(m, good);
  const std::string b = ReadBytes(good);
  auto refuse = [&](const std::string& bytes, const std::string& expect) {
    WriteBytes(bad, bytes);
    const std::string e = ErrorOf([&] { ReadMeshFileRaw(bad); });
    EXPECT_TRUE(HasText(e, bad + ": ")) << e << expect;
    EXPECT_TRUE(HasText(e, expect)) << e;
  };
  refuse(b.substr(0, b.size() - 1), "truncated: ");
  refuse(b.substr(0, 100), "shorter than the 128-byte header");
  refuse(b + "x", "trailing bytes: ");
  std::string x = b;
  x[0] = 'X';
  refuse(x, "not a meshreuse mesh file");
  x = b;
  x[17] ^= 1;  // the vertex count
  refuse(x, "the header's hash does not match");
  x = b;
  x[8] = 2;  // version 2, hashes mended
  refuse(RehashMeshFile(x), "version 2");
  x = b;
  x[b.size() - 3] ^= 1;  // the page table
  refuse(x, "does not belong to this header's content id");
  x = b;
  x[DataEnd(m.NumVertices(), m.NumTriangles()) + 9] ^= 1;  // block 1's hash: page 0
  refuse(x, "page 0 of the block table does not match its hash");
  // A flipped byte in the triangles: refused when read, naming its block; the coordinates before
  // it still read.
  const int64_t v = m.NumVertices(), t = m.NumTriangles();
  const int64_t at = 128 + 16 * v + Pad8(v) + 8 * (v + 1) + Pad8(12 * t) + 12 * (t / 2);
  x = b;
  x[at] ^= 4;
  const int64_t block = (at - 128) / kMeshFileBlock;
  refuse(x, "block " + std::to_string(block) + " (bytes " +
                std::to_string(128 + block * kMeshFileBlock) + "..");
  {
    MeshFile f(bad);
    std::vector<double> xy(2 * v);
    EXPECT_NO_THROW(f.Read(MeshFile::kXy, 0, v, xy.data()));
    std::vector<int32_t> tri(3 * t);
    EXPECT_TRUE(HasText(ErrorOf([&] { f.Read(MeshFile::kTri, 0, t, tri.data()); }),
                        "does not match its hash"))
        << ErrorOf([&] { f.Read(MeshFile::kTri, 0, t, tri.data()); });
  }
  // Mended damage reaches the mesh's own checks: a corner out of range, a non-finite coordinate.
  x = b;
  const int32_t huge = 1 << 30;
  std::memcpy(&x[at - at % 4], &huge, 4);
  refuse(RehashMeshFile(x), "outside 0..");
  x = b;
  const double nan = std::nan("");
  std::memcpy(&x[128 + 16 * 7], &nan, 8);
  WriteBytes(bad, RehashMeshFile(x));
  EXPECT_TRUE(HasText(ErrorOf([&] { ReadMesh(bad); }), "non-finite"))
      << ErrorOf([&] { ReadMesh(bad); });
  // Not a regular file.
  EXPECT_TRUE(HasText(ErrorOf([&] { MeshFile f(dir.path().string()); }), "not a regular file"))
      << ErrorOf([&] { MeshFile f(dir.path().string()); });
  EXPECT_TRUE(HasText(ErrorOf([&] { MeshFile f(dir / "missing.mrm"); }), "cannot open"))
      << ErrorOf([&] { MeshFile f(dir / "missing.mrm"); });
}

}  // namespace
}  // namespace meshreuse
