// The .vtu writer (core/vtu_io.h) read back by a decoder written here from VTK's format notes: the
// XML names each array's type and offset into the appended data; there, a compressed array is a
// UInt64 header [blocks, block bytes, last block's bytes or 0, each block's compressed size] and
// the zlib blocks. Every array decodes to the bytes it was given: one-block and several-block
// arrays (a partial last block and a full one), every type, an empty grid; a regular file (its
// header rewritten in place) and a pipe (arrays held) decode alike; a wrong length is refused.
#include "core/vtu_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "tests/test_util.h"

namespace meshreuse {
namespace {

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

uint64_t Word(const std::string& b, size_t at) {
  uint64_t w;
  std::memcpy(&w, b.data() + at, 8);
  return w;
}

// The bytes of array `name` (its `nth` occurrence in the XML), and its type.
std::string Decode(const std::string& file, const std::string& name, std::string* type = nullptr,
                   std::vector<uint64_t>* header = nullptr) {
  const size_t tag = file.find("Name=\"" + name + "\"");
  if (tag == std::string::npos) return "<no array " + name + ">";
  const size_t open = file.rfind('<', tag), close = file.find('>', tag);
  const std::string element = file.substr(open, close - open);
  auto attr = [&element](const std::string& a) {
    const size_t at = element.find(a + "=\"");
    if (at == std::string::npos) return std::string();
    const size_t b = at + a.size() + 2;
    return element.substr(b, element.find('"', b) - b);
  };
  if (type) *type = attr("type");
  const size_t data = file.find("<AppendedData encoding=\"raw\">");
  const size_t base = file.find('_', data) + 1;
  const size_t at = base + std::stoull(attr("offset"));
  const uint64_t blocks = Word(file, at), block = Word(file, at + 8), last = Word(file, at + 16);
  if (header) {
    header->clear();
    for (uint64_t i = 0; i < 3 + blocks; ++i) header->push_back(Word(file, at + 8 * i));
  }
  size_t p = at + 8 * (3 + blocks);
  std::string out;
  for (uint64_t i = 0; i < blocks; ++i) {
    const uint64_t csize = Word(file, at + 8 * (3 + i));
    uLongf n = (i + 1 == blocks && last != 0) ? last : block;
    std::string raw(n, '\0');
    EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(&raw[0]), &n,
                         reinterpret_cast<const Bytef*>(file.data() + p), csize),
              Z_OK);
    raw.resize(n);
    out += raw;
    p += csize;
  }
  return out;
}

template <class T>
std::string Bytes(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

struct Fixture {
  std::vector<double> xy;
  std::vector<int32_t> tri;
  std::vector<uint8_t> u8;
  std::vector<int64_t> i64;
  std::vector<float> f32;
  std::vector<double> f64;  // 2 components
  VtuGrid grid;
  explicit Fixture(int32_t n) {
    for (int32_t i = 0; i < n; ++i) {
      xy.push_back(i * 0.5 + 1e-9 * i * i);
      xy.push_back(-i / 3.0);
      u8.push_back(static_cast<uint8_t>(i * 7));
      i64.push_back(int64_t{i} * 1000003 - (int64_t{1} << 40));
      f32.push_back(static_cast<float>(i) / 7.0f);
      f64.push_back(i * 1.25);
      f64.push_back(1.0 / (i + 1));
    }
    for (int32_t t = 0; t + 2 < n; ++t) tri.insert(tri.end(), {t, t + 1, t + 2});
    grid.points = n, grid.xy = xy.data();
    grid.cells = static_cast<int64_t>(tri.size() / 3), grid.tri = tri.data();
    grid.point_data.push_back(VtuArrayOf("u8", u8.data(), n));
    grid.point_data.push_back(VtuArrayOf("i64", i64.data(), n));
    grid.point_data.push_back(VtuArrayOf("f32", f32.data(), n));
    grid.point_data.push_back(VtuArrayOf("f64", f64.data(), n, 2));
    grid.global_ids = "i64";
  }
  std::string Points() const {
    std::vector<double> p;
    for (size_t i = 0; i < xy.size(); i += 2) p.insert(p.end(), {xy[i], xy[i + 1], 0.0});
    return Bytes(p);
  }
};

void ExpectDecodes(const std::string& file, const Fixture& f) {
  std::string type;
  EXPECT_EQ(Decode(file, "u8", &type), Bytes(f.u8));
  EXPECT_EQ(type, "UInt8");
  EXPECT_EQ(Decode(file, "i64", &type), Bytes(f.i64));
  EXPECT_EQ(type, "Int64");
  EXPECT_EQ(Decode(file, "f32", &type), Bytes(f.f32));
  EXPECT_EQ(type, "Float32");
  EXPECT_EQ(Decode(file, "f64", &type), Bytes(f.f64));
  EXPECT_EQ(type, "Float64");
  EXPECT_EQ(Decode(file, "Points", &type), f.Points());
  EXPECT_EQ(Decode(file, "connectivity", &type), Bytes(f.tri));
  EXPECT_EQ(type, "Int32");
  std::vector<int32_t> offsets, types;
  for (int64_t c = 0; c < f.grid.cells; ++c) offsets.push_back(static_cast<int32_t>(3 * (c + 1)));
  EXPECT_EQ(Decode(file, "offsets", &type), Bytes(offsets));
  EXPECT_EQ(Decode(file, "types", &type), std::string(f.grid.cells, '\5'));
  EXPECT_NE(file.find("<PointData GlobalIds=\"i64\">"), std::string::npos);
  EXPECT_NE(file.find("NumberOfPoints=\"" + std::to_string(f.grid.points) + "\""),
            std::string::npos);
}

TEST(Vtu, EveryArrayDecodesToItsBytes) {
  ASSERT_TRUE(VtuCompressed());  // zlib is a build requirement here (Scotch needs it too)
  const testing::TempDir dir;
  for (int32_t n : {3, 1000, 100000}) {
    SCOPED_TRACE(n);
    const Fixture f(n);
    const std::string path = dir / "g.vtu";
    WriteVtu(f.grid, path);
    ExpectDecodes(Slurp(path), f);
  }
}

TEST(Vtu, BlocksFollowVtksHeader) {
  const testing::TempDir dir;
  // Points are 24-byte tuples: 43,690 to a 1 MiB block. 100,000 points: two full blocks and a
  // partial one; 87,380: exactly two full blocks (the last block's size is then 0).
  for (int32_t n : {100000, 87380}) {
    const Fixture f(n);
    WriteVtu(f.grid, dir / "b.vtu");
    std::vector<uint64_t> h;
    EXPECT_EQ(Decode(Slurp(dir / "b.vtu"), "Points", nullptr, &h), f.Points());
    ASSERT_GE(h.size(), 3u);
    EXPECT_EQ(h[0], n == 100000 ? 3u : 2u);
    EXPECT_EQ(h[1], 43690u * 24);
    EXPECT_EQ(h[2], n == 100000 ? (100000u - 2 * 43690) * 24 : 0u);
  }
}

TEST(Vtu, AnEmptyGridHasZeroBlocks) {
  const testing::TempDir dir;
  const Fixture f(0);
  WriteVtu(f.grid, dir / "e.vtu");
  const std::string file = Slurp(dir / "e.vtu");
  std::vector<uint64_t> h;
  EXPECT_EQ(Decode(file, "Points", nullptr, &h), "");
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0], 0u);
  EXPECT_NE(file.find("NumberOfPoints=\"0\" NumberOfCells=\"0\""), std::string::npos);
}

TEST(Vtu, APipeGetsTheSameArrays) {
  const testing::TempDir dir;
  const Fixture f(50000);
  const std::string fifo = dir / "p.vtu";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string piped;
  std::thread reader([&] { piped = Slurp(fifo); });
  WriteVtu(f.grid, fifo);
  reader.join();
  ExpectDecodes(piped, f);
}

TEST(Vtu, ALengthThatIsNotTheGridsIsRefused) {
  const testing::TempDir dir;
  Fixture f(10);
  f.grid.cell_data.push_back(VtuArrayOf("short", f.f32.data(), 3));
  EXPECT_THROW(WriteVtu(f.grid, dir / "x.vtu"), std::invalid_argument);
  EXPECT_NE(::access((dir / "x.vtu").c_str(), F_OK), 0);
}

TEST(Vtu, PvtuDeclaresThePiecesArrays) {
  const testing::TempDir dir;
  const Fixture f(5);
  WritePvtu(dir / "g.pvtu", {"g_0.vtu", "g_1.vtu"}, f.grid);
  const std::string x = Slurp(dir / "g.pvtu");
  EXPECT_NE(x.find("<PUnstructuredGrid GhostLevel=\"1\">"), std::string::npos);
  EXPECT_NE(x.find("<PPointData GlobalIds=\"i64\">"), std::string::npos);
  EXPECT_NE(x.find("<PDataArray type=\"Float64\" Name=\"f64\" NumberOfComponents=\"2\"/>"),
            std::string::npos);
  EXPECT_NE(x.find("<Piece Source=\"g_0.vtu\"/>\n    <Piece Source=\"g_1.vtu\"/>"),
            std::string::npos);
}

}  // namespace
}  // namespace meshreuse
