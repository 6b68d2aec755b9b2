// LineQuantiles against the whole exact analysis (ReuseAnalysis at line granularity): on streams of
// small and large distances, two threads, accesses that straddle two lines, repeats, canonical
// and host addresses, every quantile it answers is the exact one and it answers exactly when the
// exact one lies below its depth; its access and distinct-line counts are the exact ones. Cyclic
// scans put the quantile at depth - 1 (answered) and at depth (not).
#include "analysis/line_quantiles.h"

#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "analysis/reuse_analysis.h"
#include "core/access.h"

namespace meshreuse {
namespace {

constexpr double kXs[] = {0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 1.0};

// Returns how many quantiles were answered and how many lay at depth or beyond.
std::pair<int, int> ExpectExact(const std::vector<Access>& stream, bool canonical, int threads,
                                uint32_t depth) {
  StreamInfo info;
  info.threads = threads;
  info.canonical = canonical;
  ReuseOptions o;
  o.granularity = Granularity::kLine;
  o.profile = false;
  ReuseAnalysis exact(o);
  LineQuantiles lq(64, depth);
  FanOut both({&exact, &lq});
  both.Begin(info);
  for (size_t i = 0; i < stream.size(); i += 1000)
    both.Consume(stream.data() + i, std::min<size_t>(1000, stream.size() - i));
  both.End();
  int answered = 0, beyond = 0;
  for (int t = 0; t < threads; ++t) {
    const StreamAnalysis* s = exact.line(t);
    if (s == nullptr) {
      ADD_FAILURE() << "no stream " << t;
      return {answered, beyond};
    }
    EXPECT_EQ(lq.accesses(t), s->hist.accesses()) << t;
    EXPECT_EQ(lq.cold(t), s->distinct()) << t;
    for (double x : kXs) {
      const uint64_t want = s->hist.Quantile(x);
      const std::optional<uint64_t> got = lq.Quantile(t, x);
      if (want < depth) {
        EXPECT_EQ(got, std::optional<uint64_t>(want))
            << "thread " << t << " x " << x << " depth " << depth;
        ++answered;
      } else {
        EXPECT_FALSE(got.has_value()) << "thread " << t << " x " << x << " exact " << want;
        ++beyond;
      }
    }
  }
  return {answered, beyond};
}

// Two threads interleaved: mostly short reuses of nearby lines (a mesh sweep's pattern), some
// reuses far back, some new lines; sizes 4 and 8 at any byte, so some straddle; runs of repeats.
std::vector<Access> MixedStream(uint64_t base, uint64_t lines, uint64_t seed, size_t n) {
  std::mt19937_64 rng(seed);
  std::vector<Access> out;
  uint64_t at[2] = {base, base + 64 * lines / 2};
  for (size_t i = 0; i < n; ++i) {
    const int t = static_cast<int>(rng() % 2);
    const uint64_t r = rng() % 100;
    uint64_t addr;
    if (r < 70) {
      at[t] += rng() % 24;  // a little forward
      addr = at[t];
    } else if (r < 85) {
      addr = at[t] - rng() % 2048;  // a few dozen lines back
    } else {
      addr = base + rng() % (64 * lines);  // anywhere
    }
    Access a{};
    a.address = addr, a.size = rng() % 2 ? 8 : 4, a.thread = static_cast<uint8_t>(t);
    out.push_back(a);
    if (r % 7 == 0) out.push_back(a);  // a repeat
  }
  return out;
}

TEST(LineQuantiles, EqualsTheWholeAnalysisWhereItAnswersAndAnswersBelowItsDepth) {
  int answered = 0, beyond = 0;
  for (uint32_t depth : {1u, 2u, 8u, 32u, 64u, 300u})
    for (bool canonical : {true, false}) {
      const uint64_t base = canonical ? AddressCanonicalizer::kCanonicalBase : 0x7f12345678c0ull;
      const auto [a, b] =
          ExpectExact(MixedStream(base, 5000, depth * 7 + canonical, 60000), canonical, 2, depth);
      answered += a, beyond += b;
    }
  EXPECT_GT(answered, 0);  // both paths, over the depths
  EXPECT_GT(beyond, 0);
}

// Ranks of a byte up to 128 slots, of 16 bits beyond: exact on both sides of the change, with
// quantiles answered and not (a few dozen lines back is the stream's usual reuse).
TEST(LineQuantiles, ByteAndWideRanksAreExactAroundTheirBoundary) {
  for (uint32_t depth : {16u, 17u, 112u, 113u, 128u, 129u, 136u, 137u}) {
    const auto [a, b] = ExpectExact(
        MixedStream(AddressCanonicalizer::kCanonicalBase, 3000, depth + 11, 30000), true, 2, depth);
    EXPECT_GT(a, 0) << depth;
    EXPECT_GT(b, 0) << depth;
  }
}

// A canonical stream with other addresses in its second half (a host address, a line below the
// canonical base): their marks in the hash table, the others' in the array, one top for both.
// Exact at each depth.
TEST(LineQuantiles, ACanonicalStreamWithOtherAddressesLaterIsExact) {
  for (uint32_t depth : {1u, 8u, 32u, 64u})
    for (const uint64_t other : {uint64_t{0x7f12345678c0}, uint64_t{0x1000}}) {
      std::vector<Access> s =
          MixedStream(AddressCanonicalizer::kCanonicalBase, 5000, depth + other % 7, 40000);
      std::mt19937_64 rng(depth);
      for (size_t i = s.size() / 2; i < s.size(); ++i)  // the second half: some elsewhere
        if (rng() % 10 == 0) s[i].address = other + 64 * (rng() % 40) + s[i].address % 64;
      ExpectExact(s, true, 2, depth);
    }
}

TEST(LineQuantiles, ACyclicScanAnswersAtDepthMinusOneAndNotAtDepth) {
  for (uint32_t depth : {1u, 5u, 32u, 64u})
    for (uint64_t lines : {uint64_t{depth}, uint64_t{depth} + 1}) {
      std::vector<Access> scan;
      for (int round = 0; round < 4; ++round)
        for (uint64_t l = 0; l < lines; ++l) {
          Access a{};
          a.address = 4096 + 64 * l, a.size = 8;
          scan.push_back(a);
        }
      LineQuantiles lq(64, depth);
      lq.Begin(StreamInfo{});
      lq.Consume(scan.data(), scan.size());
      // Every reuse is at distance lines - 1.
      if (lines == depth) {
        EXPECT_EQ(lq.Quantile(0, 0.5), std::optional<uint64_t>(depth - 1)) << depth;
      } else {
        EXPECT_EQ(lq.Quantile(0, 0.5), std::nullopt) << depth;
      }
      EXPECT_EQ(lq.cold(0), lines);
      ExpectExact(scan, false, 1, depth);
    }
}

TEST(LineQuantiles, NoFiniteDistanceAndBadArguments) {
  LineQuantiles lq(64, 8);
  lq.Begin(StreamInfo{});
  EXPECT_EQ(lq.Quantile(0, 0.5), std::nullopt);  // no stream
  Access a{};
  a.address = 128, a.size = 8;
  lq.Consume(&a, 1);
  EXPECT_EQ(lq.Quantile(0, 0.5), std::nullopt);  // only a cold access
  EXPECT_EQ(lq.Quantile(1, 0.5), std::nullopt);  // no such thread
  lq.Consume(&a, 1);
  EXPECT_EQ(lq.Quantile(0, 0.5), std::optional<uint64_t>(0));
  EXPECT_THROW(lq.Quantile(0, 1.5), std::invalid_argument);
  EXPECT_THROW(LineQuantiles(48, 8), std::invalid_argument);
  EXPECT_THROW(LineQuantiles(64, 0), std::invalid_argument);
  EXPECT_THROW(LineQuantiles(64, 4097), std::invalid_argument);
}

}  // namespace
}  // namespace meshreuse
