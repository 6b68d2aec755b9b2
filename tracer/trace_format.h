// The binary trace format (DESIGN.md "Files the toolkit writes"). Little-endian throughout.
//   offset  size  field
//   0       8     magic "MRTRACE\0"
//   8       4     version (2; version-1 files are still read)
//   12      4     header bytes (records start here)
//   16      4     granularity: 3 = both (each record has a vertex id and a byte address)
//   20      4     element bytes (the paper's node size, 66 by default; for the element miss model)
//   24      4     threads (streams)
//   28      4     iterations I (sweeps recorded)
//   32      4     boundary slots S >= I (room reserved when the file was opened)
//   36      4     vertices of the mesh (0: unknown)
//   40      8     record count
//   48      8*S   iteration boundaries: index of the first record of sweep 1..I, then zeros
//   ...     8*S*T records of each thread in each sweep (sweep-major; T = threads), then zeros
//   ...     8*S*T version 2: element touches of each thread in each sweep, then zeros
//   ...     2+n   mesh name (u16 length, bytes), then 2+n ordering name; zero padding to 16
// then `record count` records of 16 bytes: u64 address, u32 vertex, u8 kind (AccessKind),
// u8 thread, u8 size, u8 array (bits 0-6: Array, bit 7: a store). Records of all threads are in
// one sequence (a traced run is serial: thread 0's part of a sweep, then thread 1's ...); each
// thread's stream is its records in file order.
// Version 2 records are the address stream: every load and store of the sweep (tracer/sink.h);
// the element touches among them have kind 0-2 and a vertex id, the others kind 3 (none).
// Version 1 records were the element touches alone (kind 0-2, size and array 0); read as such,
// their addresses are the line stream, as the version-1 tools had it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshreuse {

inline constexpr char kTraceMagic[8] = {'M', 'R', 'T', 'R', 'A', 'C', 'E', '\0'};
inline constexpr uint32_t kTraceVersion = 2;
inline constexpr uint32_t kGranularityBoth = 3;

struct TraceRecord {
  uint64_t address;
  uint32_t vertex;
  uint8_t kind;
  uint8_t thread;
  uint8_t size;   // bytes; 0 in version-1 files
  uint8_t array;  // bits 0-6: Array, bit 7: store
};
inline constexpr uint8_t kStoreBit = 0x80;
static_assert(sizeof(TraceRecord) == 16, "records are 16 bytes on disk");

struct TraceHeader {
  uint32_t version = kTraceVersion;
  uint32_t granularity = kGranularityBoth;
  uint32_t element_bytes = 66;
  uint32_t threads = 1;
  uint32_t vertices = 0;  // 0: unknown
  uint64_t records = 0;
  std::vector<uint64_t> iteration_starts;  // one per sweep
  // sweep_records[i][t]: records of thread t in sweep i (what a per-thread profile needs), and
  // sweep_elements[i][t] the element touches among them (version 1: the same).
  std::vector<std::vector<uint64_t>> sweep_records;
  std::vector<std::vector<uint64_t>> sweep_elements;
  std::string mesh, ordering;
};

}  // namespace meshreuse
