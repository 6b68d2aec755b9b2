// Access sinks: what the instrumented smoother reports to. The smoother is a template over its sink
// (Ligra-style), so NullSink -- kEnabled == false -- removes every report at compile time and the
// timed loop is the uninstrumented loop. A sink receives, in program order and per thread, each
// touch of a vertex record: which vertex, which kind of touch, and the byte address touched, and
// BeginSweep(k) before sweep k (1-based). The exact sequence of one vertex visit is in
// core/smoother.h. A traced run is serial: with P threads, thread t's stream is what thread t of
// the static schedule issues, in its order (the interleaving of threads is not modelled).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace meshreuse {

enum class AccessKind : uint8_t {
  kAdjacency = 0,   // reading the vertex's adjacency row (offsets into the neighbour list)
  kCoordRead = 1,   // reading a vertex's coordinates
  kCoordWrite = 2,  // writing the moved vertex's coordinates
};

const char* AccessKindName(AccessKind k);

struct NullSink {
  static constexpr bool kEnabled = false;
  void BeginSweep(int /*sweep*/) {}
  void Touch(int /*thread*/, AccessKind, int32_t /*vertex*/, const void* /*address*/) {}
};

// Counts touches per thread and kind; the reference for AccessesPerSweep and the access tests.
struct CountingSink {
  static constexpr bool kEnabled = true;
  std::vector<std::array<uint64_t, 3>> per_thread;  // [thread][kind]
  int sweeps = 0;
  void BeginSweep(int) { ++sweeps; }
  void Touch(int thread, AccessKind k, int32_t, const void*) {
    if (static_cast<size_t>(thread) >= per_thread.size()) per_thread.resize(thread + 1, {0, 0, 0});
    ++per_thread[thread][static_cast<int>(k)];
  }
  uint64_t Total() const {
    uint64_t s = 0;
    for (const auto& a : per_thread) s += a[0] + a[1] + a[2];
    return s;
  }
};

// Records every touch; for tests on tiny meshes.
struct RecordingSink {
  static constexpr bool kEnabled = true;
  struct Touched {
    int thread;
    AccessKind kind;
    int32_t vertex;
    const void* address;
    bool operator==(const Touched& o) const {
      return thread == o.thread && kind == o.kind && vertex == o.vertex && address == o.address;
    }
  };
  std::vector<Touched> touches;
  std::vector<size_t> sweep_starts;  // index into touches where each sweep begins
  void BeginSweep(int) { sweep_starts.push_back(touches.size()); }
  void Touch(int thread, AccessKind k, int32_t v, const void* a) {
    touches.push_back({thread, k, v, a});
  }
};

inline const char* AccessKindName(AccessKind k) {
  switch (k) {
    case AccessKind::kAdjacency:
      return "adjacency";
    case AccessKind::kCoordRead:
      return "coord-read";
    case AccessKind::kCoordWrite:
      return "coord-write";
  }
  return "?";
}

}  // namespace meshreuse
