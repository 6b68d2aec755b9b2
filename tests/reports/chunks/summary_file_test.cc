// Chunk summary files (reports/chunks/summary_file.h; SweepsOfMeshChunk of summarize_chunk.h): a
// summary written and read back is the same; every single-byte change of the payload, with the
// checksum made to match, is either read as a valid summary or refused as an InputError naming the
// file -- never a crash, a huge allocation or another exception (counts are checked against the
// bytes left before anything is allocated).
#include "reports/chunks/summary_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "reports/chunks/summarize_chunk.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

SummaryFile Sample() {
  SummaryFile s;
  s.id.format = "u64";
  s.id.input_bytes = 800, s.id.fingerprint = 42, s.id.granularity = 1, s.id.line_bytes = 64;
  s.id.chunks = 3;
  s.input = "trace.u64";
  s.chunk = 1, s.first = 33, s.end = 66, s.total = 100;
  s.info.threads = 1;
  s.info.records = 100;
  s.info.sweep_records = s.info.sweep_elements = {{100}};
  s.moves = {0};
  StreamSummary x;
  x.accesses = 33, x.offset = 33;
  x.chunk.first_ids = {5, 9, 7};
  x.chunk.first_positions = {0, 1, 4};
  x.chunk.stack = {9, 5, 7};
  x.hist = {{0, 10}, {1, 12}, {2, 8}};
  x.profile = {{33, 20, 2, 17}, {34, 13, 1, 9}};
  s.streams.push_back(x);
  return s;
}

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

TEST(ChunkSummary, MeshChunksRegenerateFromTheirFirstSweep) {
  StreamInfo whole;  // 4 sweeps of 15 records on 2 threads
  whole.threads = 2;
  whole.sweep_records.assign(4, {10, 5});
  auto run = [&](UpdateMode mode, uint64_t first, uint64_t end) {
    const MeshChunkSweeps s = SweepsOfMeshChunk(whole, mode, first, end);
    return std::vector<uint64_t>{static_cast<uint64_t>(s.from), static_cast<uint64_t>(s.to),
                                 s.skipped};
  };
  const UpdateMode gs = UpdateMode::kGaussSeidel, jacobi = UpdateMode::kJacobi;
  EXPECT_EQ(run(gs, 0, 15), (std::vector<uint64_t>{1, 1, 0}));
  EXPECT_EQ(run(gs, 14, 16), (std::vector<uint64_t>{1, 2, 0}));
  EXPECT_EQ(run(gs, 15, 31), (std::vector<uint64_t>{2, 3, 15}));
  EXPECT_EQ(run(gs, 59, 60), (std::vector<uint64_t>{4, 4, 45}));
  EXPECT_EQ(run(jacobi, 15, 31), (std::vector<uint64_t>{1, 3, 0}));  // sweep 2 reads sweep 0's
  EXPECT_EQ(run(jacobi, 30, 45), (std::vector<uint64_t>{3, 3, 30}));
  EXPECT_EQ(run(jacobi, 59, 60), (std::vector<uint64_t>{3, 4, 30}));
  EXPECT_EQ(run(gs, 20, 20), (std::vector<uint64_t>{1, 0, 0}));  // empty: nothing
}

TEST(ChunkSummary, RoundTrip) {
  testing::TempDir dir;
  const std::string path = dir / "s";
  const SummaryFile s = Sample();
  WriteSummary(path, s);
  const SummaryFile r = ReadSummary(path);
  EXPECT_TRUE(r.id == s.id);
  EXPECT_EQ(r.input, s.input);
  EXPECT_EQ(r.chunk, 1u);
  EXPECT_EQ(r.first, 33u);
  EXPECT_EQ(r.end, 66u);
  ASSERT_EQ(r.streams.size(), 1u);
  EXPECT_EQ(r.streams[0].chunk.first_ids, s.streams[0].chunk.first_ids);
  EXPECT_EQ(r.streams[0].chunk.stack, s.streams[0].chunk.stack);
  EXPECT_EQ(r.streams[0].hist, s.streams[0].hist);
  ASSERT_EQ(r.streams[0].profile.size(), 2u);
  EXPECT_TRUE(r.streams[0].profile[1].sum == 9);
  EXPECT_EQ(r.info.sweep_records, s.info.sweep_records);
}

TEST(ChunkSummary, EveryByteChangedIsReadOrRefusedCleanly) {
  testing::TempDir dir;
  const std::string path = dir / "s";
  WriteSummary(path, Sample());
  const std::string good = Slurp(path);
  ASSERT_GT(good.size(), 32u);
  int refused = 0, read = 0;
  for (size_t i = 32; i < good.size(); ++i)
    for (unsigned char v : {0x00, 0x01, 0x80, 0xff}) {
      std::string b = good;
      if (static_cast<unsigned char>(b[i]) == v) continue;
      b[i] = static_cast<char>(v);
      const uint64_t sum = SummaryChecksum(b.data() + 32, b.size() - 32);
      std::memcpy(&b[24], &sum, 8);
      std::ofstream(path, std::ios::binary | std::ios::trunc) << b;
      // The file is parsed as it streams in; the bytes in memory (an MPI rank's message) are
      // checked whole first: the same verdict and message either way.
      std::string streamed = "read", whole = "read";
      try {
        ReadSummary(path);
        ++read;
      } catch (const InputError& e) {
        ++refused;
        streamed = e.problem();
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      }
      try {
        DecodeSummary(path, b);
      } catch (const InputError& e) {
        whole = e.problem();
      }
      EXPECT_EQ(streamed, whole) << "byte " << i;
    }
  EXPECT_GT(refused, 0);
  EXPECT_GT(read, 0);  // ids, names and counts that stay consistent are valid summaries
  // The checksum itself: a payload change without it is refused.
  std::string b = good;
  b[40] ^= 1;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << b;
  EXPECT_THROW(ReadSummary(path), InputError);
}

// The written file is streamed through three passes (size, checksum, bytes): it must be exactly
// the in-memory encoding, for a summary larger than the writer's 64 KiB buffer, with strings and
// arrays that leave words split across pieces; every damage that the checksum catches is reported
// as such by the streamed reader too, and a truncated file by its size.
TEST(ChunkSummary, StreamedWriteAndReadEqualTheInMemoryEncoding) {
  testing::TempDir dir;
  const std::string path = dir / "big";
  SummaryFile s = Sample();
  s.input = "a name of odd length.u64";
  StreamSummary& x = s.streams[0];
  const uint64_t f = 20011;  // distinct ids: 3 x 160 KB of arrays
  x.chunk = ChunkSummary();
  for (uint64_t i = 0; i < f; ++i) {
    x.chunk.first_ids.push_back(i * 7919 % 1000003);
    x.chunk.first_positions.push_back(i);
    x.chunk.stack.push_back((i * 31) % 1000003);
  }
  x.accesses = f + 9, x.hist = {{0, 4}, {17, 5}};
  WriteSummary(path, s);
  const std::string bytes = EncodeSummary(s);
  ASSERT_GT(bytes.size(), size_t{3} << 16);
  EXPECT_EQ(Slurp(path), bytes);
  const SummaryFile r = ReadSummary(path);
  EXPECT_EQ(r.input, s.input);
  EXPECT_EQ(r.streams[0].chunk.stack, x.chunk.stack);
  EXPECT_EQ(r.streams[0].hist, x.hist);
  for (size_t i = 32; i < bytes.size(); i += 4099) {  // unfixed checksum: refused as damaged
    std::string b = bytes;
    b[i] ^= 0x40;
    std::ofstream(path, std::ios::binary | std::ios::trunc) << b;
    try {
      ReadSummary(path);
      ADD_FAILURE() << "byte " << i << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.problem(), "corrupt summary: the checksum does not match its contents") << i;
    }
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() - 5);
  try {
    ReadSummary(path);
    ADD_FAILURE() << "a truncated file accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("truncated or extended summary"), std::string::npos) << e.what();
  }
}

// Through a pipe (`--merge <(cat S)`): no size to check up front, so it is read whole (a header's
// claim must not size an allocation) and a payload cut short or followed by more bytes refused.
TEST(ChunkSummary, StreamedFromAPipe) {
  testing::TempDir dir;
  const std::string fifo = dir / "pipe";
  const std::string bytes = EncodeSummary(Sample());
  auto read_through_pipe = [&](const std::string& sent) {
    EXPECT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << sent; });
    std::string verdict = "read";
    try {
      const SummaryFile r = ReadSummary(fifo);
      EXPECT_EQ(r.streams.at(0).hist, Sample().streams[0].hist);
    } catch (const InputError& e) {
      verdict = e.problem();
    }
    writer.join();
    std::remove(fifo.c_str());
    return verdict;
  };
  EXPECT_EQ(read_through_pipe(bytes), "read");
  EXPECT_NE(read_through_pipe(bytes + "x").find("truncated or extended summary"),
            std::string::npos);
  EXPECT_NE(read_through_pipe(bytes.substr(0, bytes.size() - 3)).find("truncated or extended"),
            std::string::npos);
}

// A chunk's distances are bounded by its own distinct ids (what the merge may allocate for);
// a resolved stream's reach back before the chunk, so only a rank's message may hold one.
TEST(ChunkSummary, DistancesBoundedByTheFileAndResolvedOnlyFromRanks) {
  testing::TempDir dir;
  const std::string path = dir / "s";
  SummaryFile s = Sample();
  s.streams[0].hist = {{2, 10}, {3, 20}};  // 3 distinct ids: distance 3 cannot occur
  WriteSummary(path, s);
  EXPECT_THROW(ReadSummary(path), InputError);
  s = Sample();
  s.streams[0].resolved = true;
  s.streams[0].chunk = ChunkSummary();
  s.streams[0].hist = {{40, 33}};
  const std::string bytes = EncodeSummary(s);
  try {
    DecodeSummary("f", bytes);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("resolved message"), std::string::npos) << e.what();
  }
  EXPECT_EQ(DecodeSummary("rank 1", bytes, true).streams[0].hist, s.streams[0].hist);
}

// A rank's resolved stream whose histogram travels apart (the reduce-scatter by distance): no
// pairs, and its accesses not counted by them; refused with pairs, and from a file.
TEST(ChunkSummary, AHistogramSentApartIsEmptyAndOnlyFromRanks) {
  SummaryFile s = Sample();
  s.streams[0].resolved = true;
  s.streams[0].hist_apart = true;
  s.streams[0].chunk = ChunkSummary();
  s.streams[0].hist.clear();
  const std::string bytes = EncodeSummary(s);
  const SummaryFile got = DecodeSummary("rank 1", bytes, true);
  EXPECT_TRUE(got.streams[0].resolved && got.streams[0].hist_apart);
  EXPECT_TRUE(got.streams[0].hist.empty());
  EXPECT_EQ(got.streams[0].accesses, s.streams[0].accesses);
  EXPECT_THROW(DecodeSummary("f", bytes), InputError);
  s.streams[0].hist = {{StackDistance::kCold, s.streams[0].accesses}};  // would add up, but apart
  try {
    DecodeSummary("rank 1", EncodeSummary(s), true);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sent apart"), std::string::npos) << e.what();
  }
  s.streams[0].hist_apart = false;  // the same stream, its histogram here: it must add up
  EXPECT_EQ(DecodeSummary("rank 1", EncodeSummary(s), true).streams[0].hist, s.streams[0].hist);
  s.streams[0].hist.clear();
  EXPECT_THROW(DecodeSummary("rank 1", EncodeSummary(s), true), InputError);
}

// The summaries in tests/data/broken (made by make_summaries.py, rows of kind "summary" in
// EXPECTED): each refused with the file, place and problem EXPECTED names.
TEST(ChunkSummary, BrokenFilesAreRefusedByName) {
  std::ifstream in(testing::DataPath("broken/EXPECTED"));
  int cases = 0;
  for (std::string l; std::getline(in, l);) {
    if (l.empty() || l[0] == '#') continue;
    std::vector<std::string> f;
    for (size_t a = 0, b; a <= l.size(); a = b + 1) {
      b = l.find('\t', a);
      if (b == std::string::npos) b = l.size();
      f.push_back(l.substr(a, b - a));
    }
    if (f.size() < 4 || f[3] != "summary") continue;
    ++cases;
    const std::string path = testing::DataPath("broken/" + f[0]);
    SCOPED_TRACE(path);
    try {
      ReadSummary(path);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path) << e.what();
      EXPECT_EQ(e.line(), std::stoll(f[1])) << e.what();
      EXPECT_NE(e.problem().find(f[2]), std::string::npos) << e.what() << "\nexpected: " << f[2];
    }
  }
  EXPECT_GE(cases, 5);
}

}  // namespace
}  // namespace meshreuse
