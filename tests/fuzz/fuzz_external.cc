// libFuzzer harness: other tools' traces. The first byte picks the format (text, u32, u64); the
// rest is the file. Every value goes through the exact analyzer and the cache simulator.
#include "analysis/cache_model.h"
#include "analysis/cache_sim.h"
#include "analysis/trace_analysis.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  if (size == 0) return 0;
  const ExternalFormat fmt = data[0] % 3 == 0   ? ExternalFormat::kText
                             : data[0] % 3 == 1 ? ExternalFormat::kU32
                                                : ExternalFormat::kU64;
  fuzz::MemFile f(data + 1, size - 1);
  TraceAnalysisOptions o;
  o.iteration_lengths = o.line_iteration_lengths = {{ExternalTraceLength(f.path(), fmt)}};
  TraceAnalysis a(o);
  CacheSimulation sim(ParseCacheSpec("L1=1K/2,L2=4K/4"), 64, 1);
  try {
    ReadExternalTrace(f.path(), fmt, [&](uint64_t v) {
      a.AddElement(0, v);
      a.AddAccess(0, v, 1);
      sim.Access(0, v, 1, false);
    });
  } catch (const InputError&) {
  }
  return 0;
}
