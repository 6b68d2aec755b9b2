// The one way an input reaches an analysis. Three sources -- a mesh streamed through the traced
// smoother (no file), a meshreuse trace file, another tool's trace in one of the formats of
// trace_formats.h -- deliver the same thing to the same interface: a StreamInfo up front (threads,
// sweeps and their lengths where known), then the accesses in order, in batches, with BeginSweep
// between sweeps. The reuse analysis, the cache simulator and the trace writer are consumers
// (analysis/reuse_analysis.h, analysis/cache_sim.h, tracer/trace_writer.h), so each command is
// "pick a source, pick consumers" and no command dispatches on the input kind itself.
// Sources check what they deliver: a trace record naming a thread beyond its header's, a foreign
// value the analyzer reserves, are InputErrors naming the file and the record.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/kernels/kernel.h"
#include "core/mesh.h"
#include "core/ranks/halo_smoother.h"
#include "core/smoother.h"
#include "tracer/trace_formats.h"

namespace meshreuse {

// One access, whatever the input.
struct Access {
  static constexpr uint64_t kNoElement = std::numeric_limits<uint64_t>::max();
  uint64_t address;  // byte address (canonical for the smoother's streams, core/access.h)
  uint64_t element;  // the element touched: a vertex id, a foreign trace's value; or kNoElement
  uint32_t size;     // bytes (0 counts as 1)
  uint8_t thread;    // the stream
  uint8_t kind;      // AccessKind (kNone for accesses that touch no vertex record, and foreign)
  uint8_t array;     // Array; kForeignArray for other tools' traces
  bool write;
  static constexpr uint8_t kForeignArray = 0xff;
};

struct StreamInfo {
  std::string input;     // the mesh's or file's path, as given
  std::string ordering;  // the mesh's layout (a trace header's); "" for other tools' traces
  int threads = 1;       // streams, 1..kMaxThreads
  int64_t vertices = 0;  // element ids below this are dense (0: unknown)
  uint32_t element_bytes = 66;
  bool canonical = false;  // addresses are the smoother's canonical ones (line ids start near 0)
  uint64_t records = 0;    // accesses, 0: unknown
  // Per sweep, per thread: accesses, and the element touches among them. Empty: unknown (then
  // there is no profile). Other tools' traces of known length are one sweep.
  std::vector<std::vector<uint64_t>> sweep_records, sweep_elements;
  int sweeps() const { return static_cast<int>(sweep_records.size()); }
};

class AccessConsumer {
 public:
  virtual ~AccessConsumer() = default;
  virtual void Begin(const StreamInfo& info) = 0;
  virtual void BeginSweep(int /*sweep, 1-based*/) {}
  virtual void Consume(const Access* a, size_t n) = 0;  // the next n accesses, in order
  virtual void End() {}
};

// Sends everything to several consumers (the analysis and the simulator from one pass).
class FanOut : public AccessConsumer {
 public:
  explicit FanOut(std::vector<AccessConsumer*> to) : to_(std::move(to)) {}
  void Begin(const StreamInfo& i) override {
    for (AccessConsumer* c : to_) c->Begin(i);
  }
  void BeginSweep(int s) override {
    for (AccessConsumer* c : to_) c->BeginSweep(s);
  }
  void Consume(const Access* a, size_t n) override {
    for (AccessConsumer* c : to_) c->Consume(a, n);
  }
  void End() override {
    for (AccessConsumer* c : to_) c->End();
  }

 private:
  std::vector<AccessConsumer*> to_;
};

// Passes everything on to `to`, calling `told` with the StreamInfo first (a progress line that
// needs the stream's length, without asking a source to count it twice).
class Announced : public AccessConsumer {
 public:
  Announced(AccessConsumer& to, std::function<void(const StreamInfo&)> told)
      : to_(to), told_(std::move(told)) {}
  void Begin(const StreamInfo& i) override {
    told_(i);
    to_.Begin(i);
  }
  void BeginSweep(int s) override { to_.BeginSweep(s); }
  void Consume(const Access* a, size_t n) override { to_.Consume(a, n); }
  void End() override { to_.End(); }

 private:
  AccessConsumer& to_;
  std::function<void(const StreamInfo&)> told_;
};

using ProgressFn = std::function<void(double done_fraction)>;

// `sweeps` traced sweeps of `mesh` (laid out already; it is smoothed in place), each thread's
// stream as the static schedule gives it (core/smoother.h). `label`, `ordering`: for StreamInfo.
// `kernel`: another kernel of core/kernels/ than the Laplacian (nullptr: the smoother itself).
// Returns the kernel's result (each sweep's time is the traced sweep's, consumers included).
// `counts`: the StreamInfo announced carries the per-sweep counts (MeshStreamInfo: for another
// kernel a whole counting run first); false for consumers that read none of them (a cache
// simulation, line distances without profiles): then that run is not made and they are empty.
SmoothResult StreamMesh(Mesh& mesh, const SmoothOptions& sweeps, const std::string& label,
                        const std::string& ordering, AccessConsumer& to,
                        const KernelInfo* kernel = nullptr, bool counts = true);
// The info StreamMesh will announce (for memory checks before the work): for the Laplacian without
// running it; for the other kernels by a counting run on a copy of the mesh (traced runs are
// serial, so the counts are exact; a kernel's stream may depend on the values).
StreamInfo MeshStreamInfo(const Mesh& mesh, const SmoothOptions& sweeps,
                          const KernelInfo* kernel = nullptr);
// One rank's part of a distributed run (core/ranks/halo_smoother.h) smoothed by SmoothRankPart with
// `tx` as its transport: the rank's own loads and stores, its ghost messages' packs and unpacks
// included, as one stream (thread 0) of local ids. Returns the smoother's result.
HaloResult StreamRankPart(RankPart& part, const HaloOptions& opt, Communicator& tx,
                          const std::string& label, const std::string& ordering,
                          AccessConsumer& to);
// What StreamRankPart announces: opt.max_iters sweeps of TracedPerSweep's counts.
StreamInfo RankStreamInfo(const RankPart& part, const HaloOptions& opt);
// Records [first, end) of a trace file: a chunk (reports/chunks/summarize_chunk.h). The StreamInfo
// is still the whole file's (its sweeps place the chunk's accesses in the profile).
struct RecordRange {
  uint64_t first = 0, end = ~uint64_t{0};
};
// A meshreuse trace file (plain or zstd; a range needs a plain file).
void StreamTraceFile(const std::string& path, AccessConsumer& to, const ProgressFn& progress = {},
                     const RecordRange* range = nullptr);
// Another tool's trace: one stream; each value an access of its size (1 but for lackey); element
// ids are the values. Lackey's loads and stores keep their direction. A range: fixed-record
// formats only.
void StreamForeignTrace(const std::string& path, const TraceFormat& format, bool instructions,
                        AccessConsumer& to, const ProgressFn& progress = {},
                        const RecordRange* range = nullptr);

// Ids already in memory (the Python module's numpy arrays): one stream, each value an access of
// one byte, element and address alike -- exactly what StreamForeignTrace delivers for a u64 file of
// the same values (a range too: ids [first, end)), so every table equals `--format u64` on that
// file. The value 2^64-1 is refused (InputError naming `label` and the index). `poll`, when set,
// is called between batches of 2^16 ids (a caller's chance to stop the work: it may throw).
void StreamIds(const uint64_t* ids, uint64_t n, const std::string& label, AccessConsumer& to,
               const ProgressFn& progress = {}, const std::function<void()>& poll = {},
               const RecordRange* range = nullptr);
// What a path given without --format is: a mesh (by its name: .node, .ele, .msh, .mrm, or a
// prefix P with P.node), standard input ("-": a text trace of ids), or else a meshreuse trace.
enum class InputKind { kMesh, kTrace, kText };
InputKind ClassifyInput(const std::string& path);
// Among `inputs`, the meshreuse traces that are ranks of a `trace --ranks` set ("MESH [rank r of
// P, set TAG]" in their headers) must come from one run: two files naming the same mesh and P
// with different tags are refused (InputError naming the second), a set written over in part.
void CheckTraceSets(const std::vector<std::string>& inputs);

}  // namespace meshreuse
