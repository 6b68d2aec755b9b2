// Where every runner's access streams come from (analyze, simulate, validate, the chunk runs): the
// inputs and how to stream them, held once (StreamSource: one check, one JSON), and the one input
// loop over them (ForEachStream). An input is
//   - a mesh (.node/.ele, .msh, .mrm): for each ordering, laid out (reports/inputs.h) and streamed
//     through the traced smoother, `iterations` exact sweeps on `threads` streams in `mode`; or,
//     with `ranks` > 0, each rank's part as the distributed smoother lays it out and sweeps it
//     (reports/rank_locality.h), one stream per rank;
//   - a meshreuse trace file (tracer/trace_reader.h), or another tool's trace (`format`, or text
//     when not a meshreuse trace), read by tracer/access_stream.h.
// A new analysis over every kind of input is then a StreamConsumer (libCacheSim's add/dump): it
// hands out the AccessConsumer of each stream and keeps what it made.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/kernels/kernel.h"
#include "core/mesh.h"
#include "core/orderings/registry.h"
#include "core/ranks/rank_part.h"
#include "core/smoother.h"
#include "reports/log.h"
#include "reports/run_info.h"
#include "tracer/access_stream.h"
#include "tracer/trace_formats.h"

namespace meshreuse {

struct StreamSource {
  std::vector<std::string> inputs;  // meshes, meshreuse traces, other tools' traces ("-": stdin)
  std::string format;               // "": meshes and meshreuse traces; else a TraceFormat name
  std::vector<OrderingSpec> orderings = {"ori"};  // for meshes, parsed once
  uint64_t seed = 1;                              // of seeded orderings (and of sampling)
  std::string kernel = kPaperKernel;              // for meshes: which sweep (core/kernels/)
  int iterations = 1;                             // for meshes: exact sweeps
  int threads = 1;                                // for meshes: the smoother's streams
  UpdateMode mode = UpdateMode::kGaussSeidel;
  TriangleOrder triangle_order = TriangleOrder::kSorted;
  // For meshes on several threads: how their streams are interleaved into one consumer
  // (SmoothOptions::interleave; the many-core simulator's turns).
  int interleave = kSerialShares;
  bool instructions = false;  // lackey: instruction fetches count too
  // Meshes: each of `ranks` parts as a rank of the distributed smoother (0: the whole mesh).
  int32_t ranks = 0;
  std::string partition = "hilbert";
  CutPlacement cut_placement = CutPlacement::kLast;
  // The mesh inputs[0] names, already read (the report reads each mesh once for many runs): laid
  // out from it, not read again. Not owned.
  const Mesh* loaded = nullptr;
  // Ids in memory for the input inputs[0] names (the Python module's numpy arrays): streamed as a
  // u64 trace of those values is (tracer/access_stream.h StreamIds), not read. Not owned. `poll`
  // is called between their batches (the module checks for Ctrl-C there).
  const uint64_t* ids = nullptr;
  uint64_t ids_count = 0;
  std::function<void()> poll;

  // UsageError for what cannot be streamed, before any work: no input, an unknown format or kernel
  // (or options it does not take: Jacobi, threads), no
  // ordering, sweeps or threads out of range, --instructions without lackey, --ranks with a trace
  // format or several threads, a partition method unknown.
  void Check() const;
  // What input `in` is: a mesh (loaded, or by its name), another tool's trace (ids in memory, or
  // any input under `format`), else a meshreuse trace (or text on standard input: ClassifyInput).
  InputKind KindOf(const std::string& in) const;
  // Whether input `in` is the ids in memory (ids, for inputs[0]).
  bool IdsOf(const std::string& in) const { return ids && !inputs.empty() && in == inputs[0]; }
  // `format` parsed (nullptr: meshes and meshreuse traces).
  const TraceFormat* Format() const;
  // The kernel named (checked by Check).
  const KernelInfo& Kernel() const { return ParseKernel(kernel); }
  // The smoother's options for a mesh: exactly `iterations` sweeps on `threads` streams.
  SmoothOptions Sweeps() const;
  // inputs, format, orderings, seed, ordering_seeds, kernel, iterations, threads, mode,
  // triangle_order (run.json's configuration; a runner adds its own fields).
  Json ToJson() const;
};

// One stream of the loop, as the consumer is asked for it.
struct StreamJob {
  std::string input;
  InputKind kind = InputKind::kMesh;       // kText: another tool's trace (`format`)
  const TraceFormat* format = nullptr;     // kText
  const OrderingSpec* ordering = nullptr;  // meshes
  int32_t rank = -1;                       // a rank's part (source.ranks > 0)
  const Mesh* mesh = nullptr;  // a whole mesh laid out, before the sweeps move it (Start only)
};

class StreamConsumer {
 public:
  virtual ~StreamConsumer() = default;
  // The progress lines' verb ("analysing", "simulating") and what follows a mesh's line (e.g. the
  // machine and placement).
  virtual std::string Verb() const = 0;
  virtual std::string Where() const { return ""; }
  // The consumer of the next stream, asked just before it starts.
  virtual AccessConsumer& Start(const StreamJob& job) = 0;
  // After the stream's last access (whole meshes and traces; a rank's part ends at the next Start).
  virtual void Finish(const StreamJob&) {}
  // A trace file this consumer reads in a way of its own (analyze's chunks on threads): true when
  // it did, and the loop goes on to the next input.
  virtual bool TakeTrace(const std::string&, const Log&) { return false; }
};

// Streams every input (each mesh in each ordering, or each rank's part) into the consumer, in the
// order of the inputs and orderings, with progress lines on `log`.
void ForEachStream(const StreamSource& source, StreamConsumer& consumer, const Log& log);

// Progress of reading a file, said as "VERB: 42% (1.2 s, about 1.6 s left)" at most every 2 s.
ProgressFn FileProgress(const Log& log, const std::string& verb = "analysing");

}  // namespace meshreuse
