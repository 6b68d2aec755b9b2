// One chunk of a reuse analysis into its summary; see summarize_chunk.h.
#include "reports/chunks/summarize_chunk.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/access.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/kernels/kernel.h"
#include "core/mix.h"
#include "core/smoother.h"
#include "reports/inputs.h"
#include "tracer/input_stream.h"
#include "tracer/trace_formats.h"
#include "tracer/trace_reader.h"

namespace meshreuse {

namespace {

// What ties summaries to one trace file (a copy elsewhere, under another name, is the same trace):
// its size and a hash of its bytes. For summary files (`whole`) every byte of a file up to
// kWholeBytes (its chunks then merge only with chunks of the same bytes); beyond, the first and
// last 64 KiB and 4 KiB at every MiB (an edit that touches none of those blocks goes unseen: the
// limit, said in reports/docs/distributed-analysis.md). The ranks of a distributed
// run read one file by construction: for them the ends alone.
constexpr uint64_t kWholeBytes = uint64_t{256} << 20;

uint64_t Fingerprint(const std::string& path, bool whole, uint64_t* bytes) {
  InputFile f(path);
  if (f.size() < 0) throw InputError(path, 0, "a chunk needs a regular file (not a pipe)");
  *bytes = static_cast<uint64_t>(f.size());
  auto at = [&](uint64_t offset, uint64_t n) {  // the hash of bytes [offset, offset + n)
    if (fseeko(f.get(), static_cast<off_t>(offset), SEEK_SET) != 0)
      throw InputError(path, 0, "cannot seek");
    std::vector<char> b(std::min<uint64_t>(n, 1 << 20));
    SummaryHasher h(n);
    for (uint64_t done = 0; done < n;) {
      const size_t got = f.Read(b.data(), std::min<uint64_t>(b.size(), n - done));
      if (got == 0) throw InputError(path, 0, "the file changed while it was read");
      h.Add(b.data(), got);
      done += got;
    }
    return h.Finish();
  };
  if (whole && *bytes <= kWholeBytes) return at(0, *bytes);
  const uint64_t end = std::min<uint64_t>(*bytes, 1 << 16);
  uint64_t h = at(0, end);
  if (*bytes > end) h = Mix64(h ^ at(*bytes - end, end));
  if (whole)
    for (uint64_t o = uint64_t{1} << 20; o + 4096 <= *bytes; o += uint64_t{1} << 20)
      h = Mix64(h ^ at(o, 4096)) + o;
  return h;
}

// A laid-out mesh's content hash (coordinates and triangles) and its size in bytes: ties the
// chunks of one mesh analysis together whatever file or copy each run read.
uint64_t MeshFingerprint(const Mesh& m, uint64_t* bytes) {
  const size_t xy = m.xy.size() * sizeof(double), tri = m.tri.size() * sizeof(int32_t);
  *bytes = xy + tri;
  return Mix64(SummaryChecksum(reinterpret_cast<const char*>(m.xy.data()), xy) ^
               SummaryChecksum(reinterpret_cast<const char*>(m.tri.data()), tri) * 3);
}

}  // namespace

std::pair<uint32_t, uint32_t> ParseChunk(const std::string& s) {
  const size_t slash = s.find('/');
  auto num = [&](const std::string& x) -> uint64_t {
    if (x.empty() || x.size() > 9 || x.find_first_not_of("0123456789") != std::string::npos)
      throw UsageError("--chunk '" + s + "': expected r/P with 0 <= r < P (e.g. 3/8)");
    return std::stoull(x);
  };
  if (slash == std::string::npos)
    throw UsageError("--chunk '" + s + "': expected r/P with 0 <= r < P (e.g. 3/8)");
  const uint64_t r = num(s.substr(0, slash)), p = num(s.substr(slash + 1));
  if (p < 1 || p > (1u << 20) || r >= p)
    throw UsageError("--chunk '" + s + "': expected 0 <= r < P <= 1048576");
  return {static_cast<uint32_t>(r), static_cast<uint32_t>(p)};
}

namespace {

// Where records [0, first) leave each thread's element and line streams: whole sweeps from the
// header's tables, the sweep the chunk starts in by reading it up to `first`. Lines assume that no
// access before that sweep straddles two lines (the merge checks).
void TraceOffsets(const std::string& path, uint64_t first, uint32_t line_bytes,
                  std::vector<uint64_t>* element, std::vector<uint64_t>* line) {
  TraceReader r(path);
  const TraceHeader& h = r.header();
  element->assign(h.threads, 0);
  line->assign(h.threads, 0);
  uint64_t from = 0;
  for (size_t i = 0; i < h.iteration_starts.size() && h.iteration_starts[i] <= first; ++i) {
    if (i > 0)
      for (uint32_t t = 0; t < h.threads; ++t)
        (*element)[t] += h.sweep_elements[i - 1][t], (*line)[t] += h.sweep_records[i - 1][t];
    from = h.iteration_starts[i];
  }
  if (from == first) return;
  r.Range(from, first);
  const int shift = __builtin_ctz(line_bytes);
  std::vector<TraceRecord> batch;
  while (r.Next(&batch)) {
    for (const TraceRecord& rec : batch) {
      if (rec.kind < kElementKinds) ++(*element)[rec.thread];
      const uint64_t a = rec.address, b = a + (rec.size ? rec.size - 1 : 0);
      (*line)[rec.thread] += (a >> shift) == (b >> shift) ? 1 : 2;
    }
  }
}

}  // namespace

// What every summary of one analysis shares besides the input: the analysis' options.
void SetAnalysis(const ReuseJob& cfg, Granularity g, SummaryFile* s) {
  s->id.granularity = static_cast<uint32_t>(g);
  s->id.line_bytes = cfg.line_bytes;
  s->id.exact = !cfg.sample || cfg.sample_error;
  s->id.sample = cfg.sample;
  s->id.rate = cfg.sample ? cfg.shards.rate : 0;
  s->id.seed = cfg.sample ? cfg.shards.seed : 0;
}

MeshChunkSweeps SweepsOfMeshChunk(const StreamInfo& whole, UpdateMode mode, uint64_t first,
                                  uint64_t end) {
  MeshChunkSweeps run;
  if (first >= end || whole.sweep_records.empty()) return run;  // nothing to regenerate
  uint64_t per_sweep = 0;
  for (uint64_t n : whole.sweep_records[0]) per_sweep += n;
  if (per_sweep == 0) return run;
  run.from = static_cast<int>(first / per_sweep) + 1;
  run.to = static_cast<int>((end - 1) / per_sweep) + 1;
  if (mode == UpdateMode::kJacobi && run.from % 2 == 0) --run.from;
  run.skipped = static_cast<uint64_t>(run.from - 1) * per_sweep;
  return run;
}

// Chunk r of P of `total` records (or bytes): [total r / P, total (r + 1) / P).
void Cut(uint64_t total, uint32_t r, uint32_t p, SummaryFile* s) {
  using U = unsigned __int128;
  s->first = static_cast<uint64_t>(U{total} * r / p);
  s->end = static_cast<uint64_t>(U{total} * (r + 1) / p);
  s->total = total;
}

ReuseOptions ChunkOptions(const ReuseJob& cfg, const SummaryFile& s, bool distributed) {
  ReuseOptions o;
  o.granularity = static_cast<Granularity>(s.id.granularity);
  o.line_bytes = cfg.line_bytes;
  // A summary file holds a profile and the first touches' places whatever this run writes (its
  // merge may write a profile); a distributed run computes them only for a profile it writes.
  o.profile = cfg.profile || !distributed;
  o.chunk = true;
  o.chunk_positions = !distributed;
  o.exact = s.id.exact;
  o.sample = s.id.sample;
  o.shards = cfg.shards;
  return o;
}

// The chunk's summary entries from its analysis (the exact chunk and the sampled ids' chunk of
// each stream); the first touches are moved out of the analysis, not copied. The last chunk of a
// distributed run passes its stack to no one: `stack` false leaves it out.
void Collect(ReuseAnalysis& a, SummaryFile* out, bool stack) {
  SummaryFile& s = *out;
  s.info = a.info();
  s.info.input.clear();
  for (int t = 0; t < a.threads(); ++t) {
    s.moves.push_back(a.moves(t));
    for (Granularity sg : {Granularity::kElement, Granularity::kLine}) {
      if (!a.stream(t, sg)) continue;
      StreamAnalysis* x = &a.MakeStream(t, sg);  // the same stream: its lists are moved out
      const uint64_t stream_accesses = x->exact ? x->sd.accesses() : x->added;
      // The exact chunk, and the sampled ids' chunk: one entry each.
      for (StreamAnalysis* y : {x->exact ? x : nullptr, x->sampled_chunk.get()}) {
        if (!y) continue;
        StreamSummary ss;
        ss.thread = static_cast<uint32_t>(t);
        ss.granularity = sg;
        ss.sampled = y != x;
        ss.accesses = y->sd.accesses();
        ss.stream_accesses = stream_accesses;
        ss.offset = ss.sampled ? 0 : x->offset;
        ss.chunk.first_ids = std::move(y->first_ids);
        ss.chunk.first_positions = std::move(y->first_positions);
        if (stack) ss.chunk.stack = y->sd.StackBottomUp();
        y->sd = StackDistance();  // its memory, free for what follows
        size_t pairs = 0;  // counted first: 16 MB of pairs at 10^6 distances, grown, touched 32
        y->hist.ForEach([&pairs](uint64_t, uint64_t) { ++pairs; });
        ss.hist.reserve(pairs);
        y->hist.ForEach([&](uint64_t d, uint64_t n) { ss.hist.emplace_back(d, n); });
        const auto& steps = y->profile.steps();
        for (size_t i = 0; i < steps.size(); ++i)
          if (steps[i].accesses)
            ss.profile.push_back({i, steps[i].accesses, steps[i].cold, steps[i].sum});
        s.streams.push_back(std::move(ss));
      }
    }
  }
}

// Passes records [first, end) of a stream on to `to`, counting where the records before them
// leave each thread's element and line streams (the chunk's profile offsets, set on `to` before
// its first access). The stream fed to it may begin after record 0: `skipped` records, which left
// the streams at `element` and `line`, come before it. `to` begins with `whole`, the info of the
// stream from record 0. Records after `end` are dropped (the smoother finishes its last sweep).
class RangeGate : public AccessConsumer {
 public:
  RangeGate(ReuseAnalysis& to, const StreamInfo& whole, uint64_t first, uint64_t end,
            uint32_t line_bytes, uint64_t skipped, std::vector<uint64_t> element,
            std::vector<uint64_t> line)
      : to_(to),
        whole_(whole),
        first_(first),
        end_(end),
        seen_(skipped),
        shift_(__builtin_ctz(line_bytes)),
        element_(std::move(element)),
        line_(std::move(line)) {}
  void Begin(const StreamInfo&) override {
    to_.Begin(whole_);
    element_.resize(whole_.threads, 0);
    line_.resize(whole_.threads, 0);
  }
  void Consume(const Access* a, size_t n) override {
    size_t i = 0;
    for (; i < n && seen_ + i < first_; ++i) {
      const Access& x = a[i];
      if (x.element != Access::kNoElement) ++element_[x.thread];
      const uint64_t b = x.address + (x.size ? x.size - 1 : 0);
      line_[x.thread] += (x.address >> shift_) == (b >> shift_) ? 1 : 2;
    }
    if (i < n && seen_ + i < end_) {
      if (!started_) to_.SetStreamOffsets(element_, line_), started_ = true;
      const size_t k = static_cast<size_t>(std::min<uint64_t>(n, end_ - seen_));
      to_.Consume(a + i, k - i);
    }
    seen_ += n;
  }

 private:
  ReuseAnalysis& to_;
  const StreamInfo& whole_;
  uint64_t first_, end_, seen_;
  int shift_;
  bool started_ = false;
  std::vector<uint64_t> element_, line_;
};

// A chunk of the access stream of a mesh smoothed in the analysis' order: records [N r/P,
// N (r+1)/P) of what `meshreuse trace MESH` would write, regenerated without a file (the stream
// depends on topology and canonical addresses only). Every sweep makes the same accesses, but for
// Jacobi's two buffers, which alternate (sweep s touches what sweep s - 2 touched): so the rank
// runs the traced smoother from the sweep its range starts in (one earlier for an even Jacobi
// sweep) to the one it ends in, at most one sweep more than its range, and counts the sweeps
// before by their closed forms (AccessesPerSweep; one line per access, since no access of the
// smoother straddles two lines: the merge checks each chunk's offset).
SummaryFile SummarizeMeshChunk(const ReuseJob& cfg, uint32_t r, uint32_t p, bool distributed,
                               const Log& log) {
  const std::string& in = cfg.inputs[0];
  const OrderingSpec& ord = cfg.orderings[0];
  // The Laplacian's stream is a closed form of the mesh (the chunk starts at its sweep); another
  // kernel's may depend on the values (a move kept or not), so a chunk cannot start mid-stream.
  if (!IsPaperSweep(ParseKernel(cfg.kernel)))
    throw UsageError(
        "a chunk of a mesh's stream regenerates the Laplacian's sweeps from their "
        "closed form: for --kernel " +
        cfg.kernel + ", write its trace (meshreuse trace --kernel " + cfg.kernel +
        ") and analyse the file in chunks");
  Mesh m = LayOut(in, ord, cfg.seed, cfg.triangle_order, log);
  const SmoothOptions sweeps = cfg.Sweeps();
  SummaryFile s;
  s.input = in;
  s.chunk = r;
  s.id.chunks = p;
  s.id.format = "mesh " + ord.label + " seed " + std::to_string(cfg.seed) + " sweeps " +
                std::to_string(cfg.iterations) + " threads " + std::to_string(cfg.threads) + " " +
                UpdateModeName(cfg.mode) + " " + TriangleOrderName(cfg.triangle_order);
  s.id.fingerprint = MeshFingerprint(m, &s.id.input_bytes);
  SetAnalysis(cfg, cfg.granularity ? *cfg.granularity : Granularity::kBoth, &s);
  StreamInfo whole = MeshStreamInfo(m, sweeps);
  whole.input = in;
  whole.ordering = ord.label;
  const uint64_t total = whole.records;
  Cut(total, r, p, &s);
  const MeshChunkSweeps run = SweepsOfMeshChunk(whole, sweeps.mode, s.first, s.end);
  const std::vector<uint64_t> elements = AccessesPerSweep(m, whole.threads, sweeps.mode);
  std::vector<uint64_t> element_before(whole.threads), line_before(whole.threads);
  const uint64_t before = static_cast<uint64_t>(run.from - 1);
  for (int t = 0; t < whole.threads && before > 0; ++t)
    element_before[t] = before * elements[t], line_before[t] = before * whole.sweep_records[0][t];
  ReuseAnalysis a(ChunkOptions(cfg, s, distributed));
  RangeGate gate(a, whole, s.first, s.end, cfg.line_bytes, run.skipped, element_before,
                 line_before);
  log.Say("analysing chunk " + ChunkName(r, p) + " of " + in + " in " + ord.text +
          " order: records " + std::to_string(s.first) + ".." + std::to_string(s.end) + " of " +
          std::to_string(total) + " (regenerated by the traced smoother, sweeps " +
          std::to_string(run.from) + ".." + std::to_string(run.to) + " of " +
          std::to_string(sweeps.max_iters) + ")");
  SmoothOptions part = sweeps;
  part.max_iters = run.to - run.from + 1;
  StreamMesh(m, part, in, whole.ordering, gate);
  a.End();
  Collect(a, &s, !(distributed && r + 1 == p));
  return s;
}

SummaryFile SummarizeChunk(const ReuseJob& cfg, uint32_t r, uint32_t p, bool distributed,
                           const Log& log) {
  if (cfg.inputs.size() != 1)
    throw UsageError("a chunked analysis takes one input (a trace file or a mesh)");
  const std::string& in = cfg.inputs[0];
  const TraceFormat* fmt = cfg.format.empty() ? nullptr : &ParseTraceFormat(cfg.format);
  if (in == "-") throw UsageError("a chunked analysis needs a file: standard input cannot be cut");
  const bool mesh = !fmt && ClassifyInput(in) == InputKind::kMesh;
  if (mesh && cfg.orderings.size() != 1)
    throw UsageError("a chunked analysis of a mesh takes one ordering");
  if (cfg.sample && cfg.shards.s_max)
    throw UsageError(
        "a chunked analysis samples at a fixed rate (--sample-rate): a fixed-size sample's "
        "threshold depends on every id before it (run --sample-size serially)");
  if (cfg.sample && cfg.shards.exact_below)
    throw UsageError(
        "--sample-exact-below counts the small distances of the whole stream in order: run it "
        "serially (or with --threads), not in chunks or ranks");
  if (cfg.threads != 1 && !mesh)
    throw UsageError("each chunk is analysed on one thread: run more chunks (ranks) instead");
  if (mesh) return SummarizeMeshChunk(cfg, r, p, distributed, log);

  SummaryFile s;
  s.input = in;
  s.chunk = r;
  s.id.chunks = p;
  s.id.format = fmt ? fmt->name : "";
  const bool memory = cfg.IdsOf(in);  // ids in memory, as a u64 file of them
  if (memory)
    s.id.input_bytes = 8 * cfg.ids_count;
  else
    s.id.fingerprint = Fingerprint(in, !distributed, &s.id.input_bytes);
  s.id.instructions = cfg.instructions;
  Granularity g = Granularity::kBoth;
  if (cfg.granularity)
    g = *cfg.granularity;
  else if (fmt)
    g = fmt->addresses ? Granularity::kLine : Granularity::kElement;
  SetAnalysis(cfg, g, &s);

  uint64_t total;
  std::vector<uint64_t> eoff, loff;
  const bool text = fmt && fmt->syntax != TraceSyntax::kFixedRecords;
  if (memory) {
    total = cfg.ids_count;
  } else if (fmt) {
    // A text trace is cut by bytes of its content (decompressed), at line boundaries.
    const int64_t content = InputStream(in).size();
    if (content < 0)
      throw InputError(in, 0,
                       "a zstd-compressed trace whose frames do not all record their sizes cannot "
                       "be cut into chunks: decompress it first (zstd -d)");
    total = static_cast<uint64_t>(content) / (text ? 1 : fmt->record_bytes);
  } else {
    TraceReader tr(in);
    total = tr.header().records;
  }
  Cut(total, r, p, &s);
  if (text) {
    eoff = loff = {0};  // no profile: a text trace's length is not known up front
  } else if (fmt) {
    eoff = loff = {s.first};  // one stream, one access per record (fixed records are 1 byte)
  } else {
    // Only a profile needs the true offsets (reading back to the sweep's start); a distributed
    // run without one sets them from the ranks before (RunDistributed), a summary file must hold
    // them (its merge may write a profile).
    TraceOffsets(in, cfg.profile || !distributed ? s.first : 0, cfg.line_bytes, &eoff, &loff);
  }

  ReuseAnalysis a(ChunkOptions(cfg, s, distributed));
  a.SetStreamOffsets(eoff, loff);
  const RecordRange range{s.first, s.end};
  log.Say("analysing chunk " + ChunkName(r, p) + " of " + in + (text ? ": bytes " : ": records ") +
          std::to_string(s.first) + ".." + std::to_string(s.end) + " of " + std::to_string(total));
  if (memory)
    StreamIds(cfg.ids, cfg.ids_count, in, a, FileProgress(log), cfg.poll, &range);
  else if (fmt)
    StreamForeignTrace(in, *fmt, cfg.instructions, a, FileProgress(log), &range);
  else
    StreamTraceFile(in, a, FileProgress(log), &range);
  Collect(a, &s, !(distributed && r + 1 == p));
  return s;
}

void RunChunk(const ReuseJob& job, uint32_t r, uint32_t p, const std::string& out, const Log& log) {
  WriteSummary(out, SummarizeChunk(job, r, p, false, log));
  log.Say("wrote " + out);
}

}  // namespace meshreuse
