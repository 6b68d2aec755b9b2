// Shared ordering helpers; see common.h.
#include "core/orderings/common.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "core/error.h"

namespace meshreuse::orderings {

std::vector<int32_t> StableSortByKey(const std::vector<int32_t>& ids,
                                     const std::vector<double>& key) {
  const size_t n = ids.size();
  if (n < 2) return ids;
  double lo = key[ids[0]], hi = lo;
  for (int32_t i : ids) lo = std::min(lo, key[i]), hi = std::max(hi, key[i]);
  if (!(hi > lo)) return ids;  // all keys equal: stable means unchanged
  // About 8 keys a bucket: the count array stays cache-resident, insertion sorts stay short.
  const size_t nb = std::max<size_t>(1, n / 8);
  const double scale = static_cast<double>(nb - 1) / (hi - lo);
  std::vector<uint32_t> bucket(n), start(nb + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const double b = std::floor((key[ids[i]] - lo) * scale);
    bucket[i] = static_cast<uint32_t>(std::min(b, static_cast<double>(nb - 1)));
    ++start[bucket[i] + 1];
  }
  for (size_t b = 0; b < nb; ++b) start[b + 1] += start[b];
  std::vector<int32_t> out(n);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < n; ++i) out[fill[bucket[i]]++] = ids[i];
  }
  auto less = [&](int32_t a, int32_t b) { return key[a] < key[b]; };
  for (size_t b = 0; b < nb; ++b) {
    int32_t* first = out.data() + start[b];
    int32_t* last = out.data() + start[b + 1];
    if (last - first < 2) continue;
    if (last - first > 64) {
      std::stable_sort(first, last, less);
      continue;
    }
    for (int32_t* p = first + 1; p < last; ++p) {  // insertion sort: stable, tiny buckets
      const int32_t v = *p;
      int32_t* q = p;
      for (; q > first && less(v, q[-1]); --q) *q = q[-1];
      *q = v;
    }
  }
  return out;
}

std::vector<int32_t> SortAlongCurve(const Mesh& m, uint64_t (*index)(uint32_t, uint32_t)) {
  const int32_t n = m.NumVertices();
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int32_t v = 0; v < n; ++v) {
    x0 = std::min(x0, m.xy[2 * int64_t{v}]), x1 = std::max(x1, m.xy[2 * int64_t{v}]);
    y0 = std::min(y0, m.xy[2 * int64_t{v} + 1]), y1 = std::max(y1, m.xy[2 * int64_t{v} + 1]);
  }
  const double sx = x1 > x0 ? 65535.0 / (x1 - x0) : 0.0;
  const double sy = y1 > y0 ? 65535.0 / (y1 - y0) : 0.0;
  std::vector<double> key(n);  // an index below 2^32 is exact in a double
  std::vector<int32_t> ids(n);
  for (int32_t v = 0; v < n; ++v) {
    const auto gx =
        static_cast<uint32_t>(std::clamp((m.xy[2 * int64_t{v}] - x0) * sx, 0.0, 65535.0));
    const auto gy =
        static_cast<uint32_t>(std::clamp((m.xy[2 * int64_t{v} + 1] - y0) * sy, 0.0, 65535.0));
    key[v] = static_cast<double>(index(gx, gy));
    ids[v] = v;
  }
  return StableSortByKey(ids, key);
}

std::vector<int32_t> RowsByKey(const Mesh& m, const std::vector<double>& key) {
  std::vector<int32_t> nbr(m.v2v.idx.begin(), m.v2v.idx.end());
  const int64_t* off = m.v2v.off.data();
  for (int32_t v = 0; v < m.NumVertices(); ++v) {
    int32_t* b = nbr.data() + off[v];
    int32_t* e = nbr.data() + off[v + 1];
    if (e - b > 32) {  // a hub: O(d log d), not the insertion sort's O(d^2)
      std::stable_sort(b, e, [&](int32_t x, int32_t y) { return key[x] < key[y]; });
      continue;
    }
    for (int32_t* p = b + 1; p < e; ++p) {
      const int32_t u = *p;
      const double ku = key[u];
      int32_t* k = p;
      for (; k > b && key[k[-1]] > ku; --k) *k = k[-1];
      *k = u;
    }
  }
  return nbr;
}

uint64_t ParseCacheBytes(const std::string& arg, uint64_t dflt, const char* name) {
  if (arg.empty()) return dflt;
  size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(arg, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (arg[0] == '-' || arg[0] == '+' || std::isspace(static_cast<unsigned char>(arg[0]))) used = 0;
  uint64_t mult = 1;
  if (used + 1 == arg.size() && (arg[used] == 'K' || arg[used] == 'k')) mult = 1024, ++used;
  if (used + 1 == arg.size() && (arg[used] == 'M' || arg[used] == 'm')) mult = 1 << 20, ++used;
  if (used != arg.size() || v == 0 || v > (uint64_t{1} << 40) / mult)
    throw UsageError(std::string(name) +
                     ":BYTES needs a positive size such as 262144 or 256K, not '" + arg + "'");
  return v * mult;
}

double SweepBytesPerVertex(const Mesh& m) {
  const double v = m.NumVertices(), t = m.NumTriangles();
  const double bytes = 16 * v + 8 * (v + 1) + 4.0 * m.v2v.idx.size() + 8 * (v + 1) +
                       4.0 * m.v2t.idx.size() + 12 * t + 16 * t + 4.0 * m.interior.size();
  return v > 0 ? bytes / v : 0;
}

PartLayout LayOutParts(const Mesh& m, const std::vector<int32_t>& part, int32_t parts) {
  const int32_t n = m.NumVertices();
  PartLayout l;
  l.first.assign(static_cast<size_t>(parts) + 1, 0);
  for (int32_t v = 0; v < n; ++v) ++l.first[part[v] + 1];
  for (int32_t p = 0; p < parts; ++p) l.first[p + 1] += l.first[p];
  l.members.resize(n);
  {
    std::vector<int64_t> at(l.first.begin(), l.first.end() - 1);
    for (int32_t v = 0; v < n; ++v) l.members[at[part[v]]++] = v;
  }
  std::vector<std::vector<int32_t>> pnbr(parts);
  for (int32_t v = 0; v < n; ++v)
    for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
      if (part[*q] != part[v]) pnbr[part[v]].push_back(part[*q]);
  for (auto& r : pnbr) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  std::vector<uint8_t> seen(parts, 0);
  auto bfs = [&](int32_t s) {
    seen[s] = 1;
    l.order.push_back(s);
    for (size_t h = l.order.size() - 1; h < l.order.size(); ++h)
      for (int32_t q : pnbr[l.order[h]])
        if (!seen[q]) seen[q] = 1, l.order.push_back(q);
  };
  if (n > 0) bfs(part[0]);
  for (int32_t p = 0; p < parts; ++p)
    if (!seen[p]) bfs(p);
  return l;
}

}  // namespace meshreuse::orderings
