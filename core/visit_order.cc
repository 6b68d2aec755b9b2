// ReadVisitOrder (visit_order.h): the file:PATH reader's checks, for the interior vertices only.
#include "core/visit_order.h"

#include <vector>

#include "core/error.h"
#include "core/text_file.h"
#include "core/vertex_id_list.h"

namespace meshreuse {

AlignedVector<int32_t> ReadVisitOrder(const std::string& path, const Mesh& m) {
  const int32_t n = m.NumVertices();
  TextFile f(path);
  const VertexIdList l = ReadVertexIdList(f, n, [&](int64_t id) {
    if (m.boundary[id]) f.Fail("vertex " + std::to_string(id) + " is on the boundary (fixed)");
  });
  if (l.ids.size() != m.interior.size()) {
    int32_t missing = 0;
    while (missing < n && (m.boundary[missing] || l.line_of[missing] != 0)) ++missing;
    throw InputError(path, f.line(),
                     "the file lists " + std::to_string(l.ids.size()) + " vertices, the mesh has " +
                         std::to_string(m.interior.size()) + " interior ones (vertex " +
                         std::to_string(missing) + " is missing)");
  }
  return AlignedVector<int32_t>(l.ids.begin(), l.ids.end());
}

}  // namespace meshreuse
