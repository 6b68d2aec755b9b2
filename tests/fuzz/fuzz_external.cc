// libFuzzer harness: other tools' traces (tracer/trace_formats.h). The first byte picks the format
// by its fixed code (low four bits: the table's `code`; a code no format has: nothing to do), bit 4
// counts lackey's instruction fetches, bit 5 runs the analysis on two workers (chunk-and-merge),
// bit 6 reads the file (plain, or zstd in frames) again in three chunks by range and traps unless
// they agree with the whole read (the same verdict; the same accesses).
// Codes are fixed per format, so a new format never changes what an existing seed means. The rest
// is the file, plain or zstd (the reader tells them apart by the magic number, so the fuzzer
// reaches the decompressor too). Every access goes through the exact analyzer and the simulator.
#include "analysis/cache_model.h"
#include "analysis/cache_sim.h"
#include "analysis/reuse_analysis.h"
#include "tests/fuzz/fuzz_util.h"
#include "tracer/access_stream.h"
#include "tracer/input_stream.h"
#include "tracer/trace_formats.h"

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
  struct Count : AccessConsumer {
    uint64_t n = 0;
    void Begin(const StreamInfo&) override {}
    void Consume(const Access*, size_t k) override { n += k; }
  } whole, parts;
  FanOut both({&a, &sim, &whole});
  bool whole_ok = true;
  try {
    StreamForeignTrace(f.path(), *fmt, instructions, both);
  } catch (const InputError&) {
    whole_ok = false;
  }
  // Bit 6: the file read again as three chunks by range, as `analyze --threads 3` and `--chunk
  // r/3` read it (records, or the lines that begin in a byte range; a zstd file from the frames
  // that begin at or before each chunk, and on to the next chunk's frame): every chunk reads
  // exactly when the whole read does, and together they hold its accesses. Not a zstd file whose
  // frames do not record their sizes (a chunk cannot enter it: refused up front).
  if (!(data[0] & 0x40)) return 0;
  int64_t content = -1;
  try {
    content = InputStream(f.path()).size();
  } catch (const InputError&) {
  }
  if (content < 0) return 0;
  const bool text = fmt->syntax != TraceSyntax::kFixedRecords;
  const uint64_t total = text ? static_cast<uint64_t>(content) : ForeignTraceLength(f.path(), *fmt);
  bool parts_ok = true;
  for (uint64_t r = 0; r < 3; ++r) {
    const RecordRange range{total * r / 3, total * (r + 1) / 3};
    try {
      StreamForeignTrace(f.path(), *fmt, instructions, parts, {}, &range);
    } catch (const InputError&) {
      parts_ok = false;
    }
  }
  // A lackey file without records: a chunk cannot tell, the merge of all of them refuses
  // (SummaryMerger::Finish).
  if (fmt->syntax == TraceSyntax::kLackey && parts.n == 0) parts_ok = false;
  if (parts_ok != whole_ok || (whole_ok && parts.n != whole.n)) __builtin_trap();
  return 0;
}
