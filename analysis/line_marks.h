// A record per cache line of a stream, found by the line's number: a vector indexed from the
// canonical base for the arrays the tracer lays out there (the smoother's and every kernel's, so
// the records of a mesh's lines sit side by side), a hash table for any other address (a trace
// file's own addresses, a non-canonical stream). Used where a consumer marks each line with the
// last sweep that touched it: the sweep footprint (analysis/sweep_footprint.h) and the working set
// (reports/working_set.h). Records start value-initialised (Mark{}).
#pragma once

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/access.h"

namespace meshreuse {

template <class Mark>
class LineMarks {
 public:
  LineMarks() = default;
  // canonical: the stream's addresses are canonical (StreamInfo::canonical).
  LineMarks(bool canonical, uint32_t line_bytes)
      : canonical_(canonical), base_(AddressCanonicalizer::kCanonicalBase / line_bytes) {}

  Mark& At(uint64_t line) {
    if (canonical_ && line >= base_ && line - base_ < (uint64_t{1} << 32)) {
      const uint64_t i = line - base_;
      if (i >= dense_.size()) dense_.resize(std::max<uint64_t>(i + 1, dense_.size() * 2));
      return dense_[i];
    }
    return hashed_[line];
  }

 private:
  bool canonical_ = false;
  uint64_t base_ = 0;
  std::vector<Mark> dense_;
  std::unordered_map<uint64_t, Mark> hashed_;
};

}  // namespace meshreuse
