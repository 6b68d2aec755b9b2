// ReadVertexIdList: see vertex_id_list.h.
#include "core/vertex_id_list.h"

#include <string>
#include <string_view>

namespace meshreuse {

VertexIdList ReadVertexIdList(TextFile& f, int32_t n, const std::function<void(int64_t)>& also) {
  VertexIdList r;
  r.line_of.assign(static_cast<size_t>(n), 0);
  std::string_view line, tok;
  while (f.NextDataLine(&line)) {
    Tokens t(line);
    t.Next(&tok);
    if (t.Next(&tok)) f.Fail("expected one vertex id per line");
    const int64_t id = f.ParseInt(line, "a vertex id");
    if (id < 0 || id >= n)
      f.Fail("vertex id " + std::to_string(id) + " is outside 0.." + std::to_string(n - 1) +
             " (the mesh has " + std::to_string(n) + " vertices; ids are 0-based)");
    if (also) also(id);
    if (r.line_of[id] != 0)
      f.Fail("vertex id " + std::to_string(id) + " is repeated (first on line " +
             std::to_string(r.line_of[id]) + ")");
    r.line_of[id] = f.line();
    r.ids.push_back(static_cast<int32_t>(id));
  }
  return r;
}

}  // namespace meshreuse
