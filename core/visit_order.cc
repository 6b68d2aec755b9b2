// ReadVisitOrder (visit_order.h): the file:PATH reader's checks, for the interior vertices only.
#include "core/visit_order.h"

#include <vector>

#include "core/error.h"
#include "core/text_file.h"

namespace meshreuse {

AlignedVector<int32_t> ReadVisitOrder(const std::string& path, const Mesh& m) {
  const int32_t n = m.NumVertices();
  TextFile f(path);
  AlignedVector<int32_t> order;
  order.reserve(m.interior.size());
  std::vector<int64_t> line_of(n, 0);
  std::string_view line, tok;
  while (f.NextDataLine(&line)) {
    Tokens t(line);
    t.Next(&tok);
    if (t.Next(&tok)) f.Fail("expected one vertex id per line");
    const int64_t id = f.ParseInt(line, "a vertex id");
    if (id < 0 || id >= n)
      f.Fail("vertex id " + std::to_string(id) + " is outside 0.." + std::to_string(n - 1) +
             " (the mesh has " + std::to_string(n) + " vertices; ids are 0-based)");
    if (m.boundary[id]) f.Fail("vertex " + std::to_string(id) + " is on the boundary (fixed)");
    if (line_of[id] != 0)
      f.Fail("vertex id " + std::to_string(id) + " is repeated (first on line " +
             std::to_string(line_of[id]) + ")");
    line_of[id] = f.line();
    order.push_back(static_cast<int32_t>(id));
  }
  if (order.size() != m.interior.size()) {
    int32_t missing = 0;
    while (missing < n && (m.boundary[missing] || line_of[missing] != 0)) ++missing;
    throw InputError(path, f.line(),
                     "the file lists " + std::to_string(order.size()) + " vertices, the mesh has " +
                         std::to_string(m.interior.size()) + " interior ones (vertex " +
                         std::to_string(missing) + " is missing)");
  }
  return order;
}

}  // namespace meshreuse
