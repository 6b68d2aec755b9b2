// The smoother's access vocabulary: what an access of the sweep is (its array, size, direction,
// and, for the paper's element model, which vertex record it touches), where the swept arrays live
// (ArrayLayout), their canonical addresses, the sink that records nothing (NullSink), and the
// region interface that hardware counters hook into (SweepRegion). Everything above the smoother
// (tracer, analysis, reports) speaks this vocabulary; it lives in core because the smoother, its
// lowest user, does.
#pragma once

#include <array>
#include <cstdint>

#include "core/schedule.h"

namespace meshreuse {

// The element kind of an access: which touch of a vertex record it is, or none.
enum class AccessKind : uint8_t {
  kAdjacency = 0,   // reading the vertex's adjacency row (its offset into the neighbour list)
  kCoordRead = 1,   // reading a vertex's coordinates
  kCoordWrite = 2,  // writing the moved vertex's coordinates (a ghost's, when a rank unpacks it)
  kNone = 3,        // an access to mesh data that is not a touch of a vertex record
  kFetch = 4,       // an instruction fetch (only in other tools' traces: lackey's I lines)
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
  // A distributed rank's ghost messages (halo_smoother.h), every link's in one array each:
  kSendIndex = 11,   // local ids of the owned vertices sent
  kSendBuffer = 12,  // their coordinates as sent
  kRecvIndex = 13,   // local ids of the ghosts received
  kRecvBuffer = 14,  // their coordinates as received
  // The FEM kernels (core/kernels/assembly.cc, spmv.cc): the P1 stiffness matrix in CSR form, the
  // per-triangle map to its entries, and the vectors of y = A x.
  kMatOffsets = 15,  // row offsets
  kMatColumns = 16,  // column ids
  kMatValues = 17,   // values
  kElementMap = 18,  // per triangle the 9 positions of its local matrix in `values`
  kVectorIn = 19,    // x
  kVectorOut = 20,   // y
  // The edge flips (core/kernels/edge_swap.cc): per triangle the triangle across each edge.
  kTriNeighbours = 21,
};
inline constexpr int kArrays = 22;

struct MemRef {
  const void* address;
  uint32_t size;  // bytes
  Array array;
  bool write;
  AccessKind element = AccessKind::kNone;
  int32_t vertex = -1;  // the vertex whose record is touched, when element != kNone
};

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
      // The bound's slots (64 B per thread) take the room of an array of their own.
      const uint64_t bytes = i == static_cast<int>(Array::kLoopBound)
                                 ? uint64_t{64} * static_cast<uint64_t>(kMaxThreads)
                                 : layout_.bytes[i];
      next = (next + bytes + 4095) / 4096 * 4096 + 4096;
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

// Each thread of a sweep's parallel region calls Enter(thread) before its share of the sweep and
// Exit(thread) after it: where hardware counters are read (analysis/papi_counters.h). Untraced
// runs only; the cost is two virtual calls per thread per sweep.
struct SweepRegion {
  virtual ~SweepRegion() = default;
  virtual void Enter(int thread) = 0;
  virtual void Exit(int thread) = 0;
};

inline const char* ArrayName(Array a) {
  static constexpr const char* kNames[kArrays] = {
      "interior", "v2v.off", "v2v.idx", "v2t.off",  "v2t.idx",  "tri",      "tq",       "w",
      "xy",       "xy.next", "bound",   "send.idx", "send.buf", "recv.idx", "recv.buf", "A.off",
      "A.col",    "A.val",   "e2a",     "x",        "y",        "t2t"};
  const int i = static_cast<int>(a);
  return i >= 0 && i < kArrays ? kNames[i] : "?";
}

}  // namespace meshreuse
