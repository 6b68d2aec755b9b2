// rcm: reverse Cuthill-McKee. Per connected component (taken in order of their lowest vertex id):
// find a pseudo-peripheral vertex by the George-Liu iteration (BFS, move to a minimum-degree vertex
// of the last level while the eccentricity grows), then Cuthill-McKee: BFS queueing each vertex's
// unvisited neighbours by increasing degree (ties by id). The whole order is reversed at the end.
#include <algorithm>

#include "core/orderings/registry.h"

namespace meshreuse {

namespace {

struct Levels {
  int32_t eccentricity;
  std::vector<int32_t> last;  // the vertices of the last level
};

// BFS from r over r's component; `stamp`/`round` avoid clearing a V-sized array per call.
Levels BfsLevels(const Mesh& m, int32_t r, std::vector<int32_t>& stamp, int32_t round,
                 std::vector<int32_t>& queue) {
  queue.clear();
  queue.push_back(r);
  stamp[r] = round;
  size_t level_begin = 0;
  int32_t ecc = 0;
  while (true) {
    const size_t level_end = queue.size();
    for (size_t i = level_begin; i < level_end; ++i)
      for (const int32_t* p = m.v2v.RowBegin(queue[i]); p != m.v2v.RowEnd(queue[i]); ++p)
        if (stamp[*p] != round) {
          stamp[*p] = round;
          queue.push_back(*p);
        }
    if (queue.size() == level_end)
      return {ecc, std::vector<int32_t>(queue.begin() + level_begin, queue.begin() + level_end)};
    level_begin = level_end;
    ++ecc;
  }
}

}  // namespace

Permutation OrderRcm(const Mesh& m, const OrderingContext&) {
  const int32_t n = m.NumVertices();
  auto degree = [&](int32_t v) { return m.v2v.RowSize(v); };
  std::vector<int32_t> order, queue, stamp(n, -1), nbr;
  order.reserve(n);
  std::vector<uint8_t> done(n, 0);
  int32_t round = 0;
  for (int32_t s = 0; s < n; ++s) {
    if (done[s]) continue;
    int32_t r = s;
    Levels lv = BfsLevels(m, r, stamp, round++, queue);
    while (true) {
      const int32_t x =
          *std::min_element(lv.last.begin(), lv.last.end(), [&](int32_t a, int32_t b) {
            return degree(a) != degree(b) ? degree(a) < degree(b) : a < b;
          });
      Levels lx = BfsLevels(m, x, stamp, round++, queue);
      if (lx.eccentricity <= lv.eccentricity) break;
      r = x;
      lv = std::move(lx);
    }
    const size_t first = order.size();
    order.push_back(r);
    done[r] = 1;
    for (size_t head = first; head < order.size(); ++head) {
      const int32_t v = order[head];
      nbr.clear();
      for (const int32_t* p = m.v2v.RowBegin(v); p != m.v2v.RowEnd(v); ++p)
        if (!done[*p]) {
          done[*p] = 1;
          nbr.push_back(*p);
        }
      std::stable_sort(nbr.begin(), nbr.end(),
                       [&](int32_t a, int32_t b) { return degree(a) < degree(b); });
      order.insert(order.end(), nbr.begin(), nbr.end());
    }
  }
  std::reverse(order.begin(), order.end());
  return Permutation::FromNewToOld(std::move(order));
}

}  // namespace meshreuse
