// Mesh kernels beyond the paper's Laplacian sweep (issue 41: the paper's closing conjecture that a
// locality-aware ordering helps "mesh untangling, constraint mesh smoothing, and mesh swapping"):
// the registry every command finds them in, the way core/orderings/registry.h holds orderings. One
// file per kernel under core/kernels/ (its definition, its reference and its documented access
// sequence at its head), one line in core/kernels/list.h.
// A kernel is a sweep over the mesh with its own visit unit (vertex, triangle, matrix row) and
// per-visit work, written once as a template on the access sink exactly as the smoother is: the
// NullSink instance is the timed loop (the sink compiles away; tests/bench proves the cost per
// kernel), the KernelSink instance streams every load and store of the sweep, in program order.
// Every kernel runs under SmoothOptions (max_iters, tol, threads, region, flush) and answers a
// SmoothResult whose per-sweep `quality` is the kernel's own measure (KernelInfo::measure), larger
// being better, and the stop rule is the smoother's: a sweep that improves it by less than tol is
// the last (fixed-work kernels, whose measure does not change, run exactly max_iters sweeps).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/access.h"
#include "core/mesh.h"
#include "core/smoother.h"

namespace meshreuse {

// A sink the kernels are compiled for once, whatever records behind it (the tracer's batches, a
// test's counter): one virtual call per access, on traced runs only. Its `interleave` is read as
// the smoother reads a sink's (SmoothOptions::interleave), EndTurn when it deals accesses.
struct KernelSink {
  static constexpr bool kEnabled = true;
  int interleave = kSerialShares;
  virtual ~KernelSink() = default;
  virtual void Bind(const ArrayLayout& layout) = 0;
  virtual void BeginSweep(int sweep) = 0;
  virtual void Access(int thread, const MemRef& r) = 0;
  virtual void EndTurn() {}
};

// Any sink (CountingSink, RecordingSink, ...) behind the KernelSink interface.
template <class S>
struct KernelSinkOf : KernelSink {
  explicit KernelSinkOf(S& s) : to(s) {}
  S& to;
  void Bind(const ArrayLayout& l) override { to.Bind(l); }
  void BeginSweep(int s) override { to.BeginSweep(s); }
  void Access(int thread, const MemRef& r) override { to.Access(thread, r); }
};

enum class VisitUnit { kVertex, kEdge, kTriangle, kRow };
const char* VisitUnitName(VisitUnit u);

// A kernel's untimed set-up that runs on the same input can share (edge-swap's jittered
// coordinates and triangle neighbours, assembly's and spmv's stiffness pattern): made once from a
// mesh, handed to each run through SmoothOptions::setup, which then starts from a copy of it
// instead of making it (the same sweeps, bit for bit). On lake (375k vertices) edge-swap's, made
// in each of its 19 timed runs, took 1.33 s of the report's 10.4-s timed kernels part (timers
// around each step); the timed rounds run each ordering's layout three times.
struct KernelSetup {
  virtual ~KernelSetup() = default;
  virtual uint64_t Bytes() const = 0;  // the memory it holds (a caller keeping many budgets it)
};
using KernelSetupFn = std::unique_ptr<KernelSetup> (*)(const Mesh&);  // nullptr: none to share

using KernelTimedFn = SmoothResult (*)(Mesh&, const SmoothOptions&);
using KernelTracedFn = SmoothResult (*)(Mesh&, const SmoothOptions&, KernelSink&);
// Loads and stores per sweep, per thread of the static schedule, when they do not depend on the
// values (empty: they do, e.g. a move kept or not).
using KernelRefsFn = std::vector<uint64_t> (*)(const Mesh&, const SmoothOptions&);

struct KernelInfo {
  const char* name;
  KernelTimedFn timed;
  KernelTracedFn traced;
  KernelRefsFn refs;
  VisitUnit unit;
  bool jacobi;           // takes --mode jacobi (else Gauss-Seidel only)
  bool threads;          // has a parallel form (else --threads 1 only)
  bool moves;            // moves vertices (smooth writes the moved mesh)
  bool fixed;            // fixed work per sweep: the measure does not change, max_iters sweeps run
  const char* measure;   // what SweepRecord::quality holds
  const char* parallel;  // how its threads split the work, or why it has none
  const char* description;  // one line
  const char* reference;
  KernelSetupFn setup;  // see KernelSetup
};

// The paper's sweep (core/smoother.h itself), every command's default: the one kernel with a
// distributed form (--ranks), a visit order (--visit-order) and a stream that is a closed form of
// the mesh (so a chunk of it can start mid-stream).
inline constexpr const char* kPaperKernel = "laplacian";
bool IsPaperSweep(const KernelInfo& k);

const std::vector<KernelInfo>& Kernels();
const KernelInfo* FindKernel(const std::string& name);  // nullptr when unknown
std::string KernelNames();                              // "laplacian, smart-laplacian, ..."
// The registered kernel `name` (UsageError naming the known ones otherwise).
const KernelInfo& ParseKernel(const std::string& name);
// UsageError when the options ask for what the kernel does not do (Jacobi, threads).
void CheckKernelOptions(const KernelInfo& k, const SmoothOptions& o);
// The kernel's set-up for runs on `m` (SmoothOptions::setup); nullptr where it has none to share.
inline std::unique_ptr<KernelSetup> PrepareKernel(const KernelInfo& k, const Mesh& m) {
  return k.setup(m);
}
// The kernel's sweeps, untraced (timed) or into `sink`.
inline SmoothResult RunKernel(const KernelInfo& k, Mesh& m, const SmoothOptions& o) {
  return k.timed(m, o);
}
inline SmoothResult RunKernel(const KernelInfo& k, Mesh& m, const SmoothOptions& o,
                              KernelSink& sink) {
  return k.traced(m, o, sink);
}

// Defines the registry's entry points of a kernel template `fn<Sink>(Mesh&, const
// SmoothOptions&, Sink&)` in its own file: fn##Timed (NullSink), fn##Traced (KernelSink) and
// fn##Setup (none). A kernel with a set-up to share uses MESHREUSE_KERNEL_ENTRIES_WITH_SETUP and
// defines `std::unique_ptr<KernelSetup> fn##Setup(const Mesh&)` itself.
#define MESHREUSE_KERNEL_ENTRIES_WITH_SETUP(fn)             \
  SmoothResult fn##Timed(Mesh& m, const SmoothOptions& o) { \
    NullSink s;                                             \
    return fn(m, o, s);                                     \
  }                                                         \
  SmoothResult fn##Traced(Mesh& m, const SmoothOptions& o, KernelSink& s) { return fn(m, o, s); }
#define MESHREUSE_KERNEL_ENTRIES(fn)      \
  MESHREUSE_KERNEL_ENTRIES_WITH_SETUP(fn) \
  std::unique_ptr<KernelSetup> fn##Setup(const Mesh&) { return nullptr; }

}  // namespace meshreuse
