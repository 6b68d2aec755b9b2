// BoundedStackDistance against the exact analyzer: every access below the depth gets the exact
// distance, every other (cold, or at the depth or beyond) kFar; it never holds more than `depth`
// ids; on traces that force compactions and evictions (cyclic scans just above and below the
// depth, uniform, mesh-like, hashed 64-bit ids), at depths 1 to 4096.
#include "analysis/bounded_stack.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "analysis/stack_distance.h"
#include "analysis/synthetic_trace.h"

namespace meshreuse {
namespace {

void ExpectBoundedEqualsExact(const std::vector<uint64_t>& t, uint32_t depth) {
  StackDistance exact;
  BoundedStackDistance b(depth);
  uint64_t below = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const uint64_t e = exact.Access(t[i]);
    const uint64_t d = b.Access(t[i]);
    if (e != StackDistance::kCold && e < depth) {
      ASSERT_EQ(d, e) << "access " << i << " depth " << depth;
      ++below;
    } else {
      ASSERT_EQ(d, BoundedStackDistance::kFar) << "access " << i << " depth " << depth;
    }
    ASSERT_LE(b.size(), depth);
  }
  EXPECT_GT(below + t.size(), 0u);
}

TEST(BoundedStackDistance, EqualsTheExactDistancesBelowItsDepth) {
  std::vector<std::vector<uint64_t>> traces = {
      CyclicScanTrace(100, 30), CyclicScanTrace(101, 30), CyclicScanTrace(99, 30),
      UniformTrace(3000, 60000, 2), MeshLikeTrace(5000, 80000, 0.1, 3)};
  std::vector<uint64_t> hashed = UniformTrace(2000, 40000, 4);
  for (uint64_t& x : hashed) x = x * 0x9E3779B97F4A7C15ull + 12345;  // sparse 64-bit ids
  traces.push_back(hashed);
  for (const auto& t : traces)
    for (uint32_t depth : {1u, 2u, 7u, 100u, 101u, 1000u, 4096u})
      ExpectBoundedEqualsExact(t, depth);
}

TEST(BoundedStackDistance, RefusesADepthOutOfRange) {
  EXPECT_THROW(BoundedStackDistance(0), std::invalid_argument);
  EXPECT_THROW(BoundedStackDistance((1u << 26) + 1), std::invalid_argument);
}

}  // namespace
}  // namespace meshreuse
