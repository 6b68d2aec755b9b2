// The trace runner; see trace.h.
#include "reports/trace.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/schedule.h"
#include "core/table.h"
#include "reports/inputs.h"
#include "tracer/access_stream.h"
#include "tracer/input_stream.h"
#include "tracer/trace_writer.h"

namespace meshreuse {

void CheckTraceConfig(const TraceConfig& cfg) {
  CheckOrderingSpec(cfg.ordering);
  if (cfg.iterations < 1 || cfg.iterations > kMaxStreamSweeps)
    throw UsageError("--iterations must be 1..65536");
  if (cfg.threads < 1 || cfg.threads > kMaxThreads)
    throw UsageError("--threads must be 1.." + std::to_string(kMaxThreads));
  CheckStreamSweeps(cfg.iterations, cfg.threads);
  CheckOutputPath(cfg.output, "-o", InputFiles({cfg.mesh}));
}

TraceRunResult RunTrace(const TraceConfig& cfg, const Log& log) {
  CheckTraceConfig(cfg);
  SmoothOptions so;
  so.max_iters = cfg.iterations;
  so.tol = -std::numeric_limits<double>::infinity();  // exactly `iterations` sweeps
  so.threads = cfg.threads;
  so.mode = cfg.mode;
  Mesh m = LayOut(cfg.mesh, cfg.ordering, cfg.seed, cfg.triangle_order, log);
  TraceRunResult r;
  r.vertices = m.NumVertices();
  TraceHeader h;
  h.element_bytes = cfg.element_bytes;
  h.mesh = std::filesystem::path(cfg.mesh).filename().string();
  h.ordering = ParseOrderingSpec(cfg.ordering).label;
  const auto t0 = std::chrono::steady_clock::now();
  // Compressed: the plain trace first (its header is final only at the end), then zstd.
  const std::string plain =
      cfg.compress ? cfg.output + ".plain.tmp." + std::to_string(::getpid()) : cfg.output;
  struct RemovePlain {
    std::string path;
    ~RemovePlain() {
      if (!path.empty()) std::remove(path.c_str());
    }
  } cleanup{cfg.compress ? plain : ""};
  {
    TraceWriter w(plain, h, cfg.iterations);
    log.Say("tracing " + std::to_string(cfg.iterations) + " sweep(s), about " +
            Grouped(static_cast<long long>(MeshStreamInfo(m, so).records)) + " accesses");
    StreamMesh(m, so, cfg.mesh, h.ordering, w);
    w.Close();
    r.records = w.records();
    r.elements = w.elements();
  }
  if (cfg.compress) {
    log.Say("compressing with zstd");
    CompressFile(plain, cfg.output);
    std::error_code ec;
    r.compressed_bytes = std::filesystem::file_size(cfg.output, ec);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace meshreuse
