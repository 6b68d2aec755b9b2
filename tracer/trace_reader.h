// Streaming reader of the binary trace, plain or zstd-compressed (input_stream.h): the header up
// front, then records in blocks, so memory
// does not grow with the trace. Rejects, with InputError naming the file and the byte offset: a
// wrong magic (not a meshreuse trace), an unknown version, a header that does not fit or
// contradicts itself (per-sweep counts that do not add up to the record count, sweeps that do not
// start where the counts say, a vertex count beyond 32-bit ids), and a truncated file (fewer record
// bytes than the header's count says, or a partial record). Every size read from the file is
// checked before any arithmetic or allocation uses it; the file handle is released on every path.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "tracer/input_stream.h"
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
  // Reads records [first, end) only (a chunk): a regular file, plain or zstd in frames that
  // record their sizes (InputStream::SeekTo).
  void Range(uint64_t first, uint64_t end);

  // True if the file starts with the trace magic (to tell traces from other inputs).
  static bool LooksLikeTrace(const std::string& path);

 private:
  std::string path_;
  std::unique_ptr<InputStream> in_;
  bool sized_ = true;

 public:
  // Whether the record count was checked against the file's size up front (else as it is read).
  bool sized() const {
    return sized_;
  }  // the content's size is known (checked against the header up front)
  TraceHeader header_;
  uint64_t left_ = 0;
  uint64_t end_ = ~uint64_t{0};  // Next stops at this record (set to the count by the constructor)
  uint64_t header_bytes_ = 0;
};

}  // namespace meshreuse
