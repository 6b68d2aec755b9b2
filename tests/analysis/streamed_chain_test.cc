// The streamed merge (analysis/streamed_chain.h) against the replay it replaces and the serial
// analyzer: ChunkResolver's first-touch distances and stack after equal MergeChunk's for every
// chunk of random chunkings (dense, hashed and sparse ids; empty chunks; a non-empty stack before);
// StreamedChain over 1..6 threads and blocks of 1, 7 and 65536 ids equals the serial analyzer
// access for access; IdIndex finds exactly its ids; an exception on one chunk's thread reaches the
// caller instead of hanging the chain.
#include "analysis/streamed_chain.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "analysis/synthetic_trace.h"
#include "core/synthetic.h"

namespace meshreuse {
namespace {

std::vector<uint64_t> Serial(const std::vector<uint64_t>& t) {
  StackDistance sd(0);
  std::vector<uint64_t> out;
  for (uint64_t id : t) out.push_back(sd.Access(id));
  return out;
}

std::vector<std::vector<uint64_t>> Traces() {
  std::vector<std::vector<uint64_t>> t = {CyclicScanTrace(3000, 5),
                                          UniformTrace(2000, 30000, 2),
                                          MeshLikeTrace(5000, 60000, 0.1, 3),
                                          {},
                                          {7},
                                          {1, 1, 1, 2, 1}};
  SplitMix64 rng(11);
  for (int k = 0; k < 12; ++k)
    t.push_back(UniformTrace(1 + rng.Below(k % 2 ? 40 : 4000), rng.Below(15000), 200 + k));
  return t;
}

std::vector<uint64_t> Hashed(std::vector<uint64_t> t) {
  for (uint64_t& id : t) id = id * 0x9E3779B97F4A7C15ull | (uint64_t{1} << 63);
  return t;
}

TEST(IdIndex, FindsExactlyItsIds) {
  for (uint64_t stride : {uint64_t{1}, uint64_t{3}, uint64_t{1} << 40}) {
    std::vector<uint64_t> ids;
    for (uint64_t i = 0; i < 5000; ++i) ids.push_back(17 + ((i * 7919) % 5000) * stride);
    const IdIndex x(ids);
    for (size_t k = 0; k < ids.size(); ++k) ASSERT_EQ(x.Find(ids[k]), k);
    EXPECT_EQ(x.Find(16), IdIndex::kAbsent);
    EXPECT_EQ(x.Find(17 + 5000 * stride), IdIndex::kAbsent);
    EXPECT_EQ(x.Find(~uint64_t{0} - 1), IdIndex::kAbsent);
    if (stride == 3) {
      EXPECT_EQ(x.Find(18), IdIndex::kAbsent);
    }
  }
  EXPECT_EQ(IdIndex(std::vector<uint64_t>{}).Find(0), IdIndex::kAbsent);
  EXPECT_EQ(IdIndex().Find(0), IdIndex::kAbsent);
  // Addresses on a power-of-two stride far from 0: direct (an array, not a table), and ids off
  // the stride, before the first or after the last absent.
  for (uint64_t stride : {uint64_t{64}, uint64_t{4096}}) {
    std::vector<uint64_t> ids;
    const uint64_t base = 0x7f3a12345000;
    for (uint64_t i = 0; i < 5000; ++i) ids.push_back(base + ((i * 7919) % 5000) * stride);
    const IdIndex x(ids);
    for (size_t k = 0; k < ids.size(); ++k) {
      ASSERT_EQ(x.Find(ids[k]), k);
      ASSERT_EQ(x.Find(ids[k] + stride / 2), IdIndex::kAbsent);
      ASSERT_EQ(x.Find(ids[k] + 1), IdIndex::kAbsent);
    }
    EXPECT_EQ(x.Find(base - stride), IdIndex::kAbsent);
    EXPECT_EQ(x.Find(base + 5000 * stride), IdIndex::kAbsent);
    EXPECT_LE(x.MemoryBytes(), 4u * 5000) << "direct, one entry per stride (a table: 256 KiB)";
  }
}

TEST(ChunkResolver, EqualsReplayChunkByChunk) {
  SplitMix64 rng(3);
  for (const std::vector<uint64_t>& base : Traces())
    for (bool hashed : {false, true}) {
      const std::vector<uint64_t> t = hashed ? Hashed(base) : base;
      // Random cut points, some chunks empty.
      std::vector<size_t> cuts = {0, t.size()};
      for (int k = 0; k < 5; ++k) cuts.push_back(t.empty() ? 0 : rng.Below(t.size() + 1));
      std::sort(cuts.begin(), cuts.end());
      StackDistance replay(0);
      std::vector<uint64_t> stack;
      for (size_t c = 0; c + 1 < cuts.size(); ++c) {
        const ChunkSummary s =
            AnalyzeChunk(t.data() + cuts[c], cuts[c + 1] - cuts[c], 0, [](size_t, uint64_t) {});
        std::vector<uint64_t> want;
        MergeChunk(&replay, s, [&](size_t, uint64_t d) { want.push_back(d); });
        ASSERT_EQ(ResolveChunk(s, &stack), want) << "chunk " << c;
        ASSERT_EQ(stack, replay.StackBottomUp()) << "chunk " << c;
      }
    }
}

TEST(StreamedChain, EqualsSerialAccessForAccess) {
  for (const std::vector<uint64_t>& base : Traces())
    for (bool hashed : {false, true})
      for (size_t block : {size_t{1}, size_t{7}, size_t{65536}})
        for (int p = 1; p <= 6; ++p) {
          const std::vector<uint64_t> t = hashed ? Hashed(base) : base;
          SCOPED_TRACE("length " + std::to_string(t.size()) + " p " + std::to_string(p) +
                       " block " + std::to_string(block) + (hashed ? " hashed" : ""));
          // Two batches through one running stack: the second starts from a non-empty stack.
          const size_t half = t.size() / 3;
          std::vector<uint64_t> stack, got(t.size());
          for (auto [lo, hi] : {std::pair<size_t, size_t>{0, half}, {half, t.size()}}) {
            const size_t n = hi - lo;
            auto begin = [&](int c) { return lo + n * c / p; };
            StreamedChain(
                p, &stack,
                [&](int c) {
                  return AnalyzeChunk(t.data() + begin(c), begin(c + 1) - begin(c), 0,
                                      [&, c](size_t i, uint64_t d) { got[begin(c) + i] = d; });
                },
                [&](int c, const ChunkSummary& s, const std::vector<uint64_t>& first) {
                  for (size_t k = 0; k < first.size(); ++k)
                    got[begin(c) + s.first_positions[k]] = first[k];
                },
                block);
          }
          ASSERT_EQ(got, Serial(t));
          StackDistance serial(0);
          for (uint64_t id : t) serial.Access(id);
          ASSERT_EQ(stack, serial.StackBottomUp());
        }
}

TEST(StreamedChain, AFailingChunkReachesTheCallerWithoutAHang) {
  const std::vector<uint64_t> t = UniformTrace(100000, 400000, 1);
  for (int bad : {0, 2, 3})
    for (bool in_finish : {false, true}) {
      std::vector<uint64_t> stack(t.begin(), t.begin() + 100000);  // a long stack in flight
      std::sort(stack.begin(), stack.end());
      stack.erase(std::unique(stack.begin(), stack.end()), stack.end());
      auto begin = [&](int c) { return t.size() * c / 4; };
      EXPECT_THROW(StreamedChain(
                       4, &stack,
                       [&](int c) {
                         if (c == bad && !in_finish) throw std::runtime_error("chunk failed");
                         return AnalyzeChunk(t.data() + begin(c), begin(c + 1) - begin(c), 0,
                                             [](size_t, uint64_t) {});
                       },
                       [&](int c, const ChunkSummary&, const std::vector<uint64_t>&) {
                         if (c == bad && in_finish) throw std::runtime_error("finish failed");
                       },
                       7),
                   std::runtime_error);
    }
}

}  // namespace
}  // namespace meshreuse
