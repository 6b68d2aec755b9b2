// WritablePages (the simulators' pages made writable before their first read): the pages asked
// for become resident, the others stay as they were, and no byte changes.
#include "analysis/writable_pages.h"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cstdint>
#include <vector>

namespace meshreuse {
namespace {

// WritablePages on a fresh mapping: the pages asked for become resident (where the kernel has
// MADV_POPULATE_WRITE), the others stay untouched, and no byte changes, written or not.
TEST(WritablePages, MakesTheTouchedPagesResidentAndChangesNoByte) {
  const size_t page = 4096, n = 16;
  void* m = mmap(nullptr, n * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(m, MAP_FAILED);
  auto* b = static_cast<uint8_t*>(m);
  for (size_t i = 0; i < 300; ++i) b[page + 7 * i] = static_cast<uint8_t>(i + 1);  // page 1
  b[5 * page + 4095] = 0xAB;                                                       // page 5
  WritablePages w;
  w.Reset(b + 16, n * page - 32);  // a block that starts and ends inside pages
  w.Touch(b + 3 * page + 100, 8);
  w.Touch(b + 5 * page + 4000, 200);  // pages 5 and 6
  w.Touch(b + page + 1, 1);
  w.Touch(b + 3 * page, 16);  // again: nothing more
  for (size_t i = 0; i < n * page; ++i) {
    const size_t k = i - page;
    const uint8_t want = i == 5 * page + 4095                     ? 0xAB
                         : i >= page && k % 7 == 0 && k / 7 < 300 ? static_cast<uint8_t>(k / 7 + 1)
                                                                  : 0;
    ASSERT_EQ(b[i], want) << "byte " << i;
  }
  // The reads above mapped every page (the zero page where untouched): ask again on a fresh map.
  ASSERT_EQ(munmap(m, n * page), 0);
  m = mmap(nullptr, n * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(m, MAP_FAILED);
  b = static_cast<uint8_t*>(m);
  if (madvise(b + 15 * page, page, MADV_POPULATE_WRITE) != 0) {
    munmap(m, n * page);
    GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE: the pages fault as before";
  }
  WritablePages v;
  v.Reset(b, n * page);
  v.Touch(b + 3 * page + 100, 8);
  v.Touch(b + 5 * page + 4000, 200);
  v.Touch(b + 8 * page, 8);
  v.Touch(b + 10 * page, 8);
  v.Touch(b + 8 * page + 100, 2 * page);  // pages 8 to 10: the first and last asked, not 9
  std::vector<unsigned char> in(n);
  ASSERT_EQ(mincore(m, n * page, in.data()), 0);
  for (size_t p = 0; p < n; ++p)
    EXPECT_EQ(in[p] & 1, p == 3 || p == 5 || p == 6 || (p >= 8 && p <= 10) || p == 15 ? 1 : 0)
        << "page " << p;
  munmap(m, n * page);
}

}  // namespace
}  // namespace meshreuse
