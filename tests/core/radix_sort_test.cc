// RadixSortUnique (core/radix_sort.h) against std::sort + std::unique: random ids over small and
// full 32-bit ranges, duplicates, sorted and reversed input, both element types; ids outside
// [0, 2^32) refused.
#include "core/radix_sort.h"

#include <gtest/gtest.h>

#include <random>

namespace meshreuse {
namespace {

template <class T>
void ExpectLikeStdSort(std::vector<T> v) {
  std::vector<T> want = v;
  std::sort(want.begin(), want.end());
  want.erase(std::unique(want.begin(), want.end()), want.end());
  RadixSortUnique(&v);
  EXPECT_EQ(v, want);
}

TEST(RadixSortUnique, EqualsStdSortAndUnique) {
  std::mt19937_64 rng(11);
  for (uint64_t range : {1ull, 7ull, 65536ull, 65537ull, 1ull << 31, 1ull << 32})
    for (size_t n : {0, 1, 2, 3, 100, 5000}) {
      std::vector<int64_t> a(n);
      for (int64_t& x : a) x = static_cast<int64_t>(rng() % range);
      ExpectLikeStdSort(a);
      std::sort(a.begin(), a.end());
      ExpectLikeStdSort(a);
      std::reverse(a.begin(), a.end());
      ExpectLikeStdSort(a);
      std::vector<int32_t> b(n);
      for (int32_t& x : b) x = static_cast<int32_t>(rng() % std::min<uint64_t>(range, INT32_MAX));
      ExpectLikeStdSort(b);
    }
  std::vector<int64_t> bad = {3, -1};
  EXPECT_THROW(RadixSortUnique(&bad), std::logic_error);
  bad = {int64_t{1} << 32, 1};
  EXPECT_THROW(RadixSortUnique(&bad), std::logic_error);
}

}  // namespace
}  // namespace meshreuse
