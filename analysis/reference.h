// Reference (verifier) implementations of the stack distance, for tests and benchmarks: the
// textbook method, a Fenwick tree over every time position plus a hash map of last accesses
// (O(N log N) time, O(N) memory). Simple enough to trust; StackDistance must agree with it exactly.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "analysis/stack_distance.h"

namespace meshreuse {

template <class Id>
std::vector<uint64_t> TextbookStackDistances(const std::vector<Id>& trace) {
  const size_t n = trace.size();
  std::vector<int64_t> tree(n + 1, 0);
  auto add = [&](size_t i, int64_t d) {
    for (++i; i <= n; i += i & (~i + 1)) tree[i] += d;
  };
  auto prefix = [&](size_t i) {  // sum over positions [0, i)
    int64_t s = 0;
    for (; i > 0; i -= i & (~i + 1)) s += tree[i];
    return s;
  };
  std::unordered_map<Id, size_t> last;
  std::vector<uint64_t> out;
  out.reserve(n);
  for (size_t t = 0; t < n; ++t) {
    auto f = last.find(trace[t]);
    if (f == last.end()) {
      out.push_back(StackDistance::kCold);
      last.emplace(trace[t], t);
    } else {
      out.push_back(static_cast<uint64_t>(prefix(t) - prefix(f->second + 1)));
      add(f->second, -1);
      f->second = t;
    }
    add(t, 1);
  }
  return out;
}

}  // namespace meshreuse
