// ori: the identity. The vertices stay in the order the mesh file gives them; for the shipped
// shapes that is Triangle's numbering, the paper's ORI baseline.
#include "core/orderings/registry.h"

namespace meshreuse {

Permutation OrderOri(const Mesh& m, const OrderingContext&) {
  return Permutation::Identity(m.NumVertices());
}

}  // namespace meshreuse
