// libFuzzer harness: a meshreuse binary trace (versions 1 and 2), read as `analyze` and `simulate`
// read it: the header, every record into the reuse analysis (element and line, with profiles) and
// the cache simulator.
#include <algorithm>
#include <vector>

#include "analysis/cache_model.h"
#include "analysis/cache_sim.h"
#include "analysis/trace_analysis.h"
#include "tests/fuzz/fuzz_util.h"
#include "tracer/trace_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  fuzz::MemFile f(data, size);
  try {
    TraceReader r(f.path());
    const TraceHeader& h = r.header();
    TraceAnalysisOptions o;
    o.threads = static_cast<int>(h.threads);
    o.dense_elements = std::min<uint64_t>(h.vertices, h.records);
    o.iteration_lengths.assign(h.threads, {});
    o.line_iteration_lengths.assign(h.threads, {});
    for (const auto& s : h.sweep_elements)
      for (uint32_t t = 0; t < h.threads; ++t) o.iteration_lengths[t].push_back(s[t]);
    for (const auto& s : h.sweep_records)
      for (uint32_t t = 0; t < h.threads; ++t) o.line_iteration_lengths[t].push_back(s[t]);
    TraceAnalysis a(o);
    CacheSimulation sim(ParseCacheSpec("L1=1K/2,L2=4K/4"), 64, static_cast<int>(h.threads));
    std::vector<TraceRecord> batch;
    while (r.Next(&batch))
      for (const TraceRecord& rec : batch) {
        if (rec.thread >= h.threads) return 0;  // the CLI rejects this record with its position
        if (rec.kind < kElementKinds) a.AddElement(rec.thread, rec.vertex);
        a.AddAccess(rec.thread, rec.address, rec.size);
        sim.Access(rec.thread, rec.address, rec.size, (rec.array & kStoreBit) != 0);
      }
  } catch (const InputError&) {
  }
  return 0;
}
