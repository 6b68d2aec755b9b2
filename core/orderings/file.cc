// file:PATH -- a user's permutation: one 0-based vertex id per line, in new order (line k holds the
// id of the vertex that goes to position k). '#' starts a comment. Ids are the mesh's own
// numbering as meshreuse reads it (for .node files: the file's ids minus their base; vertices that
// no triangle uses are dropped before numbering). `meshreuse reorder` writes this format.
// Every problem is an InputError naming the file and line: a non-number, an id out of range, a
// repeated id (with the line of its first use), too few ids (naming a missing one). Too many ids
// cannot pass: the extra one is out of range or a repeat.
#include <string>

#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/text_file.h"

namespace meshreuse {

Permutation OrderFile(const Mesh& m, const OrderingContext& ctx) {
  const int32_t n = m.NumVertices();
  TextFile f(ctx.argument);
  std::vector<int32_t> order;
  order.reserve(n);
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
    if (line_of[id] != 0)
      f.Fail("vertex id " + std::to_string(id) + " is repeated (first on line " +
             std::to_string(line_of[id]) + ")");
    line_of[id] = f.line();
    order.push_back(static_cast<int32_t>(id));
  }
  if (static_cast<int32_t>(order.size()) != n) {
    int32_t missing = 0;
    while (missing < n && line_of[missing] != 0) ++missing;
    throw InputError(ctx.argument, f.line(),
                     "the file has " + std::to_string(order.size()) + " ids, the mesh " +
                         std::to_string(n) + " vertices (vertex " + std::to_string(missing) +
                         " is missing)");
  }
  return Permutation::FromNewToOld(std::move(order));
}

}  // namespace meshreuse
