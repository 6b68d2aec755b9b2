// libFuzzer harness: other tools' traces (tracer/trace_formats.h). The first byte picks the format
// by its fixed code (low four bits: the table's `code`; a code no format has: nothing to do), bit 4
// counts lackey's instruction fetches, bit 5 runs the analysis on two workers (chunk-and-merge).
// Codes are fixed per format, so a new format never changes what an existing seed means. The rest
// is the file, plain or zstd (the reader tells them apart by the magic number, so the fuzzer
// reaches the decompressor too). Every access goes through the exact analyzer and the simulator.
#include "analysis/cache_model.h"
#include "analysis/cache_sim.h"
#include "analysis/reuse_analysis.h"
#include "tests/fuzz/fuzz_util.h"
#include "tracer/access_stream.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  if (size == 0) return 0;
  const TraceFormat* fmt = TraceFormatByCode(data[0] & 0x0f);
  if (!fmt) return 0;
  const bool instructions = data[0] & 0x10;
  fuzz::MemFile f(data + 1, size - 1);
  ReuseOptions o;
  o.workers = data[0] & 0x20 ? 2 : 1;
  o.batch_per_worker = 64;
  ReuseAnalysis a(o);
  CacheSimulation sim(ParseCacheSpec("L1=1K/2,L2=4K/4"), 64);
  FanOut both({&a, &sim});
  try {
    StreamForeignTrace(f.path(), *fmt, instructions, both);
  } catch (const InputError&) {
  }
  return 0;
}
