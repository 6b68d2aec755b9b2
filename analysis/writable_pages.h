// WritablePages: the pages of a calloc'ed block (fresh, untouched pages) made present and
// writable before their first read. A read first maps the shared zero page, and the write after it
// copies the page and flushes it from the TLB of every core the process runs on, an interrupt to
// each (in a report's jobs side by side on 2 cores, 12% of a --quick run's CPU time by perf, the
// 24-way level's sets read by a lookup before their first install). Touch asks the kernel once per
// page (MADV_POPULATE_WRITE, Linux 5.14; where it is refused, nothing: the pages fault as before).
// The contents never change; memory still follows the pages touched. Used by the cache simulators
// (cache_sim.h, multicore_sim.h) for their levels' sets and line records.
#pragma once

#include <cstdint>
#include <vector>

namespace meshreuse {

class WritablePages {
 public:
  void Reset(const void* block, uint64_t bytes);  // a block to follow (none: bytes 0)
  void Touch(const void* p, uint64_t bytes) {     // [p, p + bytes), inside the block
    // Nothing to ask once every page has been (a level's sets, full after the first sweep; a
    // level too small to follow): one test instead of the pages' (issue 40: they were 3% of a
    // one-thread many-core run's instructions, asked at every miss for each level below).
    if (left_ == 0) return;
    const uint64_t first = (reinterpret_cast<uintptr_t>(p) >> kShift) - first_page_;
    const uint64_t last = ((reinterpret_cast<uintptr_t>(p) + bytes - 1) >> kShift) - first_page_;
    // Most often one or two pages, asked already (a block that never fills, such as the records'
    // or a level's sets that a run does not cover, keeps left_ above 0 to the end).
    if (last - first <= 1 && last < pages_ && (done_[first] & done_[last])) return;
    for (uint64_t k = first; k <= last && k < pages_; ++k)
      if (!done_[k]) Populate(k);
  }

 private:
  static constexpr int kShift = 12;  // 4 KiB pages
  void Populate(uint64_t page);
  uint64_t first_page_ = 0, pages_ = 0;
  uint64_t left_ = 0;          // pages not asked yet
  std::vector<uint8_t> done_;  // a byte per page (1: asked already)
};

}  // namespace meshreuse
