// The trace runner; see trace.h.
#include "reports/trace.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>

#include "core/error.h"
#include "core/mesh_io.h"
#include "core/mix.h"
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

// A tag of the set `trace --ranks` writes: a hash of the mesh file's bytes and of every option that
// shapes the streams, so two runs of one configuration write the same files (mixing them is
// harmless) and files of runs that differ carry different tags.
std::string TraceSetTag(const TraceConfig& cfg) {
  uint64_t h = 0x6d657368736574ull;  // "meshset"
  std::FILE* f = std::fopen(cfg.mesh.c_str(), "rb");
  if (f) {
    char b[1 << 16];
    for (size_t n; (n = std::fread(b, 1, sizeof b, f)) > 0;) {
      size_t i = 0;
      for (uint64_t w; i + 8 <= n; i += 8) std::memcpy(&w, b + i, 8), h = Mix64(h ^ w) + n;
      for (; i < n; ++i) h = Mix64(h ^ static_cast<unsigned char>(b[i]));
    }
    std::fclose(f);
  }
  const std::string what = cfg.ordering + "|" + std::to_string(cfg.seed) + "|" +
                           std::to_string(cfg.ranks) + "|" + cfg.partition + "|" +
                           CutPlacementName(cfg.cut_placement) + "|" +
                           std::to_string(cfg.iterations) + "|" + UpdateModeName(cfg.mode) + "|" +
                           std::to_string(cfg.element_bytes);
  for (char c : what) h = Mix64(h ^ static_cast<unsigned char>(c));
  char tag[20];
  std::snprintf(tag, sizeof tag, "%016llx", static_cast<unsigned long long>(h));
  return tag;
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
  const KernelInfo& k = ParseKernel(cfg.kernel);
  SmoothOptions so = ExactSweeps(cfg.iterations, cfg.threads, cfg.mode);
  CheckKernelOptions(k, so);
  if (cfg.ranks > 0 && !IsPaperSweep(k))
    throw UsageError("--ranks traces the distributed Laplacian smoother: no --kernel " +
                     std::string(k.name) + " with it");
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
  const KernelInfo& kernel = ParseKernel(cfg.kernel);
  if (!IsPaperSweep(kernel)) h.mesh += " [kernel " + cfg.kernel + "]";
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
    // The files are a set: each closed complete under its temporary name, then all renamed into
    // place at the end, so a failure (a full disk) leaves every old file as it was. Each header
    // names the set (a run's nonce beside the rank), so that files of two runs read together are
    // told apart (access_stream.h).
    const std::string set = TraceSetTag(cfg);
    std::vector<std::unique_ptr<AtomicOutput>> closed;
    std::unique_ptr<TraceWriter> w;
    auto finish = [&] {
      if (!w) return;
      closed.push_back(w->CloseForSet());
      r.records += w->records();
      r.elements += w->elements();
      w.reset();
    };
    StreamRankParts(rc, log, [&](int32_t rank) -> AccessConsumer& {
      finish();
      TraceHeader hr = h;
      hr.mesh += " [rank " + std::to_string(rank) + " of " + std::to_string(cfg.ranks) + ", set " +
                 set + "]";
      w = std::make_unique<TraceWriter>(outputs[rank], hr, cfg.iterations);
      return *w;
    });
    finish();
    for (size_t k = 0; k < closed.size(); ++k) {
      closed[k]->Rename();
      log.Say("wrote " + outputs[k]);
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }
  Mesh m = LayOut(cfg.mesh, cfg.ordering, cfg.seed, cfg.triangle_order, log);
  r.vertices = m.NumVertices();
  WriteOneTrace(
      cfg.output, h, cfg.iterations, cfg.compress, log,
      [&](TraceWriter& w) {
        // The length from the stream's own announcement: another kernel than the Laplacian is
        // counted by a run of its own (MeshStreamInfo), which asking here would repeat.
        Announced told(w, [&](const StreamInfo& info) {
          log.Say("tracing " + std::to_string(cfg.iterations) + " " + cfg.kernel + " sweep(s), " +
                  Grouped(static_cast<long long>(info.records)) + " accesses");
        });
        StreamMesh(m, so, cfg.mesh, h.ordering, told, &kernel);
      },
      &r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace meshreuse
