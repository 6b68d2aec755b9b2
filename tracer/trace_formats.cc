// The table of other tools' trace formats; see trace_formats.h. A new fixed-width format is a new
// row here (with a new code) and its test in tests/tracer/foreign_trace_test.cc.
#include "tracer/trace_formats.h"

#include <sstream>

#include "core/error.h"
#include "tracer/foreign_trace.h"
#include "tracer/input_stream.h"

namespace meshreuse {

const std::vector<TraceFormat>& TraceFormats() {
  static const std::vector<TraceFormat> kFormats = {
      {"text", "", 1, TraceSyntax::kTextIds, 0, 0, 0, false,
       "a decimal or 0x-hex id per line ('#' comments and blank lines skipped; '-': stdin)"},
      {"u32", "", 2, TraceSyntax::kFixedRecords, 4, 0, 4, true,
       "raw little-endian 32-bit values, one access each"},
      {"u64", "", 3, TraceSyntax::kFixedRecords, 8, 0, 8, true,
       "raw little-endian 64-bit values, one access each"},
      {"parda", "", 4, TraceSyntax::kFixedRecords, 8, 0, 8, true,
       "PARDA's binary input (Niu et al.): the 8-byte pointers it freads (the same bytes as u64)"},
      {"oracle", "oracleGeneral", 5, TraceSyntax::kFixedRecords, 24, 4, 8, false,
       "libCacheSim's oracleGeneral: 24-byte records {u32 clock, u64 obj_id, u32 obj_size, "
       "i64 next_access_vtime}; the id is obj_id"},
      {"lackey", "", 6, TraceSyntax::kLackey, 0, 0, 0, true,
       "valgrind --tool=lackey --trace-mem=yes --log-file=F output: L (load), S (store), M "
       "(modify: a load then a store) records; I (instruction fetch) lines with --instructions"},
  };
  return kFormats;
}

const TraceFormat* FindTraceFormat(const std::string& name) {
  for (const TraceFormat& f : TraceFormats()) {
    if (name == f.name) return &f;
    std::stringstream ss(f.aliases);
    for (std::string a; std::getline(ss, a, ',');)
      if (!a.empty() && a == name) return &f;
  }
  return nullptr;
}

const TraceFormat& ParseTraceFormat(const std::string& name) {
  if (const TraceFormat* f = FindTraceFormat(name)) return *f;
  throw UsageError("unknown trace format '" + name + "' (" + TraceFormatNames() + ")");
}

const TraceFormat* TraceFormatByCode(uint8_t code) {
  for (const TraceFormat& f : TraceFormats())
    if (f.code == code) return &f;
  return nullptr;
}

std::string TraceFormatNames() {
  std::string s;
  for (const TraceFormat& f : TraceFormats()) s += (s.empty() ? "" : ", ") + std::string(f.name);
  return s;
}

std::string TraceFormatHelp() {
  std::string s;
  for (const TraceFormat& f : TraceFormats())
    s += std::string("  ") + f.name + (*f.aliases ? std::string(" (") + f.aliases + ")" : "") +
         ": " + f.help + (f.addresses ? " [addresses]" : " [ids]") + "\n";
  return s;
}

uint64_t ForeignTraceLength(const std::string& path, const TraceFormat& fmt) {
  if (fmt.syntax != TraceSyntax::kFixedRecords || path == "-") return 0;
  try {
    InputStream in(path);
    return in.size() > 0 ? static_cast<uint64_t>(in.size()) / fmt.record_bytes : 0;
  } catch (const InputError&) {
    return 0;  // the reader reports it
  }
}

}  // namespace meshreuse
