// Access sinks: what the instrumented smoother reports to. The smoother is a template over its sink
// (Ligra-style), so NullSink -- kEnabled == false -- removes every report at compile time and the
// timed loop is the uninstrumented loop.
//
// A sink receives, in program order and per thread, every load and store of mesh data that the
// compiled sweep makes (the *address stream*, DESIGN.md "Access"): its byte address, its size, the
// array it belongs to, and whether it reads or writes. Some of those accesses are also touches of a
// vertex record -- the paper's element model (its adjacency row, its coordinates read or written):
// they carry the element kind and the vertex id, and the subsequence of them is the *element
// stream*. One report per access, so both streams come from one sequence and never disagree.
// BeginSweep(k) comes before sweep k (1-based). The exact sequence of one vertex visit is in
// core/smoother.h. A traced run is serial: with P threads, thread t's stream is what thread t of
// the static schedule issues, in its order (the interleaving of threads is not modelled).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace meshreuse {

// The element kind of an access: which touch of a vertex record it is, or none.
enum class AccessKind : uint8_t {
  kAdjacency = 0,   // reading the vertex's adjacency row (its offset into the neighbour list)
  kCoordRead = 1,   // reading a vertex's coordinates
  kCoordWrite = 2,  // writing the moved vertex's coordinates
  kNone = 3,        // an access to mesh data that is not a touch of a vertex record
};
inline constexpr int kElementKinds = 3;

// The arrays the sweep reads and writes (core/mesh.h, core/smoother.h).
enum class Array : uint8_t {
  kInterior = 0,    // the interior vertex list (the iteration space)
  kAdjOffsets = 1,  // v2v.off
  kAdjIndex = 2,    // v2v.idx: neighbour ids
  kTriOffsets = 3,  // v2t.off
  kTriIndex = 4,    // v2t.idx: incident triangle ids
  kTriangles = 5,   // tri: three corners per triangle
  kTriQuality = 6,  // per-triangle quality kept by the smoother
  kWeights = 7,     // per-triangle weight in the global quality
  kCoords = 8,      // xy (Jacobi: the buffer read)
  kCoordsNext = 9,  // Jacobi only: the buffer written
  kLoopBound = 10,  // the sweep loop's end bound, a local read once per iteration (smoother.h)
};
inline constexpr int kArrays = 11;

struct MemRef {
  const void* address;
  uint32_t size;  // bytes
  Array array;
  bool write;
  AccessKind element = AccessKind::kNone;
  int32_t vertex = -1;  // the vertex whose record is touched, when element != kNone
};

const char* AccessKindName(AccessKind k);
const char* ArrayName(Array a);

// Where the swept arrays live in this run; the smoother hands it to its sink (Bind) before the
// first sweep.
struct ArrayLayout {
  std::array<uintptr_t, kArrays> base{};
  std::array<uint64_t, kArrays> bytes{};
};

// Canonical addresses: each array moved to a fixed place (in Array order from 2^32, each starting
// on a fresh 4 KiB page one page after the previous array ends; the loop bound at one fixed slot
// per thread), keeping its offset within the array. Which accesses share a line or a cache set,
// and so every line-level and simulated number, then depends on the mesh and the ordering alone,
// not on where malloc and ASLR put the arrays in this process: traces are byte for byte the same
// in every run, and a trace file and a streamed run give the same results. Every array is 64-byte
// aligned (core/aligned.h), so line sharing is the same as in the real run; the relative
// placement of arrays modulo a cache's set span is the one thing that differs from a given run.
class AddressCanonicalizer {
 public:
  // Where the first array is placed: above any small id a hand-fed sink might use, so the two
  // cannot collide. Analyses subtract it (TraceAnalysisOptions::line_base) to keep ids dense.
  static constexpr uint64_t kCanonicalBase = uint64_t{1} << 32;
  AddressCanonicalizer() = default;
  explicit AddressCanonicalizer(const ArrayLayout& l) : layout_(l) {
    uint64_t next = kCanonicalBase;
    for (int i = 0; i < kArrays; ++i) {
      int same = -1;  // two tags on one array (weights and qualities): one place
      for (int j = 0; j < i && same < 0; ++j)
        if (layout_.bytes[i] && layout_.base[j] == layout_.base[i]) same = j;
      if (same >= 0) {
        canon_[i] = canon_[same];
        continue;
      }
      canon_[i] = next;
      next = (next + layout_.bytes[i] + 4095) / 4096 * 4096 + 4096;
    }
  }
  uint64_t operator()(int thread, const MemRef& r) const {
    const uintptr_t a = reinterpret_cast<uintptr_t>(r.address);
    const int t = static_cast<int>(r.array);
    if (r.array == Array::kLoopBound) return canon_[t] + 64 * static_cast<uint64_t>(thread);
    if (a - layout_.base[t] < layout_.bytes[t]) return canon_[t] + (a - layout_.base[t]);
    for (int i = 0; i < kArrays; ++i)  // a swapped buffer (Jacobi) carries the other's tag
      if (a - layout_.base[i] < layout_.bytes[i]) return canon_[i] + (a - layout_.base[i]);
    return a;  // not a swept array (a sink fed by hand): as is
  }

 private:
  ArrayLayout layout_;
  std::array<uint64_t, kArrays> canon_{};
};

struct NullSink {
  static constexpr bool kEnabled = false;
  void Bind(const ArrayLayout&) {}
  void BeginSweep(int /*sweep*/) {}
  void Access(int /*thread*/, const MemRef&) {}
};

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

inline const char* AccessKindName(AccessKind k) {
  switch (k) {
    case AccessKind::kAdjacency:
      return "adjacency";
    case AccessKind::kCoordRead:
      return "coord-read";
    case AccessKind::kCoordWrite:
      return "coord-write";
    case AccessKind::kNone:
      return "none";
  }
  return "?";
}

inline const char* ArrayName(Array a) {
  static constexpr const char* kNames[kArrays] = {"interior", "v2v.off", "v2v.idx", "v2t.off",
                                                  "v2t.idx",  "tri",     "tq",      "w",
                                                  "xy",       "xy.next", "bound"};
  const int i = static_cast<int>(a);
  return i >= 0 && i < kArrays ? kNames[i] : "?";
}

}  // namespace meshreuse
