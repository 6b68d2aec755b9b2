// The distributed analysis on threads (reports/chunks/chunk_threads.h): the chunk relay's ids
// arrive in order with each stream's end (the communicator itself:
// core/ranks/thread_communicator_test.cc); and a trace analysed in P chunks on P threads (P = 1-5,
// fewer accesses than chunks, a meshreuse trace of 2 threads and 3 sweeps with its profile, with
// and without a profile, SHARDS at a fixed rate; the histograms added up a tree of ranks and by
// distance) gives every table byte for byte as the serial analyzer; its exchange by distance
// delivers every message, and a damaged slice is refused by name.
#include "reports/chunks/chunk_threads.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/ranks/thread_communicator.h"
#include "reports/analyze.h"
#include "reports/chunks/distributed_analysis.h"
#include "reports/trace.h"
#include "tests/test_util.h"
#include "tracer/input_stream.h"

namespace meshreuse {
namespace {

TEST(ChunkRelay, RelaysIdsInOrderWithEachStreamsEnd) {
  for (int p = 1; p <= 4; ++p) {
    std::vector<std::vector<uint64_t>> got(p);
    ThreadCommunicator::Run(p, [&](Communicator& tx) {
      const int r = tx.rank();
      ASSERT_EQ(tx.size(), p);
      // Two streams: rank r forwards what it received, then 10 blocks of its own (sizes 1..10),
      // then the end; a stream's end arrives as 0.
      for (int stream = 0; stream < 2; ++stream) {
        std::vector<uint64_t> in;
        if (r > 0)
          while (RecvIds(tx, &in) > 0) {
            got[r].insert(got[r].end(), in.begin(), in.end());
            if (r + 1 < p) SendIds(tx, in.data(), in.size());
          }
        got[r].push_back(~uint64_t{0});  // marks the end of this stream
        if (r + 1 == p) continue;
        for (uint64_t b = 1; b <= 10; ++b) {
          std::vector<uint64_t> block(b);
          for (uint64_t i = 0; i < b; ++i) block[i] = (stream * 100 + r) * 1000 + b * 10 + i;
          SendIds(tx, block.data(), block.size());
        }
        SendIds(tx, nullptr, 0);
      }
    });
    for (int r = 1; r < p; ++r) {  // rank r holds, per stream, ranks 0..r-1's blocks in order
      std::vector<uint64_t> want;
      for (int stream = 0; stream < 2; ++stream) {
        for (int from = 0; from < r; ++from)
          for (uint64_t b = 1; b <= 10; ++b)
            for (uint64_t i = 0; i < b; ++i)
              want.push_back((stream * 100 + from) * 1000 + b * 10 + i);
        want.push_back(~uint64_t{0});
      }
      EXPECT_EQ(got[r], want) << "p " << p << " rank " << r;
    }
  }
}

void WriteU64(const std::string& path, const std::vector<uint64_t>& ids) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(ids.data()), static_cast<std::streamsize>(ids.size() * 8));
}

// Every table of an analysis, as CSV.
std::string Tables(const AnalyzeResult& r, const AnalyzeConfig& cfg) {
  return AnalyzeTable(r, cfg, false).Csv() + HistogramTable(r).Csv() + ProfileTable(r).Csv() +
         MrcTable(r).Csv();
}

void ExpectChunksOnThreadsEqualSerial(const AnalyzeConfig& cfg, const std::string& what) {
  const std::string serial = Tables(RunAnalyze(cfg, Log()), cfg);
  ASSERT_GT(serial.size(), 200u) << what;
  for (int p = 1; p <= 5; ++p) {
    ASSERT_TRUE(CanAnalyzeInChunks(cfg, cfg.inputs[0])) << what;
    EXPECT_EQ(Tables(AnalyzeChunksOnThreads(cfg, p, Log()), cfg), serial) << what << " p " << p;
    AnalyzeConfig t = cfg;  // and through the runner's --threads
    t.threads = p;
    EXPECT_EQ(Tables(RunAnalyze(t, Log()), cfg), serial) << what << " threads " << p;
    AnalyzeConfig d = cfg;  // the histograms added up by distance at every P, not up the tree
    d.scatter_from_ranks = 2;
    EXPECT_EQ(Tables(AnalyzeChunksOnThreads(d, p, Log()), cfg), serial)
        << what << " scattered " << p;
  }
}

TEST(AnalyzeChunksOnThreads, EqualsTheSerialAnalyzer) {
  testing::TempDir dir;
  std::mt19937_64 rng(3);
  std::vector<uint64_t> uniform(30011), scan, hashed(20000), tiny = {5, 5, 9};
  for (uint64_t& x : uniform) x = rng() % 4096 * 8 + 0x7f3a12345000;
  for (int rep = 0; rep < 7; ++rep)
    for (uint64_t i = 0; i < 3001; ++i) scan.push_back(i * 64);
  for (uint64_t& x : hashed) x = rng() % 3000 * 0x9e3779b97f4a7c15ull >> 1;
  for (const auto& [name, ids] : {std::pair{"uniform", uniform}, std::pair{"scan", scan},
                                  std::pair{"hashed", hashed}, std::pair{"tiny", tiny}}) {
    AnalyzeConfig cfg;
    cfg.inputs = {dir / (std::string(name) + ".u64")};
    WriteU64(cfg.inputs[0], ids);
    cfg.format = "u64";
    for (Granularity g : {Granularity::kElement, Granularity::kLine}) {
      cfg.granularity = g;
      ExpectChunksOnThreadsEqualSerial(cfg, name);
    }
  }
  // A meshreuse trace: 2 threads, 3 sweeps, both granularities, with and without a profile.
  TraceConfig tc;
  tc.mesh = testing::DataPath("plate41.msh");
  tc.ordering = "rdr", tc.iterations = 3, tc.threads = 2;
  tc.output = dir / "mesh.trace";
  RunTrace(tc, Log());
  AnalyzeConfig cfg;
  cfg.inputs = {tc.output};
  for (bool profile : {true, false}) {
    cfg.profile = profile;
    ExpectChunksOnThreadsEqualSerial(cfg, profile ? "mesh trace" : "mesh trace, no profile");
  }
  cfg.sample = true, cfg.sample_error = true;  // SHARDS at a fixed rate beside the exact analysis
  cfg.shards.rate = 0.1;
  ExpectChunksOnThreadsEqualSerial(cfg, "mesh trace sampled");
  cfg.shards.s_max = 100;  // a fixed-size sample depends on every id before: not in chunks
  EXPECT_FALSE(CanAnalyzeInChunks(cfg, tc.output));
}

// A transport that damages what one rank receives in the histograms' exchange by distance.
class DamagedSlices : public Communicator {
 public:
  DamagedSlices(Communicator& tx, int how) : tx_(tx), how_(how) {}
  int32_t rank() const override { return tx_.rank(); }
  int32_t size() const override { return tx_.size(); }
  void Send(int32_t to, std::string&& b) override { tx_.Send(to, std::move(b)); }
  std::string Recv(int32_t from) override { return tx_.Recv(from); }
  std::vector<std::string> AllGather(const std::string& mine) override {
    return tx_.AllGather(mine);
  }
  bool SharesMemory() const override { return tx_.SharesMemory(); }
  void SendObject(int32_t to, std::shared_ptr<void> o) override { tx_.SendObject(to, o); }
  std::shared_ptr<void> RecvObject(int32_t from) override { return tx_.RecvObject(from); }
  std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v) override {
    return tx_.AllReduceMax(v);
  }
  std::vector<uint64_t> ExclusiveScanSum(const std::vector<uint64_t>& v) override {
    return tx_.ExclusiveScanSum(v);
  }
  std::vector<std::string> AllToAll(std::vector<std::string>&& out) override {
    std::vector<std::string> in = tx_.AllToAll(std::move(out));
    if (rank() != 1) return in;
    std::string& b = in[0];  // rank 0's slice for rank 1: key, n, then (distance, count) pairs
    EXPECT_GE(b.size(), 32u);
    if (how_ == 0) {  // the first pair's count one more: still well formed
      uint64_t c;
      std::memcpy(&c, &b[24], 8);
      ++c;
      std::memcpy(&b[24], &c, 8);
    }
    const uint64_t far = ~uint64_t{0} - 1;
    if (how_ == 1) std::memcpy(&b[b.size() - 16], &far, 8);  // the last pair's distance
    if (how_ == 2) b.resize(b.size() - 5);                   // cut
    if (how_ == 3) std::memset(&b[24], 0, 8);                // a count of 0
    return in;
  }

 private:
  Communicator& tx_;
  int how_;
};

TEST(AnalyzeChunksOnThreads, ADamagedSliceIsRefusedByName) {
  // Rank 1 receives rank 0's slice damaged: a distance outside its range, a cut message and a
  // count of 0 are refused naming rank 0; a count one more (still well formed) is caught by rank
  // 0, where the slices of a stream no longer add up to its accesses.
  testing::TempDir dir;
  std::vector<uint64_t> uniform(20000);
  std::mt19937_64 rng(5);
  for (uint64_t& x : uniform) x = rng() % 3000;
  AnalyzeConfig cfg;
  cfg.inputs = {dir / "u.u64"};
  WriteU64(cfg.inputs[0], uniform);
  cfg.format = "u64";
  cfg.granularity = Granularity::kElement;
  cfg.scatter_from_ranks = 2;
  const char* want[] = {"slices do not add up", "outside the slice", "length", "pairs"};
  for (int how = 0; how < 4; ++how) {
    try {
      ThreadCommunicator::Run(2, [&](Communicator& tx) {
        DamagedSlices d(tx, how);
        AnalyzeConfig mine = cfg;
        mine.transport = &d;
        RunDistributed(mine, d, Log());
      });
      ADD_FAILURE() << "accepted, how " << how;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(want[how]), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(how == 0 ? "the ranks" : "rank 0"), std::string::npos)
          << e.what();
    }
  }
}

TEST(AnalyzeChunksOnThreads, OnlyRegularFilesThatCanBeEntered) {
  testing::TempDir dir;
  TraceConfig tc;
  tc.mesh = testing::DataPath("two_interior.node");
  tc.output = dir / "t.trace.zst";
  tc.compress = true;
  RunTrace(tc, Log());
  AnalyzeConfig cfg;
  cfg.threads = 2;
  // A small trace: one 4 MiB frame, which a second chunk could only enter at its start.
  EXPECT_FALSE(CanAnalyzeInChunks(cfg, tc.output));
  EXPECT_FALSE(CanAnalyzeInChunks(cfg, "-"));
  EXPECT_FALSE(CanAnalyzeInChunks(cfg, dir / "missing"));
  EXPECT_FALSE(CanAnalyzeInChunks(cfg, dir.path().string()));  // a directory
  tc.output = dir / "t.trace";
  tc.compress = false;
  RunTrace(tc, Log());
  EXPECT_TRUE(CanAnalyzeInChunks(cfg, tc.output));
  // In as many frames as threads (and not fewer).
  const uint64_t bytes = std::filesystem::file_size(tc.output);
  CompressFile(tc.output, dir / "two.zst", 3, (bytes + 1) / 2);
  EXPECT_TRUE(CanAnalyzeInChunks(cfg, dir / "two.zst"));
  cfg.threads = 3;
  EXPECT_FALSE(CanAnalyzeInChunks(cfg, dir / "two.zst"));
}

}  // namespace
}  // namespace meshreuse
