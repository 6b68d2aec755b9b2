// TraceReader; see trace_reader.h.
#include "tracer/trace_reader.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "core/access.h"
#include "core/error.h"
#include "core/schedule.h"

namespace meshreuse {

namespace {
struct Cursor {
  const std::vector<char>& b;
  size_t pos;
  const std::string& path;
  template <class T>
  T Get() {
    if (pos + sizeof(T) > b.size()) throw InputError(path, 0, "truncated trace header");
    T v;
    std::memcpy(&v, b.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
};

// The rest of the header, read through a 64 KiB window: its tables can be 64 MiB of slots (room
// reserved when the file was opened), of which only the recorded sweeps are kept.
struct HeaderStream {
  InputStream& in;
  uint64_t left;  // header bytes not yet read
  const std::string& path;
  std::vector<char> buf = std::vector<char>(1 << 16);
  size_t at = 0, end = 0;
  void Fill(size_t need) {
    std::memmove(buf.data(), buf.data() + at, end - at);
    end -= at, at = 0;
    const size_t want = static_cast<size_t>(std::min<uint64_t>(buf.size() - end, left));
    const size_t got = in.Read(buf.data() + end, want);
    left -= got, end += got;
    if (end < need) throw InputError(path, 0, "truncated trace header");
  }
  template <class T>
  T Get() {
    if (end - at < sizeof(T)) Fill(sizeof(T));
    T v;
    std::memcpy(&v, buf.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  // A name, kept printable: bytes below 0x20 and 0x7F become '?', so that a hostile header
  // cannot put line breaks or escape sequences into tables, CSV or a terminal.
  std::string GetString() {
    const uint16_t n = Get<uint16_t>();
    std::string s;
    for (uint16_t i = 0; i < n; ++i) {
      const unsigned char c = Get<unsigned char>();
      s += c < 0x20 || c == 0x7F ? '?' : static_cast<char>(c);
    }
    return s;
  }
  void SkipRest() {  // the padding
    while (left > 0) {
      const size_t got =
          in.Read(buf.data(), static_cast<size_t>(std::min<uint64_t>(buf.size(), left)));
      if (got == 0) throw InputError(path, 0, "truncated trace header");
      left -= got;
    }
  }
};
}  // namespace

bool TraceReader::LooksLikeTrace(const std::string& path) {
  try {
    InputStream in(path);
    char m[8] = {};
    return in.Read(m, 8) == 8 && std::memcmp(m, kTraceMagic, 8) == 0;
  } catch (const InputError&) {
    return false;
  }
}

TraceReader::TraceReader(std::string path) : path_(std::move(path)) {
  in_ = std::make_unique<InputStream>(path_);  // owns the handle: released however this ends
  // Size unknown (a pipe, standard input, zstd frames that do not record it): the header's record
  // count is checked as the records are read, and nothing may follow the last.
  sized_ = in_->size() >= 0;
  std::vector<char> fixed(48);
  const size_t got = in_->Read(fixed.data(), fixed.size());
  if (got < 8 || std::memcmp(fixed.data(), kTraceMagic, 8) != 0)
    throw InputError(path_, 0,
                     "not a meshreuse trace (wrong magic; for other traces use --format)");
  if (got < fixed.size()) throw InputError(path_, 0, "truncated trace header");
  Cursor c{fixed, 8, path_};
  header_.version = c.Get<uint32_t>();
  if (header_.version != 1 && header_.version != kTraceVersion)
    throw InputError(path_, 0,
                     "unknown trace version " + std::to_string(header_.version) +
                         " (this reader knows versions 1 and " + std::to_string(kTraceVersion) +
                         ")");
  const uint64_t tables = header_.version >= 2 ? 2 : 1;
  const uint32_t header_bytes = c.Get<uint32_t>();
  header_.granularity = c.Get<uint32_t>();
  header_.element_bytes = c.Get<uint32_t>();
  header_.threads = c.Get<uint32_t>();
  const uint32_t iterations = c.Get<uint32_t>();
  const uint32_t slots = c.Get<uint32_t>();
  header_.vertices = c.Get<uint32_t>();
  header_.records = c.Get<uint64_t>();
  const uint64_t file_bytes = sized_ ? static_cast<uint64_t>(in_->size()) : ~uint64_t{0};
  // Every size is bounded before it is used: the header must fit in the file, its tables in the
  // header (64-bit products of 32-bit fields cannot wrap).
  if (header_bytes < 48 || header_bytes > (1u << 26))
    throw InputError(path_, 0,
                     "corrupt trace header: it claims " + std::to_string(header_bytes) +
                         " bytes (byte offset 12)");
  if (sized_ && header_bytes > file_bytes)
    throw InputError(path_, 0,
                     "truncated trace header: it claims " + std::to_string(header_bytes) +
                         " bytes (byte offset 12), the file has " + std::to_string(file_bytes));
  if (iterations > slots || header_.threads == 0 || header_.threads > 256 ||
      48 + 8ull * slots * (1 + tables * header_.threads) > header_bytes)
    throw InputError(path_, 0,
                     "corrupt trace header: " + std::to_string(iterations) + " sweeps in " +
                         std::to_string(slots) + " slots for " + std::to_string(header_.threads) +
                         " threads do not fit its " + std::to_string(header_bytes) + " bytes");
  if (header_.vertices > static_cast<uint32_t>(INT32_MAX))
    throw InputError(path_, 0,
                     "corrupt trace header: " + std::to_string(header_.vertices) +
                         " vertices (byte offset 36) exceed 32-bit vertex ids");
  if (uint64_t{iterations} * header_.threads > static_cast<uint64_t>(kMaxStreamSweeps))
    throw InputError(path_, 0,
                     "the header announces " + std::to_string(iterations) + " sweeps x " +
                         std::to_string(header_.threads) + " streams: at most " +
                         std::to_string(kMaxStreamSweeps) +
                         " (sweep, stream) pairs (each keeps per-sweep state and rows)");
  HeaderStream h{*in_, header_bytes - 48u, path_};
  for (uint32_t i = 0; i < slots; ++i) {
    const uint64_t v = h.Get<uint64_t>();
    if (i < iterations) header_.iteration_starts.push_back(v);
  }
  auto table = [&](std::vector<std::vector<uint64_t>>* per_sweep) {
    for (uint32_t i = 0; i < slots; ++i) {
      std::vector<uint64_t> per_thread(header_.threads);
      for (uint64_t& n : per_thread) n = h.Get<uint64_t>();
      if (i < iterations) per_sweep->push_back(std::move(per_thread));
    }
  };
  table(&header_.sweep_records);
  if (tables == 2)
    table(&header_.sweep_elements);
  else
    header_.sweep_elements = header_.sweep_records;  // version 1: every record is a touch
  header_.mesh = h.GetString();
  header_.ordering = h.GetString();
  h.SkipRest();
  const uint64_t body = file_bytes - header_bytes;
  // Compared by division: records * 16 could wrap for a hostile count.
  if (sized_ && (body % sizeof(TraceRecord) != 0 || body / sizeof(TraceRecord) != header_.records))
    throw InputError(path_, 0,
                     "truncated trace: the header says " + std::to_string(header_.records) +
                         " records (byte offset 40), the file holds " + std::to_string(body) +
                         " bytes of records (" + std::to_string(body / sizeof(TraceRecord)) +
                         " records" + (body % sizeof(TraceRecord) ? " and a partial one" : "") +
                         ")");
  // The per-sweep counts must add up to the records and place each sweep where it starts.
  uint64_t at = 0;
  for (uint32_t i = 0; i < iterations; ++i) {
    if (header_.iteration_starts[i] != at)
      throw InputError(path_, 0,
                       "corrupt trace header: sweep " + std::to_string(i + 1) +
                           " starts at record " + std::to_string(header_.iteration_starts[i]) +
                           ", its predecessors' counts end at " + std::to_string(at));
    for (uint32_t t = 0; t < header_.threads; ++t) {
      const uint64_t n = header_.sweep_records[i][t];
      if (n > header_.records - at || header_.sweep_elements[i][t] > n)
        throw InputError(path_, 0,
                         "corrupt trace header: sweep " + std::to_string(i + 1) + ", thread " +
                             std::to_string(t) + " claims more records than the file holds");
      at += n;
    }
  }
  if (iterations > 0 && at != header_.records)
    throw InputError(path_, 0,
                     "corrupt trace header: the sweeps hold " + std::to_string(at) +
                         " records, the header says " + std::to_string(header_.records));
  left_ = header_.records;
  end_ = header_.records;
  header_bytes_ = header_bytes;
}

TraceReader::~TraceReader() = default;

void TraceReader::Range(uint64_t first, uint64_t end) {
  if (first > end || end > header_.records)
    throw std::invalid_argument("TraceReader::Range: records out of range");
  in_->SeekTo(header_bytes_ + first * sizeof(TraceRecord));
  in_->SetLimit((end - first) * sizeof(TraceRecord));
  left_ = header_.records - first;
  end_ = end;
}

bool TraceReader::Next(std::vector<TraceRecord>* out, size_t max) {
  out->resize(std::min<uint64_t>(max, left_ - (header_.records - end_)));
  if (out->empty()) return false;
  if (in_->Read(out->data(), out->size() * sizeof(TraceRecord)) !=
      out->size() * sizeof(TraceRecord))
    throw InputError(
        path_, 0,
        "truncated trace: record " + std::to_string(header_.records - left_) + " cannot be read");
  // Each record checked, so that what reads a trace can index by thread and trust the rest.
  const uint64_t first = header_.records - left_;
  auto fail = [&](size_t i, const std::string& what) {
    throw InputError(path_, 0, "record " + std::to_string(first + i) + " " + what);
  };
  for (size_t i = 0; i < out->size(); ++i) {
    const TraceRecord& rec = (*out)[i];
    if (rec.thread >= header_.threads)
      fail(i, "has thread " + std::to_string(rec.thread) + " beyond the header's " +
                  std::to_string(header_.threads));
    if (rec.kind > static_cast<uint8_t>(AccessKind::kNone))
      fail(i, "has kind " + std::to_string(rec.kind) + " (kinds are 0-3)");
    if (rec.address >= ~uint64_t{0} - std::max<uint64_t>(rec.size, 1) + 1)
      fail(i, "runs into the last byte of the 64-bit address space, which the analyzer reserves");
  }
  left_ -= out->size();
  if (left_ == 0 && !sized_ && end_ == header_.records) {
    char extra;
    if (in_->Read(&extra, 1) == 1)
      throw InputError(path_, 0,
                       "more bytes after the " + std::to_string(header_.records) +
                           " records the header announces (byte offset 40)");
  }
  return true;
}

}  // namespace meshreuse
