// The ecosystem's trace formats read as documented: lackey (data only by default, a modify is a
// load and a store, sizes kept so a straddle touches two lines), oracleGeneral (the id at byte 4
// of 24), PARDA's binary (= u64), and zstd compression of any of them and of our own traces
// (read back byte for byte; the analysis of a compressed trace equals the plain one's).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "analysis/trace_analysis.h"
#include "core/smoother.h"
#include "tests/test_util.h"
#include "tracer/input_stream.h"
#include "tracer/trace_reader.h"
#include "tracer/trace_writer.h"

namespace meshreuse {
namespace {

using Access = std::pair<uint64_t, uint32_t>;

std::vector<Access> Read(const std::string& path, ExternalFormat f, bool instructions = false) {
  std::vector<Access> out;
  ReadExternalTrace(
      path, f, [&](uint64_t v, uint32_t s) { out.emplace_back(v, s); }, instructions);
  return out;
}

void Write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(TraceFormats, Lackey) {
  testing::TempDir dir;
  Write(dir / "t.lackey",
        "==4242== Lackey, an example Valgrind tool\n"
        "--4242-- a valgrind note\n"
        "I  0040a1b0,3\n"
        " L 7ff0001c8,8\n"
        " S 1000,4\n"
        " M 203e,4\n"  // a modify that straddles lines 0x80 and 0x81 (64-byte lines)
        "\n");
  EXPECT_EQ(Read(dir / "t.lackey", ExternalFormat::kLackey),
            (std::vector<Access>{{0x7ff0001c8, 8}, {0x1000, 4}, {0x203e, 4}, {0x203e, 4}}));
  EXPECT_EQ(Read(dir / "t.lackey", ExternalFormat::kLackey, true).front(), Access(0x40a1b0, 3));
  // Through the analyzer: the straddling modify touches lines 0x80 and 0x81 twice each.
  TraceAnalysisOptions o;
  o.granularity = Granularity::kLine;
  TraceAnalysis a(o);
  ReadExternalTrace(dir / "t.lackey", ExternalFormat::kLackey,
                    [&](uint64_t v, uint32_t s) { a.AddAccess(0, v, s); });
  a.Finish();
  EXPECT_EQ(a.line(0)->hist.accesses(), 2u + 4u);
  EXPECT_EQ(a.line(0)->sd.distinct(), 4u);
  EXPECT_EQ(a.line(0)->hist.counts()[1], 2u);  // 0x80 after 0x81, 0x81 after 0x80
}

TEST(TraceFormats, OracleGeneralAndParda) {
  testing::TempDir dir;
  std::string oracle;
  for (uint64_t id : {7ull, 9ull, 7ull}) {
    char rec[24] = {};
    const uint32_t clock = 1, size = 4096;
    const int64_t next = -1;
    std::memcpy(rec, &clock, 4);
    std::memcpy(rec + 4, &id, 8);
    std::memcpy(rec + 12, &size, 4);
    std::memcpy(rec + 16, &next, 8);
    oracle.append(rec, 24);
  }
  Write(dir / "t.oracle", oracle);
  EXPECT_EQ(Read(dir / "t.oracle", ExternalFormat::kOracle),
            (std::vector<Access>{{7, 1}, {9, 1}, {7, 1}}));
  EXPECT_EQ(ExternalTraceLength(dir / "t.oracle", ExternalFormat::kOracle), 3u);
  std::string parda(16, '\0');
  const uint64_t p[2] = {0x7fff0010, 0x7fff0018};
  std::memcpy(parda.data(), p, 16);
  Write(dir / "t.parda", parda);
  EXPECT_EQ(Read(dir / "t.parda", ExternalFormat::kParda),
            (std::vector<Access>{{0x7fff0010, 1}, {0x7fff0018, 1}}));
  EXPECT_EQ(ParseExternalFormat("oracleGeneral"), ExternalFormat::kOracle);
  EXPECT_THROW(ParseExternalFormat("csv"), std::invalid_argument);
}

TEST(TraceFormats, ZstdIsReadTransparently) {
  testing::TempDir dir;
  std::string text;
  for (int i = 0; i < 300000; ++i) text += std::to_string(i % 777) + "\n";
  Write(dir / "t.txt", text);
  CompressFile(dir / "t.txt", dir / "t.txt.zst");
  EXPECT_LT(std::filesystem::file_size(dir / "t.txt.zst"), text.size() / 10);
  {
    InputStream in(dir / "t.txt.zst");
    EXPECT_TRUE(in.compressed());
    EXPECT_EQ(in.size(), static_cast<int64_t>(text.size()));  // from the frame header
    std::string back(text.size() + 10, '\0');
    size_t got = 0, n;
    while ((n = in.Read(back.data() + got, 4097)) > 0) got += n;
    back.resize(got);
    EXPECT_EQ(back, text);
  }
  EXPECT_EQ(Read(dir / "t.txt.zst", ExternalFormat::kText),
            Read(dir / "t.txt", ExternalFormat::kText));
  // Binary formats count their records from the decompressed size.
  std::string u64(8 * 1000, '\0');
  for (uint64_t i = 0; i < 1000; ++i) std::memcpy(u64.data() + 8 * i, &i, 8);
  Write(dir / "t.u64", u64);
  CompressFile(dir / "t.u64", dir / "t.u64.zst");
  EXPECT_EQ(ExternalTraceLength(dir / "t.u64.zst", ExternalFormat::kU64), 1000u);
  EXPECT_EQ(Read(dir / "t.u64.zst", ExternalFormat::kU64),
            Read(dir / "t.u64", ExternalFormat::kU64));
}

TEST(TraceFormats, CompressedTraceFileReadsLikeThePlainOne) {
  testing::TempDir dir;
  Mesh m = testing::TwoInterior();
  TraceHeader h;
  h.threads = 1;
  h.vertices = static_cast<uint32_t>(m.NumVertices());
  {
    TraceWriter w(dir / "t.trace", h, 3);
    SmoothOptions o;
    o.max_iters = 3;
    o.tol = -1;
    Smooth(m, o, w);
    w.Close();
  }
  CompressFile(dir / "t.trace", dir / "t.trace.zst");
  EXPECT_TRUE(TraceReader::LooksLikeTrace(dir / "t.trace.zst"));
  TraceReader a(dir / "t.trace"), b(dir / "t.trace.zst");
  EXPECT_EQ(a.header().records, b.header().records);
  EXPECT_EQ(a.header().sweep_elements, b.header().sweep_elements);
  std::vector<TraceRecord> x, y;
  while (a.Next(&x, 7)) {
    ASSERT_TRUE(b.Next(&y, 7));
    ASSERT_EQ(x.size(), y.size());
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(TraceRecord)), 0);
  }
  EXPECT_FALSE(b.Next(&y, 7));
}

}  // namespace
}  // namespace meshreuse
