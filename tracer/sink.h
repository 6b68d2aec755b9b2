// Sinks for tests and composition: counting, recording and fan-out (two sinks fed from one sweep).
// What a sink receives (core/access.h): in program order and per thread, every load and store of
// mesh data that the compiled sweep makes (the *address stream*, DESIGN.md "Access"), some of them
// also touches of a vertex record (the *element stream*, the paper's model); BeginSweep(k) before
// sweep k (1-based). The exact sequence of one vertex visit is in core/smoother.h. A traced run is
// serial: with P threads, thread t's stream is what thread t of the static schedule issues, in its
// order (the interleaving of threads is not modelled here).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/access.h"

namespace meshreuse {

// Counts accesses per thread: element touches per kind, and all accesses per array and direction.
// The reference for AccessesPerSweep / RefsPerSweep and the access tests.
struct CountingSink {
  static constexpr bool kEnabled = true;
  struct PerThread {
    std::array<uint64_t, kElementKinds> kind{};
    std::array<std::array<uint64_t, 2>, kArrays> array{};  // [array][write]
  };
  std::vector<PerThread> per_thread;
  int sweeps = 0;
  void Bind(const ArrayLayout&) {}
  void BeginSweep(int) { ++sweeps; }
  void Access(int thread, const MemRef& r) {
    if (static_cast<size_t>(thread) >= per_thread.size()) per_thread.resize(thread + 1);
    PerThread& p = per_thread[thread];
    if (r.element != AccessKind::kNone) ++p.kind[static_cast<int>(r.element)];
    ++p.array[static_cast<int>(r.array)][r.write];
  }
  uint64_t Elements() const {  // element touches, all threads
    uint64_t s = 0;
    for (const PerThread& p : per_thread)
      for (uint64_t n : p.kind) s += n;
    return s;
  }
  uint64_t Refs() const {  // loads and stores, all threads
    uint64_t s = 0;
    for (const PerThread& p : per_thread)
      for (const auto& a : p.array) s += a[0] + a[1];
    return s;
  }
};

// Sends every report to two sinks (e.g. the reuse analysis and the cache simulator in one pass).
template <class A, class B>
struct FanOutSink {
  static constexpr bool kEnabled = A::kEnabled || B::kEnabled;
  A& a;
  B& b;
  void Bind(const ArrayLayout& l) {
    a.Bind(l);
    b.Bind(l);
  }
  void BeginSweep(int s) {
    a.BeginSweep(s);
    b.BeginSweep(s);
  }
  void Access(int thread, const MemRef& r) {
    a.Access(thread, r);
    b.Access(thread, r);
  }
};

// Records every access; for tests on tiny meshes. `touches` is the element stream.
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
  struct Ref {
    int thread;
    MemRef ref;
  };
  std::vector<Touched> touches;
  std::vector<Ref> refs;
  std::vector<size_t> sweep_starts;  // index into touches where each sweep begins
  ArrayLayout layout;
  void Bind(const ArrayLayout& l) { layout = l; }
  void BeginSweep(int) { sweep_starts.push_back(touches.size()); }
  void Access(int thread, const MemRef& r) {
    refs.push_back({thread, r});
    if (r.element != AccessKind::kNone) touches.push_back({thread, r.element, r.vertex, r.address});
  }
};

}  // namespace meshreuse
