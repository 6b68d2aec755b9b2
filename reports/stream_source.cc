// The stream source and the one input loop; see stream_source.h.
#include "reports/stream_source.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include "core/error.h"
#include "core/schedule.h"
#include "core/table.h"
#include "reports/inputs.h"
#include "reports/rank_locality.h"

namespace meshreuse {

void StreamSource::Check() const {
  if (inputs.empty()) throw UsageError("no input given");
  const TraceFormat* fmt = Format();
  if (orderings.empty()) throw UsageError("no ordering given");
  if (iterations < 1 || iterations > kMaxStreamSweeps)
    throw UsageError("--iterations must be 1..65536");
  if (threads < 1 || threads > kMaxThreads)
    throw UsageError("--threads must be 1.." + std::to_string(kMaxThreads));
  CheckStreamSweeps(iterations, threads);
  if (instructions && (!fmt || fmt->syntax != TraceSyntax::kLackey))
    throw UsageError("--instructions applies to --format lackey");
  if (ranks > 0 && (fmt || threads != 1))
    throw UsageError(
        "--ranks streams each rank's part of a mesh (one stream per rank): no --format or "
        "--threads with it");
  CheckRankParts(ranks, partition, inputs);
  const KernelInfo& k = Kernel();
  CheckKernelOptions(k, Sweeps());
  if (ranks > 0 && !IsPaperSweep(k))
    throw UsageError("--ranks streams the distributed Laplacian smoother: no --kernel " +
                     std::string(k.name) + " with it");
}

const TraceFormat* StreamSource::Format() const {
  return format.empty() ? nullptr : &ParseTraceFormat(format);
}

SmoothOptions StreamSource::Sweeps() const {
  SmoothOptions o = ExactSweeps(iterations, threads, mode);
  o.interleave = interleave;
  return o;
}

Json StreamSource::ToJson() const {
  Json j;
  j["inputs"] = inputs;
  j["format"] = format;
  j["orderings"] = OrderingTexts(orderings);
  j["seed"] = seed;
  j["ordering_seeds"] = OrderingSeedsJson(orderings, seed);
  j["kernel"] = kernel;
  j["iterations"] = iterations;
  j["threads"] = threads;
  j["mode"] = UpdateModeName(mode);
  j["triangle_order"] = TriangleOrderName(triangle_order);
  return j;
}

ProgressFn FileProgress(const Log& log, const std::string& verb) {
  auto last = std::make_shared<double>(-1);
  auto t0 =
      std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  return [&log, verb, last, t0](double done) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - *t0).count();
    if (s - *last < 2.0) return;
    *last = s;
    char b[120];
    if (done > 0)
      std::snprintf(b, sizeof b, "%s: %.0f%% (%.1f s, about %.1f s left)", verb.c_str(), 100 * done,
                    s, s * (1 - done) / done);
    else
      std::snprintf(b, sizeof b, "%s: %.1f s so far", verb.c_str(), s);
    log.Say(b);
  };
}

namespace {

// One mesh in one ordering: each rank's part, or the whole mesh laid out and swept.
void StreamMeshInput(const StreamSource& src, StreamJob job, StreamConsumer& c, const Log& log) {
  if (src.ranks > 0) {
    RankLocalityConfig rc;
    rc.mesh = job.input, rc.ranks = src.ranks, rc.partition = src.partition;
    rc.ordering = *job.ordering, rc.placement = src.cut_placement;
    rc.seed = src.seed, rc.sweeps = src.Sweeps();
    StreamRankParts(rc, log, [&](int32_t r) -> AccessConsumer& {
      job.rank = r;
      return c.Start(job);
    });
    return;
  }
  Mesh m =
      src.loaded && job.input == src.inputs[0]
          ? ApplyPermutation(*src.loaded, ComputeOrdering(*job.ordering, *src.loaded, src.seed),
                             src.triangle_order)
          : LayOut(job.input, *job.ordering, src.seed, src.triangle_order, log);
  const KernelInfo& kernel = src.Kernel();
  const std::string what =
      IsPaperSweep(kernel) ? " sweep(s) of " : " " + std::string(kernel.name) + " sweep(s) of ";
  log.Say(c.Verb() + " " + std::to_string(src.iterations) + what + job.input + " in " +
          job.ordering->text + " order" + c.Where());
  const auto t0 = std::chrono::steady_clock::now();
  job.mesh = &m;
  AccessConsumer& to = c.Start(job);
  job.mesh = nullptr;
  StreamMesh(m, src.Sweeps(), job.input, job.ordering->label, to, &kernel);
  c.Finish(job);
  log.Say("done in " +
          Fixed(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2) +
          " s");
}

}  // namespace

InputKind StreamSource::KindOf(const std::string& in) const {
  const bool first = !inputs.empty() && in == inputs[0];
  if (loaded && first) return InputKind::kMesh;  // a mesh already read
  if (IdsOf(in) || !format.empty()) return InputKind::kText;
  return ClassifyInput(in);
}

void ForEachStream(const StreamSource& src, StreamConsumer& c, const Log& log) {
  const TraceFormat* fmt = src.Format();
  if (!fmt) CheckTraceSets(src.inputs);
  for (const std::string& in : src.inputs) {
    StreamJob job;
    job.input = in;
    job.kind = src.KindOf(in);
    if (job.kind == InputKind::kMesh) {
      for (const OrderingSpec& ord : src.orderings) {
        job.ordering = &ord;
        StreamMeshInput(src, job, c, log);
      }
      continue;
    }
    if (c.TakeTrace(in, log)) continue;
    if (src.IdsOf(in)) {
      job.format = fmt ? fmt : &ParseTraceFormat("u64");
      log.Say(c.Verb() + " " + in + " (" + Grouped(static_cast<long long>(src.ids_count)) +
              " ids in memory)" + c.Where());
      StreamIds(src.ids, src.ids_count, in, c.Start(job), {}, src.poll);
      c.Finish(job);
      continue;
    }
    if (job.kind == InputKind::kTrace) {
      log.Say(c.Verb() + " trace " + in + c.Where());
      StreamTraceFile(in, c.Start(job), FileProgress(log, c.Verb()));
    } else {
      job.format = fmt ? fmt : &ParseTraceFormat("text");
      const uint64_t len = ForeignTraceLength(in, *job.format);
      log.Say(c.Verb() + " " + in + " as " + job.format->name +
              (len ? " (" + Grouped(static_cast<long long>(len)) + " accesses)" : "") + c.Where());
      StreamForeignTrace(in, *job.format, src.instructions, c.Start(job),
                         FileProgress(log, c.Verb()));
    }
    c.Finish(job);
  }
}

}  // namespace meshreuse
