// libFuzzer harness: other tools' traces. The first byte picks the format (text, u32, u64, parda,
// oracle, lackey; lackey with or without instruction fetches) and whether the analysis runs on
// two workers (chunk-and-merge); the rest is the file, plain or zstd (the reader tells them apart
// by the magic number, so the fuzzer reaches the decompressor too). Every access goes through the
// exact analyzer and the cache simulator.
#include "analysis/cache_model.h"
#include "analysis/cache_sim.h"
#include "analysis/trace_analysis.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  if (size == 0) return 0;
  const ExternalFormat formats[] = {ExternalFormat::kText,   ExternalFormat::kU32,
                                    ExternalFormat::kU64,    ExternalFormat::kParda,
                                    ExternalFormat::kOracle, ExternalFormat::kLackey};
  const ExternalFormat fmt = formats[data[0] % 6];
  const bool instructions = (data[0] / 6) % 2;
  fuzz::MemFile f(data + 1, size - 1);
  TraceAnalysisOptions o;
  o.iteration_lengths = o.line_iteration_lengths = {{ExternalTraceLength(f.path(), fmt)}};
  o.workers = (data[0] / 12) % 2 ? 2 : 1;
  o.batch_per_worker = 64;
  TraceAnalysis a(o);
  CacheSimulation sim(ParseCacheSpec("L1=1K/2,L2=4K/4"), 64, 1);
  try {
    ReadExternalTrace(
        f.path(), fmt,
        [&](uint64_t v, uint32_t bytes) {
          a.AddElement(0, v);
          a.AddAccess(0, v, bytes);
          sim.Access(0, v, bytes, false);
        },
        instructions);
  } catch (const InputError&) {
  }
  a.Finish();
  return 0;
}
