// A text file of vertex ids, one 0-based id per line ('#' starts a comment): the format of
// permutations (`--ordering file:PATH`, orderings/file.cc) and of serial visit orders
// (`smooth --visit-order`, visit_order.h). Every id must lie in [0, n) and appear at most once;
// each reader adds its own rule per id and its own rule for what must be present.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/text_file.h"

namespace meshreuse {

struct VertexIdList {
  std::vector<int32_t> ids;      // in file order
  std::vector<int64_t> line_of;  // per vertex: the line naming it, 0 when none does
};

// Reads every data line of `f`. InputError naming the file and line for a line that is not one
// integer, an id outside [0, n) (saying ids are 0-based), a repeat (with the line of its first
// use), and whatever `also(id)` rejects (it calls f.Fail).
VertexIdList ReadVertexIdList(TextFile& f, int32_t n,
                              const std::function<void(int64_t id)>& also = {});

}  // namespace meshreuse
