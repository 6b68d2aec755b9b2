// Other tools' traces, as one table (trace_formats.cc): each format's name, aliases, a fixed code
// (fuzz seeds start with it, so adding a format never changes what an existing seed means), its
// syntax, record layout, whether its values are byte addresses or ids, and its help text. The
// CLI's --help, the README's format table and the fuzz harness all read this table: a
// fixed-width format is one row.
//   text    a decimal or 0x-hex id per line, '#' comments and blank lines skipped
//   lackey  valgrind --tool=lackey --trace-mem=yes: " L addr,size", " S", " M" (a modify is a load
//           then a store), "I" (instruction fetches, skipped unless asked for)
//   fixed   little-endian records of record_bytes, the value's value_bytes at value_offset
// Any of them may be zstd-compressed (tracer/input_stream.h reads them transparently).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshreuse {

enum class TraceSyntax { kFixedRecords, kTextIds, kLackey };

struct TraceFormat {
  const char* name;
  const char* aliases;  // comma-separated other names, "" for none
  uint8_t code;         // fixed forever: fuzz seeds and nothing else depend on it
  TraceSyntax syntax;
  uint32_t record_bytes, value_offset, value_bytes;  // kFixedRecords; value_bytes 1, 2, 4 or 8
  bool addresses;  // values are byte addresses (default granularity line) or ids (element)
  const char* help;
};

const std::vector<TraceFormat>& TraceFormats();
const TraceFormat* FindTraceFormat(const std::string& name);   // by name or alias; nullptr
const TraceFormat& ParseTraceFormat(const std::string& name);  // UsageError naming the known ones
const TraceFormat* TraceFormatByCode(uint8_t code);            // nullptr for an unused code
std::string TraceFormatNames();                                // "text, u32, ..."
// One line per format, "name (aliases): help", for --help.
std::string TraceFormatHelp();
// Accesses in a fixed-record trace (from its size, decompressed when zstd records it); 0 when
// unknown (a text format, a pipe, a compressed stream without its size).
uint64_t ForeignTraceLength(const std::string& path, const TraceFormat& fmt);

}  // namespace meshreuse
