// rdr-wave: a wavefront reading of RDR -- breadth-first search whose tie-break is the paper's
// quality order. A FIFO queue starts at the worst-quality interior vertex; each dequeued vertex
// appends (and enqueues) its not yet placed neighbours in increasing initial vertex quality (ties
// by id). When the queue empties, the worst interior vertex not yet placed starts the next wave;
// vertices no wave reaches (components without interior vertices) are appended in id order.
#include "core/orderings/common.h"
#include "core/orderings/rdr.h"
#include "core/orderings/registry.h"
#include "core/quality.h"

namespace meshreuse {

Permutation RdrWaveOrder(const Mesh& m, const std::vector<double>& quality) {
  const int32_t n = m.NumVertices();
  const std::vector<int32_t> nbr = orderings::RowsByKey(m, quality);
  const int64_t* off = m.v2v.off.data();
  std::vector<uint8_t> placed(n, 0);
  std::vector<int32_t> order;  // also the FIFO: order[head..] are placed, not yet dequeued
  order.reserve(n);
  for (const int32_t s :
       orderings::StableSortByKey({m.interior.begin(), m.interior.end()}, quality)) {
    if (placed[s]) continue;
    placed[s] = 1;
    order.push_back(s);
    for (size_t head = order.size() - 1; head < order.size(); ++head) {
      const int32_t v = order[head];
      for (const int32_t* p = nbr.data() + off[v]; p != nbr.data() + off[v + 1]; ++p)
        if (!placed[*p]) {
          placed[*p] = 1;
          order.push_back(*p);
        }
    }
  }
  for (int32_t v = 0; v < n; ++v)
    if (!placed[v]) order.push_back(v);
  return Permutation::FromNewToOld(std::move(order));
}

Permutation OrderRdrWave(const Mesh& m, const OrderingContext&) {
  return RdrWaveOrder(m, VertexQualities(m));
}

}  // namespace meshreuse
