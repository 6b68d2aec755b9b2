// libFuzzer harness: a meshreuse binary trace (versions 1 and 2), read as `analyze` and `simulate`
// read it (tracer/access_stream.h): the header, every record into the reuse analysis (element and
// line, with profiles) and the cache simulator.
#include "analysis/cache_model.h"
#include "analysis/cache_sim.h"
#include "analysis/reuse_analysis.h"
#include "tests/fuzz/fuzz_util.h"
#include "tracer/access_stream.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  fuzz::MemFile f(data, size);
  ReuseAnalysis a({});
  CacheSimulation sim(ParseCacheSpec("L1=1K/2,L2=4K/4"), 64);
  FanOut both({&a, &sim});
  try {
    StreamTraceFile(f.path(), both);
  } catch (const InputError&) {
  }
  return 0;
}
