// The three sources of access streams; see access_stream.h.
#include "tracer/access_stream.h"

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <map>

#include "core/error.h"
#include "core/input_file.h"
#include "core/mesh_file.h"
#include "core/schedule.h"
#include "tracer/foreign_trace.h"
#include "tracer/trace_reader.h"

namespace meshreuse {

namespace {

// A batch small enough to stay in L1 between the smoother writing it and the consumer's loop.
constexpr size_t kBatch = 512;

// The smoother's sink: canonical addresses, packed into batches for the consumer. With
// kAccessGrain (several threads) each turn's accesses wait in per-thread queues until EndTurn
// deals them out one at a time, thread after thread (smoother.h ForStatic).
struct BatchSink {
  static constexpr bool kEnabled = true;
  AccessConsumer& to;
  meshreuse::Access* buf;  // kBatch entries
  size_t n = 0;
  AddressCanonicalizer canon;
  int interleave = kSerialShares;
  std::vector<std::vector<meshreuse::Access>> queued;  // kAccessGrain: per thread, this turn's
  void Bind(const ArrayLayout& l) { canon = AddressCanonicalizer(l); }
  void Flush() {
    EndTurn();
    if (n) to.Consume(buf, n);
    n = 0;
  }
  void EndTurn() {
    size_t longest = 0;
    for (const auto& q : queued) longest = std::max(longest, q.size());
    for (size_t i = 0; i < longest; ++i)
      for (auto& q : queued)
        if (i < q.size()) Emit(q[i]);
    for (auto& q : queued) q.clear();
  }
  void Emit(const meshreuse::Access& a) {
    buf[n] = a;
    if (++n == kBatch) {
      to.Consume(buf, n);
      n = 0;
    }
  }
  void BeginSweep(int s) {
    Flush();
    to.BeginSweep(s);
  }
  void Access(int thread, const MemRef& r) {
    if (!queued.empty()) {
      meshreuse::Access a;
      Fill(&a, thread, r);
      queued[thread].push_back(a);
      return;
    }
    Fill(buf + n, thread, r);
    if (++n == kBatch) Flush();
  }
  void Fill(meshreuse::Access* out, int thread, const MemRef& r) {
    meshreuse::Access& a = *out;
    a.address = canon(thread, r);
    // kNone's vertex is -1: as uint64 sign-extended, exactly Access::kNoElement.
    a.element = static_cast<uint64_t>(static_cast<int64_t>(r.vertex));
    a.size = r.size;
    a.thread = static_cast<uint8_t>(thread);
    a.kind = static_cast<uint8_t>(r.element);
    a.array = static_cast<uint8_t>(r.array);
    a.write = r.write;
  }
};
static_assert(static_cast<uint64_t>(int64_t{-1}) == meshreuse::Access::kNoElement,
              "a vertex of -1 (no element) must map to kNoElement");

}  // namespace

namespace {

// The BatchSink behind the kernels' one sink interface.
struct KernelBatchSink : KernelSink {
  explicit KernelBatchSink(BatchSink& b) : to(b) { interleave = b.interleave; }
  BatchSink& to;
  void Bind(const ArrayLayout& l) override { to.Bind(l); }
  void BeginSweep(int s) override { to.BeginSweep(s); }
  void Access(int thread, const MemRef& r) override { to.Access(thread, r); }
  void EndTurn() override { to.EndTurn(); }
};

// Accesses and element touches per sweep and thread.
struct SweepCounter : KernelSink {
  explicit SweepCounter(int t) : threads(t) {}
  int threads;
  std::vector<std::vector<uint64_t>> refs, elements;
  void Bind(const ArrayLayout&) override {}
  void BeginSweep(int) override {
    refs.emplace_back(threads, 0);
    elements.emplace_back(threads, 0);
  }
  void Access(int thread, const MemRef& r) override {
    ++refs.back()[thread];
    if (r.element != AccessKind::kNone) ++elements.back()[thread];
  }
};

bool IsLaplacian(const KernelInfo* k) { return !k || IsPaperSweep(*k); }

// What every mesh stream announces; the per-sweep counts are MeshStreamInfo's.
StreamInfo BareStreamInfo(const Mesh& mesh, const SmoothOptions& sweeps) {
  StreamInfo info;
  info.threads = std::max(1, sweeps.threads);
  info.vertices = mesh.NumVertices();
  info.canonical = true;
  return info;
}

}  // namespace

StreamInfo MeshStreamInfo(const Mesh& mesh, const SmoothOptions& sweeps, const KernelInfo* kernel) {
  StreamInfo info = BareStreamInfo(mesh, sweeps);
  if (!IsLaplacian(kernel)) {
    // Counted, the element touches too; KernelInfo::refs, where a kernel has it, is the closed form
    // its tests check against this.
    Mesh copy = mesh.Clone();
    SweepCounter count(info.threads);
    kernel->traced(copy, sweeps, count);
    info.sweep_records = count.refs;
    info.sweep_elements = count.elements;
    for (const auto& sweep : info.sweep_records)
      for (uint64_t n : sweep) info.records += n;
    return info;
  }
  const std::vector<uint64_t> refs = RefsPerSweep(mesh, info.threads, sweeps.mode);
  info.sweep_records.assign(sweeps.max_iters, refs);
  for (uint64_t n : refs) info.records += n * static_cast<uint64_t>(sweeps.max_iters);
  // Element touches per sweep are known in closed form for Gauss-Seidel (AccessesPerSweep).
  if (sweeps.mode == UpdateMode::kGaussSeidel)
    info.sweep_elements.assign(sweeps.max_iters, AccessesPerSweep(mesh, info.threads));
  return info;
}

SmoothResult StreamMesh(Mesh& mesh, const SmoothOptions& sweeps, const std::string& label,
                        const std::string& ordering, AccessConsumer& to, const KernelInfo* kernel,
                        bool counts) {
  // The Laplacian's counts are in closed form: no reason to leave them out.
  StreamInfo info = counts || IsLaplacian(kernel) ? MeshStreamInfo(mesh, sweeps, kernel)
                                                  : BareStreamInfo(mesh, sweeps);
  info.input = label;
  info.ordering = ordering;
  to.Begin(info);
  std::vector<Access> buf(kBatch);
  BatchSink sink{to, buf.data(), 0, {}, sweeps.interleave, {}};
  if (sweeps.interleave == kAccessGrain && info.threads > 1) sink.queued.resize(info.threads);
  SmoothResult r;
  if (IsLaplacian(kernel)) {
    r = Smooth(mesh, sweeps, sink);
  } else {
    KernelBatchSink ks(sink);
    r = kernel->traced(mesh, sweeps, ks);
  }
  sink.Flush();
  to.End();
  return r;
}

StreamInfo RankStreamInfo(const RankPart& part, const HaloOptions& opt) {
  StreamInfo info;
  info.vertices = part.total;
  info.canonical = true;
  const HaloSweepCounts c = TracedPerSweep(part);
  const int sweeps = std::max(0, opt.max_iters);
  info.sweep_records.assign(sweeps, {c.refs});
  info.sweep_elements.assign(sweeps, {c.elements});
  info.records = c.refs * static_cast<uint64_t>(sweeps);
  return info;
}

HaloResult StreamRankPart(RankPart& part, const HaloOptions& opt, Communicator& tx,
                          const std::string& label, const std::string& ordering,
                          AccessConsumer& to) {
  StreamInfo info = RankStreamInfo(part, opt);
  info.input = label;
  info.ordering = ordering;
  to.Begin(info);
  std::vector<Access> buf(kBatch);
  BatchSink sink{to, buf.data(), 0, {}, kSerialShares, {}};
  HaloResult r = SmoothRankPart(part, opt, tx, sink);
  sink.Flush();
  to.End();
  return r;
}

void StreamTraceFile(const std::string& path, AccessConsumer& to, const ProgressFn& progress,
                     const RecordRange* range) {
  TraceReader r(path);
  const TraceHeader& h = r.header();
  StreamInfo info;
  info.input = path;
  info.ordering = h.ordering;
  info.threads = static_cast<int>(h.threads);
  // Direct arrays for ids below the vertex count, never more than the records: a header's count
  // cannot make memory exceed what the file holds.
  // A stream of unknown size has not proved its record count yet: a smaller direct array then.
  info.vertices = static_cast<int64_t>(
      std::min<uint64_t>({h.vertices, h.records, r.sized() ? ~uint64_t{0} : uint64_t{1} << 20}));
  info.element_bytes = h.element_bytes;
  info.canonical = true;
  info.records = h.records;
  info.sweep_records = h.sweep_records;
  info.sweep_elements = h.sweep_elements;
  to.Begin(info);
  std::vector<TraceRecord> batch;
  std::vector<Access> out;
  out.reserve(kBatch);
  uint64_t seen = 0, first = 0, end = h.records;
  size_t next_sweep = 0;
  if (range) {
    first = range->first, end = std::min(range->end, h.records);
    r.Range(first, end);
    seen = first;
    while (next_sweep < h.iteration_starts.size() && h.iteration_starts[next_sweep] < first)
      ++next_sweep;
  }
  while (r.Next(&batch, kBatch)) {
    out.clear();
    for (const TraceRecord& rec : batch) {
      while (next_sweep < h.iteration_starts.size() && h.iteration_starts[next_sweep] == seen) {
        if (!out.empty()) to.Consume(out.data(), out.size());
        out.clear();
        to.BeginSweep(static_cast<int>(++next_sweep));
      }
      out.push_back({rec.address,
                     rec.kind < kElementKinds ? uint64_t{rec.vertex} : Access::kNoElement, rec.size,
                     rec.thread, rec.kind, static_cast<uint8_t>(rec.array & ~kStoreBit),
                     (rec.array & kStoreBit) != 0});
      ++seen;
    }
    if (!out.empty()) to.Consume(out.data(), out.size());
    if (progress && end > first)
      progress(static_cast<double>(seen - first) / static_cast<double>(end - first));
  }
  to.End();
}

void StreamForeignTrace(const std::string& path, const TraceFormat& format, bool instructions,
                        AccessConsumer& to, const ProgressFn& progress, const RecordRange* range) {
  StreamInfo info;
  info.input = path;
  info.threads = 1;
  info.records = ForeignTraceLength(path, format);
  if (info.records) info.sweep_records = info.sweep_elements = {{info.records}};
  to.Begin(info);
  std::vector<Access> out;
  out.reserve(kBatch);
  uint64_t seen = 0;
  const uint64_t first = range ? range->first : 0, end = range ? range->end : ~uint64_t{0};
  // Accesses to come, when known (a text chunk's range is in bytes: unknown).
  const uint64_t todo = !range                                        ? info.records
                        : format.syntax == TraceSyntax::kFixedRecords ? end - first
                                                                      : 0;
  ReadForeignTrace(
      path, format,
      [&](uint64_t v, uint32_t size, bool write, bool fetch) {
        out.push_back({v, v, size, 0,
                       static_cast<uint8_t>(fetch ? AccessKind::kFetch : AccessKind::kNone),
                       Access::kForeignArray, write});
        if (out.size() == kBatch) {
          to.Consume(out.data(), out.size());
          out.clear();
          seen += kBatch;
          if (progress && (seen & 0xFFFFF) == 0)
            progress(todo ? static_cast<double>(seen) / static_cast<double>(todo) : -1.0);
        }
      },
      instructions, first, end);
  if (!out.empty()) to.Consume(out.data(), out.size());
  to.End();
}

void StreamIds(const uint64_t* ids, uint64_t n, const std::string& label, AccessConsumer& to,
               const ProgressFn& progress, const std::function<void()>& poll,
               const RecordRange* range) {
  StreamInfo info;
  info.input = label;
  info.threads = 1;
  info.records = n;
  if (n) info.sweep_records = info.sweep_elements = {{n}};
  to.Begin(info);
  std::vector<Access> out(kBatch);
  const uint64_t last = range ? std::min(n, range->end) : n;
  for (uint64_t at = range ? std::min(n, range->first) : 0; at < last;) {
    const uint64_t end = std::min(last, at + (uint64_t{1} << 16));
    for (; at < end;) {
      const size_t k = static_cast<size_t>(std::min<uint64_t>(kBatch, end - at));
      for (size_t i = 0; i < k; ++i) {
        const uint64_t v = ids[at + i];
        if (v == foreign_detail::kReserved)
          throw InputError(label, 0,
                           "value " + std::to_string(at + i) +
                               " is 2^64-1, which is reserved: ids and addresses must be below it");
        out[i] = {v,    v, 1, 0, static_cast<uint8_t>(AccessKind::kNone), Access::kForeignArray,
                  false};
      }
      to.Consume(out.data(), k);
      at += k;
    }
    if (progress && (at & 0xFFFFF) == 0)
      progress(static_cast<double>(at) / static_cast<double>(last));
    if (poll) poll();
  }
  to.End();
}

InputKind ClassifyInput(const std::string& path) {
  auto ends = [&](const std::string& x) {
    return path.size() >= x.size() && path.compare(path.size() - x.size(), x.size(), x) == 0;
  };
  if (path != "-" && (ends(".node") || ends(".ele") || ends(".msh") || IsMeshFilePath(path) ||
                      ::access((path + ".node").c_str(), F_OK) == 0))
    return InputKind::kMesh;
  // Anything else given by name is read as a meshreuse trace, whose reader says "not a meshreuse
  // trace ... use --format" when the magic is wrong. Standard input is looked at: our trace's
  // magic makes it one (the bytes are given back), anything else is a text trace.
  if (path != "-") return InputKind::kTrace;
  std::string& back = StdinPushback();
  char magic[8];
  size_t got = 0;
  while (back.size() + got < sizeof magic) {
    const size_t n = std::fread(magic + got, 1, sizeof magic - back.size() - got, stdin);
    if (n == 0) break;
    got += n;
  }
  back.append(magic, got);
  return back.size() == sizeof magic && std::memcmp(back.data(), kTraceMagic, 8) == 0
             ? InputKind::kTrace
             : InputKind::kText;
}

void CheckTraceSets(const std::vector<std::string>& inputs) {
  std::map<std::string, std::pair<std::string, std::string>> seen;  // mesh and P -> (tag, file)
  for (const std::string& in : inputs) {
    if (in == "-" || ClassifyInput(in) != InputKind::kTrace) continue;
    std::string label;
    try {
      label = TraceReader(in).header().mesh;
    } catch (const std::exception&) {
      continue;  // the analysis reports it
    }
    const size_t at = label.rfind(" [rank ");
    const size_t set = label.rfind(", set ");
    if (at == std::string::npos || set == std::string::npos || set < at || label.back() != ']')
      continue;
    const size_t of = label.find(" of ", at);
    if (of == std::string::npos || of > set) continue;
    const std::string key = label.substr(0, at) + label.substr(of, set - of);
    const std::string tag = label.substr(set + 6, label.size() - set - 7);
    const auto [it, fresh] = seen.emplace(key, std::make_pair(tag, in));
    if (!fresh && it->second.first != tag)
      throw InputError(in, 0,
                       "a rank of another `trace --ranks` run than " + it->second.second +
                           " (set " + tag + ", not " + it->second.first +
                           "): write the set again, all ranks at once");
  }
}

}  // namespace meshreuse
