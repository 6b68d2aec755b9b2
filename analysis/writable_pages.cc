// WritablePages (writable_pages.h): the pages asked of the kernel once each.
#include "analysis/writable_pages.h"

#include <sys/mman.h>

namespace meshreuse {

void WritablePages::Reset(const void* block, uint64_t bytes) {
  const uintptr_t a = reinterpret_cast<uintptr_t>(block);
  first_page_ = a >> kShift;
  pages_ = bytes ? ((a + bytes - 1) >> kShift) - first_page_ + 1 : 0;
  left_ = pages_;
  done_.assign(pages_, 0);
}

void WritablePages::Populate(uint64_t page) {
  done_[page] = 1;
  --left_;
#ifdef MADV_POPULATE_WRITE
  // A page shared with the block's neighbours (its first and last) is theirs too: populating it
  // writes nothing, so it is harmless; a refusal (an older kernel) leaves the page as it was.
  (void)madvise(reinterpret_cast<void*>((first_page_ + page) << kShift), uint64_t{1} << kShift,
                MADV_POPULATE_WRITE);
#endif
}

}  // namespace meshreuse
