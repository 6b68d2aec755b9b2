// Access sinks: what the instrumented smoother reports to. The smoother is a template over its sink
// (Ligra-style), so NullSink -- kEnabled == false -- removes every report at compile time and the
// timed loop is the uninstrumented loop. A sink receives, in program order and per thread, each
// touch of a vertex record: which vertex, which kind of touch, and the byte address touched.
#pragma once

#include <cstdint>

namespace meshreuse {

enum class AccessKind : uint8_t {
  kAdjacency = 0,   // reading the vertex's adjacency row (offsets into the neighbour list)
  kCoordRead = 1,   // reading a vertex's coordinates
  kCoordWrite = 2,  // writing the moved vertex's coordinates
};

struct NullSink {
  static constexpr bool kEnabled = false;
  void Touch(int /*thread*/, AccessKind, int32_t /*vertex*/, const void* /*address*/) {}
};

}  // namespace meshreuse
