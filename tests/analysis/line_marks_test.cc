// LineMarks against a std::map on random lines: near the canonical base (the dense part, grown as
// lines arrive), below it and far above it (hashed), with canonical streams and without.
#include "analysis/line_marks.h"

#include <gtest/gtest.h>

#include <map>

#include "core/synthetic.h"

namespace meshreuse {
namespace {

TEST(LineMarks, KeepsOneRecordPerLineWhereverItLies) {
  for (bool canonical : {true, false}) {
    SplitMix64 rng(7);
    LineMarks<uint32_t> marks(canonical, 64);
    std::map<uint64_t, uint32_t> want;
    const uint64_t base = AddressCanonicalizer::kCanonicalBase / 64;
    for (int k = 0; k < 20000; ++k) {
      const uint64_t r = rng.Next();
      const uint64_t line = r % 3 == 0   ? base + r % 5000                        // dense, growing
                            : r % 3 == 1 ? r % 4096                               // below the base
                                         : base + (uint64_t{1} << 33) + r % 100;  // beyond 2^32
      const uint32_t add = static_cast<uint32_t>(r >> 40) % 7;
      marks.At(line) += add;
      want[line] += add;
    }
    for (const auto& [line, value] : want) EXPECT_EQ(marks.At(line), value) << line;
    EXPECT_EQ(marks.At(base + 123456), 0u);  // a line never seen: a new, zeroed record
  }
}

}  // namespace
}  // namespace meshreuse
