// TraceWriter: the consumer that writes the binary trace (trace_format.h). Records are buffered and
// written in 1 MiB blocks through core/output_file.h (a temporary renamed when complete: an
// interrupted run leaves no trace file behind; a device or FIFO written in place). Close() writes
// the final header. The header reserves room for `max_sweeps` sweeps (the sweep count is known
// only at the end); each thread's records per sweep are counted as they come, so readers need no
// pass of their own to find them. Addresses arrive canonical (core/access.h): the same trace in
// every run. A FIFO or device gets the header only at the start (it cannot be rewritten): readers
// need a regular file, so `trace -o /dev/null` is for timing the tracer, not for reading back.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/output_file.h"
#include "tracer/access_stream.h"
#include "tracer/trace_format.h"

namespace meshreuse {

class TraceWriter : public AccessConsumer {
 public:
  // `header`: element bytes, mesh and ordering names; threads, vertices and sweeps come from the
  // stream (Begin).
  TraceWriter(std::string path, TraceHeader header, int max_sweeps);
  ~TraceWriter() override;  // removes the temporary file unless Close() succeeded
  TraceWriter(const TraceWriter&) = delete;
  TraceWriter& operator=(const TraceWriter&) = delete;

  void Begin(const StreamInfo& info) override;
  void BeginSweep(int sweep) override;
  void Consume(const Access* a, size_t n) override;
  void Close();  // throws EnvironmentError on an I/O failure
  // Closes the file complete but leaves it under its temporary name: the caller renames it with
  // the other files of a set (AtomicOutput::Rename), all or none (a rank per file).
  std::unique_ptr<AtomicOutput> CloseForSet();
  uint64_t records() const { return records_ + buf_.size(); }
  uint64_t elements() const {  // element touches among the records (of the marked sweeps)
    uint64_t n = 0;
    for (const auto& sweep : header_.sweep_elements)
      for (uint64_t e : sweep) n += e;
    return n;
  }

 private:
  void Flush();

  std::string path_;
  TraceHeader header_;
  int max_sweeps_;
  std::unique_ptr<AtomicOutput> out_;
  std::vector<TraceRecord> buf_;
  uint64_t records_ = 0;
};

// The header bytes, with room for `reserve_iterations` sweeps (TraceReader decodes them).
std::vector<char> EncodeTraceHeader(const TraceHeader& h, int reserve_iterations);

}  // namespace meshreuse
