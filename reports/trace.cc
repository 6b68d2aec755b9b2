// The trace runner; see trace.h.
#include "reports/trace.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/schedule.h"
#include "core/table.h"
#include "reports/inputs.h"
#include "reports/rank_locality.h"
#include "tracer/access_stream.h"
#include "tracer/input_stream.h"
#include "tracer/trace_writer.h"

namespace meshreuse {

std::vector<std::string> TraceOutputs(const TraceConfig& cfg) {
  if (cfg.ranks <= 0) return {cfg.output};
  std::vector<std::string> out;
  for (int32_t r = 0; r < cfg.ranks; ++r) out.push_back(cfg.output + ".rank" + std::to_string(r));
  return out;
}

void CheckTraceConfig(const TraceConfig& cfg) {
  CheckOrderingSpec(cfg.ordering);
  CheckRankParts(cfg.ranks, cfg.partition, {cfg.mesh});
  if (cfg.ranks > 0) {
    if (cfg.threads != 1) throw UsageError("--ranks traces one stream per rank: no --threads");
    if (cfg.compress)
      throw UsageError("--ranks writes plain traces (compress each with zstd afterwards)");
  }
  if (cfg.iterations < 1 || cfg.iterations > kMaxStreamSweeps)
    throw UsageError("--iterations must be 1..65536");
  if (cfg.threads < 1 || cfg.threads > kMaxThreads)
    throw UsageError("--threads must be 1.." + std::to_string(kMaxThreads));
  CheckStreamSweeps(cfg.iterations, cfg.threads);
  for (const std::string& f : TraceOutputs(cfg)) CheckOutputPath(f, "-o", InputFiles({cfg.mesh}));
}

namespace {

// One trace file from whatever `stream` feeds it: plain, or plain then zstd-compressed.
void WriteOneTrace(const std::string& output, const TraceHeader& h, int sweeps, bool compress,
                   const Log& log, const std::function<void(TraceWriter&)>& stream,
                   TraceRunResult* r) {
  // Compressed: the plain trace first (its header is final only at the end), then zstd.
  const std::string plain = compress ? output + ".plain.tmp." + std::to_string(::getpid()) : output;
  struct RemovePlain {
    std::string path;
    ~RemovePlain() {
      if (!path.empty()) std::remove(path.c_str());
    }
  } cleanup{compress ? plain : ""};
  {
    TraceWriter w(plain, h, sweeps);
    stream(w);
    w.Close();
    r->records += w.records();
    r->elements += w.elements();
  }
  if (compress) {
    log.Say("compressing " + output + " with zstd");
    CompressFile(plain, output);
    std::error_code ec;
    r->compressed_bytes += std::filesystem::file_size(output, ec);
  }
}

}  // namespace

TraceRunResult RunTrace(const TraceConfig& cfg, const Log& log) {
  CheckTraceConfig(cfg);
  SmoothOptions so;
  so.max_iters = cfg.iterations;
  so.tol = -std::numeric_limits<double>::infinity();  // exactly `iterations` sweeps
  so.threads = cfg.threads;
  so.mode = cfg.mode;
  TraceRunResult r;
  TraceHeader h;
  h.element_bytes = cfg.element_bytes;
  h.mesh = std::filesystem::path(cfg.mesh).filename().string();
  h.ordering = ParseOrderingSpec(cfg.ordering).label;
  const auto t0 = std::chrono::steady_clock::now();
  if (cfg.ranks > 0) {
    // Each rank's part in turn (StreamRankParts asks for rank r's consumer just before streaming
    // it): a writer per rank, closed when the next rank begins and after the last.
    RankLocalityConfig rc;
    rc.mesh = cfg.mesh, rc.ranks = cfg.ranks, rc.partition = cfg.partition;
    rc.ordering = cfg.ordering, rc.seed = cfg.seed, rc.sweeps = so;
    rc.placement = cfg.cut_placement;
    const std::vector<std::string> outputs = TraceOutputs(cfg);
    std::unique_ptr<TraceWriter> w;
    int32_t open_rank = -1;
    auto finish = [&] {
      if (!w) return;
      w->Close();
      r.records += w->records();
      r.elements += w->elements();
      w.reset();
      log.Say("wrote " + outputs[open_rank]);
    };
    StreamRankParts(rc, log, [&](int32_t rank) -> AccessConsumer& {
      finish();
      TraceHeader hr = h;
      hr.mesh += " [rank " + std::to_string(rank) + " of " + std::to_string(cfg.ranks) + "]";
      w = std::make_unique<TraceWriter>(outputs[rank], hr, cfg.iterations);
      open_rank = rank;
      return *w;
    });
    finish();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }
  Mesh m = LayOut(cfg.mesh, cfg.ordering, cfg.seed, cfg.triangle_order, log);
  r.vertices = m.NumVertices();
  WriteOneTrace(
      cfg.output, h, cfg.iterations, cfg.compress, log,
      [&](TraceWriter& w) {
        log.Say("tracing " + std::to_string(cfg.iterations) + " sweep(s), about " +
                Grouped(static_cast<long long>(MeshStreamInfo(m, so).records)) + " accesses");
        StreamMesh(m, so, cfg.mesh, h.ordering, w);
      },
      &r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace meshreuse
