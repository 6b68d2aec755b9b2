// rcm: reverse Cuthill-McKee (Cuthill and McKee 1969; George and Liu's reversal, 1981), by
// Boost.Graph's cuthill_mckee_ordering (libboost-graph-dev, header-only): per connected component
// from a pseudo-peripheral vertex found by Boost's own search, a BFS queueing unvisited neighbours
// by increasing degree; the order reversed. Until issue 10 this file had its own implementation
// (George-Liu start, ties by id); on the 18 meshes new_orderings_test.cc used then (16 synthetic,
// two_interior, two_components) it had a larger bandwidth than Boost's on 10 and a smaller one on 3
// (profile: larger on 10), so the better, widely used one is used. The test checks rcm equals
// Boost's order.
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>
#include <utility>
#include <vector>

#include "core/orderings/registry.h"

namespace meshreuse {

Permutation OrderRcm(const Mesh& m, const OrderingContext&) {
  // The mesh's adjacency as Boost's CSR graph (both directions of every edge, rows in id order,
  // as an undirected adjacency_list would give them): built in O(V + E), unlike adding edges one
  // by one to an adjacency_list (2.8x slower on carabiner: 264 against 95 ms).
  using Graph = boost::compressed_sparse_row_graph<boost::directedS>;
  const int32_t n = m.NumVertices();
  std::vector<std::pair<int32_t, int32_t>> edges;
  edges.reserve(m.v2v.idx.size());
  for (int32_t v = 0; v < n; ++v)
    for (const int32_t* p = m.v2v.RowBegin(v); p != m.v2v.RowEnd(v); ++p) edges.emplace_back(v, *p);
  const Graph g(boost::edges_are_sorted, edges.begin(), edges.end(), static_cast<size_t>(n));
  std::vector<boost::default_color_type> color(n);
  std::vector<int32_t> degree(n);
  for (int32_t v = 0; v < n; ++v) degree[v] = static_cast<int32_t>(m.v2v.RowSize(v));
  const auto index = boost::get(boost::vertex_index, g);
  std::vector<Graph::vertex_descriptor> order(n);  // filled back to front: the reversal
  boost::cuthill_mckee_ordering(g, order.rbegin(),
                                boost::make_iterator_property_map(color.begin(), index),
                                boost::make_iterator_property_map(degree.begin(), index));
  return Permutation::FromNewToOld(std::vector<int32_t>(order.begin(), order.end()));
}

}  // namespace meshreuse
