// The ecosystem's trace formats (tracer/trace_formats.h) read as documented: lackey (data only by
// default, loads and stores kept apart, a modify is a load and a store, sizes kept so a straddle
// touches two lines; a file without data records refused), oracleGeneral (the id at byte 4 of
// 24), PARDA's binary (= u64), every fixed-width row of the table round-tripped, and zstd
// compression of any of them and of our own traces (read back byte for byte).
#include "tracer/foreign_trace.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <tuple>

#include "analysis/reuse_analysis.h"
#include "core/error.h"
#include "core/smoother.h"
#include "tests/test_util.h"
#include "tracer/access_stream.h"
#include "tracer/input_stream.h"
#include "tracer/trace_reader.h"
#include "tracer/trace_writer.h"

namespace meshreuse {
namespace {

using Access = std::tuple<uint64_t, uint32_t, bool>;  // value, size, store

std::vector<Access> Read(const std::string& path, const std::string& f, bool instructions = false) {
  std::vector<Access> out;
  ReadForeignTrace(
      path, ParseTraceFormat(f),
      [&](uint64_t v, uint32_t s, bool w, bool) { out.emplace_back(v, s, w); }, instructions);
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
  EXPECT_EQ(
      Read(dir / "t.lackey", "lackey"),
      (std::vector<Access>{
          {0x7ff0001c8, 8, false}, {0x1000, 4, true}, {0x203e, 4, false}, {0x203e, 4, true}}));
  EXPECT_EQ(Read(dir / "t.lackey", "lackey", true).front(), Access(0x40a1b0, 3, false));
  // Through the analyzer: the straddling modify touches lines 0x80 and 0x81 twice each.
  ReuseOptions o;
  o.granularity = Granularity::kLine;
  ReuseAnalysis a(o);
  StreamForeignTrace(dir / "t.lackey", ParseTraceFormat("lackey"), false, a);
  EXPECT_EQ(a.line(0)->hist.accesses(), 2u + 4u);
  EXPECT_EQ(a.line(0)->distinct(), 4u);
  // distance 1 twice: 0x80 after 0x81, 0x81 after 0x80
  EXPECT_EQ(a.line(0)->hist.CountAtLeast(1) - a.line(0)->hist.CountAtLeast(2), 2u);
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
  EXPECT_EQ(Read(dir / "t.oracle", "oracle"),
            (std::vector<Access>{{7, 1, false}, {9, 1, false}, {7, 1, false}}));
  EXPECT_EQ(ForeignTraceLength(dir / "t.oracle", ParseTraceFormat("oracle")), 3u);
  std::string parda(16, '\0');
  const uint64_t p[2] = {0x7fff0010, 0x7fff0018};
  std::memcpy(parda.data(), p, 16);
  Write(dir / "t.parda", parda);
  EXPECT_EQ(Read(dir / "t.parda", "parda"),
            (std::vector<Access>{{0x7fff0010, 1, false}, {0x7fff0018, 1, false}}));
  EXPECT_EQ(&ParseTraceFormat("oracleGeneral"), FindTraceFormat("oracle"));
  EXPECT_THROW(ParseTraceFormat("csv"), UsageError);
}

TEST(TraceFormats, LackeyWithoutDataRecordsIsRefused) {
  testing::TempDir dir;
  // Lackey without --trace-mem=yes writes only its summary; with it but no data, only I lines.
  Write(dir / "summary.lackey", "==1== Lackey, an example Valgrind tool\n==1== Counted 3 calls\n");
  Write(dir / "ifetch.lackey", "I  0040a1b0,3\nI  0040a1b3,2\n");
  for (const char* f : {"summary.lackey", "ifetch.lackey"}) {
    try {
      Read(dir / f, "lackey");
      ADD_FAILURE() << f << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--trace-mem=yes"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(Read(dir / "ifetch.lackey", "lackey", true).size(), 2u);  // I lines asked for
}

// Every fixed-width row of the format table: records written at the row's layout read back as
// the values, in order, with the record count known from the size; a partial record refused.
TEST(TraceFormats, EveryFixedWidthFormatRoundTrips) {
  testing::TempDir dir;
  for (const TraceFormat& f : TraceFormats()) {
    if (f.syntax != TraceSyntax::kFixedRecords) continue;
    const std::vector<uint64_t> values = {5, 0x1234, 5, 77};
    const uint64_t mask =
        f.value_bytes == 8 ? ~uint64_t{0} : (uint64_t{1} << (8 * f.value_bytes)) - 1;
    std::string bytes;
    for (uint64_t v : values) {
      std::string rec(f.record_bytes, '\xAB');  // filler around the value
      std::memcpy(rec.data() + f.value_offset, &v, f.value_bytes);
      bytes += rec;
    }
    const std::string path = dir / (std::string("t.") + f.name);
    Write(path, bytes);
    std::vector<Access> want;
    for (uint64_t v : values) want.emplace_back(v & mask, 1, false);
    EXPECT_EQ(Read(path, f.name), want) << f.name;
    EXPECT_EQ(ForeignTraceLength(path, f), values.size()) << f.name;
    Write(path, bytes + "x");
    EXPECT_THROW(Read(path, f.name), InputError) << f.name;
    EXPECT_EQ(TraceFormatByCode(f.code), &f);
  }
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
  EXPECT_EQ(Read(dir / "t.txt.zst", "text"), Read(dir / "t.txt", "text"));
  // Binary formats count their records from the decompressed size.
  std::string u64(8 * 1000, '\0');
  for (uint64_t i = 0; i < 1000; ++i) std::memcpy(u64.data() + 8 * i, &i, 8);
  Write(dir / "t.u64", u64);
  CompressFile(dir / "t.u64", dir / "t.u64.zst");
  EXPECT_EQ(ForeignTraceLength(dir / "t.u64.zst", ParseTraceFormat("u64")), 1000u);
  EXPECT_EQ(Read(dir / "t.u64.zst", "u64"), Read(dir / "t.u64", "u64"));
}

// A zstd frame written by hand (RFC 8878): one raw block; its content size recorded in one byte
// (single segment) or not at all (a window descriptor instead), as pzstd's frames do.
std::string RawFrame(const std::string& data, bool record_size) {
  std::string f = "\x28\xB5\x2F\xFD";
  if (record_size) {
    f += '\x20', f += static_cast<char>(data.size());  // single segment, 1-byte content size
  } else {
    f += '\x00', f += '\x00';  // no content size; window descriptor
  }
  const uint32_t word = 1u | static_cast<uint32_t>(data.size()) << 3;  // last block, raw
  f += static_cast<char>(word & 0xFF), f += static_cast<char>((word >> 8) & 0xFF);
  f += static_cast<char>(word >> 16);
  return f + data;
}

std::string SkippableFrame(const std::string& payload) {
  std::string f = "\x50\x2A\x4D\x18";
  for (int i = 0; i < 4; ++i) f += static_cast<char>((payload.size() >> (8 * i)) & 0xFF);
  return f + payload;
}

// As `zstd -d` reads them: every frame in turn, skippable ones (pzstd begins with one) skipped;
// the content size is known only when every frame records its own.
TEST(TraceFormats, SeveralAndSkippableZstdFrames) {
  testing::TempDir dir;
  Write(dir / "a.txt", "1\n2\n3\n");
  CompressFile(dir / "a.txt", dir / "a.zst");
  std::ifstream az(dir / "a.zst", std::ios::binary);
  const std::string a((std::istreambuf_iterator<char>(az)), std::istreambuf_iterator<char>());
  const std::string plain =
      "1\n2\n3\n"
      "4\n5\n"
      "6\n";
  Write(dir / "sized.zst", SkippableFrame("pzstd") + a + RawFrame("4\n5\n", true) +
                               SkippableFrame("") + RawFrame("6\n", true));
  Write(dir / "unsized.zst",
        SkippableFrame("x") + a + RawFrame("4\n5\n", false) + RawFrame("6\n", true));
  Write(dir / "plain.txt", plain);
  for (const char* f : {"sized.zst", "unsized.zst"}) {
    InputStream in(dir / f);
    EXPECT_TRUE(in.compressed()) << f;
    EXPECT_EQ(in.size(), std::string(f) == "sized.zst" ? static_cast<int64_t>(plain.size()) : -1);
    std::string back(100, '\0');
    back.resize(in.Read(back.data(), back.size()));
    EXPECT_EQ(back, plain) << f;
    EXPECT_EQ(Read(dir / f, "text"), Read(dir / "plain.txt", "text")) << f;
  }
  // A frame cut short: an error naming the file, not a short read.
  Write(dir / "cut.zst", a + RawFrame("4\n5\n", true).substr(0, 9));
  EXPECT_THROW(Read(dir / "cut.zst", "text"), InputError);
}

// Reading [a, b) of the content by range (SeekTo, SetLimit), as a chunk does, to the end.
std::string ReadRange(const std::string& path, uint64_t a, uint64_t b) {
  InputStream in(path);
  in.SeekTo(a);
  in.SetLimit(b - a);
  std::string out(b - a + 10, '\0');
  size_t got = 0, n;
  while ((n = in.Read(out.data() + got, 13)) > 0) got += n;
  out.resize(got);
  return out;
}

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// `trace --compress` writes independent frames that record their sizes; a range starts at the last
// frame that begins at or before it (tracer/input_stream.h): every range reads the plain bytes.
TEST(ZstdFrames, EveryRangeReadsThePlainBytes) {
  testing::TempDir dir;
  std::string text;
  for (int i = 0; i < 200; ++i) text += std::to_string(i * 7919 % 1009) + "\n";
  Write(dir / "t.txt", text);
  CompressFile(dir / "t.txt", dir / "t.zst", 3, 37);
  const size_t frames = (text.size() + 36) / 37;
  InputStream in(dir / "t.zst");
  EXPECT_TRUE(in.seekable());
  EXPECT_EQ(in.entry_points(), frames);
  EXPECT_EQ(in.size(), static_cast<int64_t>(text.size()));
  for (uint64_t a = 0; a <= text.size(); ++a) {
    EXPECT_EQ(ReadRange(dir / "t.zst", a, text.size()), text.substr(a)) << a;
    const uint64_t b = std::min<uint64_t>(text.size(), a + a % 91);
    EXPECT_EQ(ReadRange(dir / "t.zst", a, b), text.substr(a, b - a)) << a << " " << b;
  }
  // Cut into chunks at any place, in lines, every format reads what the whole read does.
  for (uint64_t p = 1; p <= 5; ++p) {
    std::vector<Access> parts;
    for (uint64_t r = 0; r < p; ++r) {
      ReadForeignTrace(
          dir / "t.zst", ParseTraceFormat("text"),
          [&](uint64_t v, uint32_t z, bool w, bool) { parts.emplace_back(v, z, w); }, false,
          text.size() * r / p, text.size() * (r + 1) / p);
    }
    EXPECT_EQ(parts, Read(dir / "t.txt", "text")) << p;
  }
  // One frame: entered at its start, decompressed up to the range.
  CompressFile(dir / "t.txt", dir / "one.zst", 3, kZstdMaxFrameBytes);
  EXPECT_EQ(InputStream(dir / "one.zst").entry_points(), 1u);
  EXPECT_EQ(ReadRange(dir / "one.zst", 500, 600), text.substr(500, 100));
  // A frame without its size (as pzstd writes them): no range, by name.
  Write(dir / "unsized.zst", RawFrame("4\n5\n", false));
  EXPECT_FALSE(InputStream(dir / "unsized.zst").seekable());
  try {
    ReadRange(dir / "unsized.zst", 1, 3);
    ADD_FAILURE() << "an unsized frame entered in the middle";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("decompress it first"), std::string::npos) << e.what();
  }
}

// Damage that only decompressing finds (a checksum; an empty frame whose block holds a byte):
// however the content is cut in two, one of the ranges fails, as the whole read does.
TEST(ZstdFrames, DamageFailsSomeRangeWhereverTheCut) {
  testing::TempDir dir;
  std::string text;
  for (int i = 0; i < 60; ++i) text += std::to_string(i) + "\n";
  Write(dir / "t.txt", text);
  CompressFile(dir / "t.txt", dir / "t.zst", 3, 40);
  const std::string good = Slurp(dir / "t.zst");
  ASSERT_GE(InputStream(dir / "t.zst").entry_points(), 4u);
  // Where the second and third frames begin (their magic numbers); the second frame's checksum is
  // the 4 bytes before the third.
  std::vector<size_t> starts;
  for (size_t at = 4; at + 4 <= good.size() && starts.size() < 2; ++at)
    if (good.compare(at, 4, "\x28\xB5\x2F\xFD") == 0) starts.push_back(at);
  ASSERT_EQ(starts.size(), 2u);
  std::string bad_sum = good;
  bad_sum[starts[1] - 1] ^= 0x5A;
  // An empty frame (content size 0) holding one raw byte, between the first two frames.
  std::string empty_bad = std::string("\x28\xB5\x2F\xFD\x20\x00", 6);
  const uint32_t word = 1u | 1u << 3;  // last block, raw, 1 byte
  empty_bad += static_cast<char>(word & 0xFF), empty_bad += '\0', empty_bad += '\0';
  empty_bad += 'x';
  const std::string bad_empty = good.substr(0, starts[0]) + empty_bad + good.substr(starts[0]);
  for (const auto& [name, bytes] :
       {std::pair{"sum.zst", bad_sum}, std::pair{"empty.zst", bad_empty}}) {
    Write(dir / name, bytes);
    EXPECT_THROW(Read(dir / name, "text"), InputError) << name;
    InputStream in(dir / name);
    ASSERT_TRUE(in.seekable()) << name;
    for (uint64_t cut = 0; cut <= text.size(); ++cut) {
      int failed = 0;
      for (auto [a, b] : {std::pair{uint64_t{0}, cut}, std::pair{cut, uint64_t{text.size()}}}) {
        try {
          ReadRange(dir / name, a, b);
        } catch (const InputError&) {
          ++failed;
        }
      }
      EXPECT_GE(failed, 1) << name << " cut at " << cut;
    }
  }
}

// zstd's seekable format: a skippable frame holding each frame's compressed and content sizes,
// the frame count, a descriptor and the magic 0x8F92EAB1 (written by hand here, as the spec
// lays it out).
std::string SeekTable(const std::vector<std::pair<uint32_t, uint32_t>>& frames,
                      unsigned char descriptor = 0) {
  std::string t;
  auto put = [&t](uint32_t v) {
    for (int i = 0; i < 4; ++i) t += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  put(0x184D2A5E);
  put(static_cast<uint32_t>(frames.size() * 8 + 9));
  for (auto [c, d] : frames) put(c), put(d);
  put(static_cast<uint32_t>(frames.size()));
  t += static_cast<char>(descriptor);
  put(0x8F92EAB1);
  return t;
}

// A seek table is read instead of walking every block; it agrees with the walk, makes frames that
// do not record their sizes enterable, and is checked against the frames as they are
// decompressed: a table that lies fails the whole read, and one of the two ranges wherever the
// content is cut. A table that is not well formed is ignored (the frames are walked).
TEST(ZstdFrames, SeekTable) {
  testing::TempDir dir;
  std::string text;
  for (int i = 0; i < 40; ++i) text += std::to_string(i * 37 % 101) + "\n";
  Write(dir / "t.txt", text);
  CompressFile(dir / "t.txt", dir / "t.zst", 3, 20);  // with its seek table
  const std::string with = Slurp(dir / "t.zst");
  const size_t frames = (text.size() + 19) / 20, table = 17 + 8 * frames;
  ASSERT_EQ(with.compare(with.size() - 4, 4, "\xB1\xEA\x92\x8F"), 0);
  const std::string without = with.substr(0, with.size() - table);
  Write(dir / "walked.zst", without);
  // Each frame's compressed size, from the table just written.
  std::vector<std::pair<uint32_t, uint32_t>> sizes;
  for (size_t f = 0; f < frames; ++f) {
    const char* e = with.data() + with.size() - table + 8 + 8 * f;
    uint32_t c, d;
    std::memcpy(&c, e, 4), std::memcpy(&d, e + 4, 4);
    sizes.emplace_back(c, d);
  }
  for (const char* f : {"t.zst", "walked.zst"}) {
    InputStream in(dir / f);
    EXPECT_EQ(in.entry_points(), frames) << f;
    EXPECT_EQ(in.size(), static_cast<int64_t>(text.size())) << f;
    for (uint64_t a = 0; a <= text.size(); a += 7)
      EXPECT_EQ(ReadRange(dir / f, a, std::min<uint64_t>(text.size(), a + 30)), text.substr(a, 30))
          << f << " " << a;
  }
  // Frames without their sizes (as pzstd and zstd's seekable compressor write them), with a table.
  std::string unsized;
  std::vector<std::pair<uint32_t, uint32_t>> raw;
  for (size_t at = 0; at < text.size(); at += 25) {
    const std::string frame = RawFrame(text.substr(at, 25), false);
    unsized += frame;
    raw.emplace_back(static_cast<uint32_t>(frame.size()),
                     static_cast<uint32_t>(std::min<size_t>(25, text.size() - at)));
  }
  Write(dir / "unsized.zst", unsized);
  EXPECT_FALSE(InputStream(dir / "unsized.zst").seekable());
  Write(dir / "tabled.zst", unsized + SeekTable(raw));
  EXPECT_TRUE(InputStream(dir / "tabled.zst").seekable());
  EXPECT_EQ(InputStream(dir / "tabled.zst").size(), static_cast<int64_t>(text.size()));
  for (uint64_t a = 0; a <= text.size(); a += 5)
    EXPECT_EQ(ReadRange(dir / "tabled.zst", a, text.size()), text.substr(a)) << a;
  // A skippable frame among the data (as pzstd writes one), in the table with no content.
  const std::string f1 = RawFrame("1\n2\n", true), sk = SkippableFrame("pz"),
                    f2 = RawFrame("3\n", true);
  Write(dir / "skip.zst", f1 + sk + f2 +
                              SeekTable({{static_cast<uint32_t>(f1.size()), 4},
                                         {static_cast<uint32_t>(sk.size()), 0},
                                         {static_cast<uint32_t>(f2.size()), 2}}));
  EXPECT_EQ(InputStream(dir / "skip.zst").entry_points(), 3u);
  for (uint64_t a = 0; a <= 6; ++a)
    EXPECT_EQ(ReadRange(dir / "skip.zst", a, 6), std::string("1\n2\n3\n").substr(a)) << a;
  // Not well formed (a reserved bit; sizes that do not add up to the file): ignored.
  Write(dir / "reserved.zst", unsized + SeekTable(raw, 0x04));
  EXPECT_FALSE(InputStream(dir / "reserved.zst").seekable());
  auto short_by_one = raw;
  short_by_one[0].first -= 1;
  Write(dir / "short.zst", unsized + SeekTable(short_by_one));
  EXPECT_FALSE(InputStream(dir / "short.zst").seekable());
  // Tables that add up but lie: a byte of content moved between two frames (a place's content
  // offset wrong), a compressed size moved to the next frame (a place inside a frame), the last
  // frame's content one byte longer (the total wrong).
  auto shifted = sizes, moved = sizes, longer = sizes;
  shifted[1].second += 1, shifted[2].second -= 1;
  moved[1].first -= 1, moved[2].first += 1;
  longer.back().second += 1;
  for (const auto& [name, lie] : {std::pair{"shifted.zst", shifted}, std::pair{"moved.zst", moved},
                                  std::pair{"longer.zst", longer}}) {
    Write(dir / name, without + SeekTable(lie));
    ASSERT_TRUE(InputStream(dir / name).seekable()) << name;
    EXPECT_THROW(Read(dir / name, "text"), InputError) << name;
    const uint64_t size = static_cast<uint64_t>(InputStream(dir / name).size());
    for (uint64_t cut = 0; cut <= size; ++cut) {
      int failed = 0;
      for (auto [a, b] : {std::pair{uint64_t{0}, cut}, std::pair{cut, size}}) {
        try {
          ReadRange(dir / name, a, b);
        } catch (const InputError&) {
          ++failed;
        }
      }
      EXPECT_GE(failed, 1) << name << " cut at " << cut;
    }
  }
}

// Beyond 2^16 frames the places are thinned evenly (memory bounded whatever the frame count);
// ranges still read the plain bytes.
TEST(ZstdFrames, ManyFramesThinnedPlaces) {
  testing::TempDir dir;
  std::string bytes(70001, '\0');
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>('a' + i * 31 % 26);
  Write(dir / "b.txt", bytes);
  CompressFile(dir / "b.txt", dir / "b.zst", 1, 1);
  InputStream in(dir / "b.zst");
  EXPECT_EQ(in.size(), 70001);
  EXPECT_LE(in.entry_points(), uint64_t{1} << 16);
  EXPECT_GE(in.entry_points(), uint64_t{1} << 15);
  for (uint64_t a : {uint64_t{0}, uint64_t{1}, uint64_t{65535}, uint64_t{65536}, uint64_t{69999},
                     uint64_t{70001}})
    EXPECT_EQ(ReadRange(dir / "b.zst", a, std::min<uint64_t>(a + 7, 70001)), bytes.substr(a, 7))
        << a;
}

TEST(TraceFormats, CompressedTraceFileReadsLikeThePlainOne) {
  testing::TempDir dir;
  Mesh m = testing::TwoInterior();
  {
    TraceWriter w(dir / "t.trace", TraceHeader(), 3);
    SmoothOptions o;
    o.max_iters = 3;
    o.tol = -1;
    StreamMesh(m, o, "two_interior", "ori", w);
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
