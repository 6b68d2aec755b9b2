// Sorting ids (non-negative, below 2^32) in O(n): least-significant-digit radix sort in two passes
// of 16 bits, then duplicates dropped. A rank's read of a mesh file and its part's layout sort a
// few entries per vertex (tens of millions on a large part), where std::sort's n log n was a third
// of the set-up time. Reference: Knuth, TAOCP vol. 3, 5.2.5 (LSD radix sorting).
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace meshreuse {

template <class T>
void RadixSortUnique(std::vector<T>* v) {
  std::vector<T>& a = *v;
  if (a.size() < 2) return;
  std::vector<T> b(a.size());
  for (int shift = 0; shift < 32; shift += 16) {
    std::vector<size_t> count((1u << 16) + 1, 0);
    for (T x : a) {
      if (x < 0 || static_cast<uint64_t>(x) >> 32)
        throw std::logic_error("RadixSortUnique: an id outside [0, 2^32)");
      ++count[((static_cast<uint64_t>(x) >> shift) & 0xFFFF) + 1];
    }
    for (size_t d = 1; d < count.size(); ++d) count[d] += count[d - 1];
    for (T x : a) b[count[(static_cast<uint64_t>(x) >> shift) & 0xFFFF]++] = x;
    a.swap(b);
  }
  a.erase(std::unique(a.begin(), a.end()), a.end());
}

}  // namespace meshreuse
