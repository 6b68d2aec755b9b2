// rcm: reverse Cuthill-McKee (Cuthill and McKee 1969; George and Liu's reversal, 1981), by
// Boost.Graph's cuthill_mckee_ordering (libboost-graph-dev, header-only): per connected component
// from a pseudo-peripheral vertex found by Boost's own search, a BFS queueing unvisited neighbours
// by increasing degree; the order reversed. Until issue 10 this file had its own implementation
// (George-Liu start, ties by id); on the 18 meshes of tests/core/orderings/new_orderings_test.cc
// it had a larger bandwidth than Boost's on 10 and a smaller one on 3 (profile: larger on 10),
// so the better, widely used one is used. The test checks rcm equals Boost's order.
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>

#include "core/orderings/registry.h"

namespace meshreuse {

Permutation OrderRcm(const Mesh& m, const OrderingContext&) {
  using Graph =
      boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS,
                            boost::property<boost::vertex_color_t, boost::default_color_type,
                                            boost::property<boost::vertex_degree_t, int>>>;
  const int32_t n = m.NumVertices();
  Graph g(n);
  for (int32_t v = 0; v < n; ++v)
    for (const int32_t* p = m.v2v.RowBegin(v); p != m.v2v.RowEnd(v); ++p)
      if (v < *p) boost::add_edge(v, *p, g);
  std::vector<Graph::vertex_descriptor> order(n);  // filled back to front: the reversal
  boost::cuthill_mckee_ordering(g, order.rbegin(), boost::get(boost::vertex_color, g),
                                boost::make_degree_map(g));
  return Permutation::FromNewToOld(std::vector<int32_t>(order.begin(), order.end()));
}

}  // namespace meshreuse
