// TraceWriter: a sink that writes the binary trace (trace_format.h). Records are buffered and
// written in 1 MiB blocks to PATH.tmp.PID; Close() writes the final header and renames the file
// into place, so an interrupted run leaves no trace file behind. The header reserves room for
// `max_iterations` sweeps (the sweep count is known only at the end); each thread's records per
// sweep are counted as they come, so readers need no pass of their own to find them. Addresses are
// written canonical (sink.h, AddressCanonicalizer): the same trace in every run.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "tracer/sink.h"
#include "tracer/trace_format.h"

namespace meshreuse {

class TraceWriter {
 public:
  static constexpr bool kEnabled = true;

  TraceWriter(std::string path, TraceHeader header, int max_iterations);
  ~TraceWriter();  // removes the temporary file unless Close() succeeded
  TraceWriter(const TraceWriter&) = delete;
  TraceWriter& operator=(const TraceWriter&) = delete;

  void Bind(const ArrayLayout& l) { canon_ = AddressCanonicalizer(l); }
  void BeginSweep(int sweep);
  void Access(int thread, const MemRef& r) {
    if (buf_.size() == buf_.capacity()) Flush();
    if (!header_.sweep_records.empty()) {
      ++header_.sweep_records.back()[thread];
      if (r.element != AccessKind::kNone) ++header_.sweep_elements.back()[thread];
    }
    buf_.push_back(TraceRecord{
        canon_(thread, r), static_cast<uint32_t>(r.vertex), static_cast<uint8_t>(r.element),
        static_cast<uint8_t>(thread), static_cast<uint8_t>(r.size),
        static_cast<uint8_t>(static_cast<uint8_t>(r.array) | (r.write ? kStoreBit : 0))});
  }
  void Close();  // throws InputError on an I/O failure
  uint64_t records() const { return records_ + buf_.size(); }
  uint64_t elements() const {  // element touches among the records (of the marked sweeps)
    uint64_t n = 0;
    for (const auto& sweep : header_.sweep_elements)
      for (uint64_t e : sweep) n += e;
    return n;
  }

 private:
  void Flush();

  std::string path_, tmp_;
  TraceHeader header_;
  int max_iterations_;
  std::FILE* f_ = nullptr;
  std::vector<TraceRecord> buf_;
  uint64_t records_ = 0;
  bool closed_ = false;
  AddressCanonicalizer canon_;
};

// The header bytes, with room for `reserve_iterations` sweeps (TraceReader decodes them).
std::vector<char> EncodeTraceHeader(const TraceHeader& h, int reserve_iterations);

}  // namespace meshreuse
