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
#include "core/vertex_id_list.h"

namespace meshreuse {

Permutation OrderFile(const Mesh& m, const OrderingContext& ctx) {
  const int32_t n = m.NumVertices();
  TextFile f(ctx.argument);
  VertexIdList l = ReadVertexIdList(f, n);
  if (static_cast<int32_t>(l.ids.size()) != n) {
    int32_t missing = 0;
    while (missing < n && l.line_of[missing] != 0) ++missing;
    throw InputError(ctx.argument, f.line(),
                     "the file has " + std::to_string(l.ids.size()) + " ids, the mesh " +
                         std::to_string(n) + " vertices (vertex " + std::to_string(missing) +
                         " is missing)");
  }
  return Permutation::FromNewToOld(std::move(l.ids));
}

}  // namespace meshreuse
