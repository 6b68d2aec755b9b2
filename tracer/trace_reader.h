// Streaming reader of the binary trace: the header up front, then records in blocks, so memory
// does not grow with the trace. Rejects, with InputError naming the file: a wrong magic (not a
// meshreuse trace), an unknown version, a header that does not fit, and a truncated file (fewer
// record bytes than the header's count says, or a partial record).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "tracer/trace_format.h"

namespace meshreuse {

class TraceReader {
 public:
  explicit TraceReader(std::string path);
  ~TraceReader();
  TraceReader(const TraceReader&) = delete;
  TraceReader& operator=(const TraceReader&) = delete;

  const TraceHeader& header() const { return header_; }
  // Fills `out` with up to `max` next records; returns false when none are left.
  bool Next(std::vector<TraceRecord>* out, size_t max = 1 << 16);

  // True if the file starts with the trace magic (to tell traces from other inputs).
  static bool LooksLikeTrace(const std::string& path);

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  TraceHeader header_;
  uint64_t left_ = 0;
};

}  // namespace meshreuse
