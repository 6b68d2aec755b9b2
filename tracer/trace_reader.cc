// TraceReader; see trace_reader.h.
#include "tracer/trace_reader.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

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
  std::string GetString() {
    const uint16_t n = Get<uint16_t>();
    if (pos + n > b.size()) throw InputError(path, 0, "truncated trace header");
    std::string s(b.data() + pos, n);
    pos += n;
    return s;
  }
};
}  // namespace

bool TraceReader::LooksLikeTrace(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  char m[8] = {};
  const bool ok = std::fread(m, 1, 8, f) == 8 && std::memcmp(m, kTraceMagic, 8) == 0;
  std::fclose(f);
  return ok;
}

TraceReader::TraceReader(std::string path) : path_(std::move(path)) {
  f_ = std::fopen(path_.c_str(), "rb");
  if (!f_) throw InputError(path_, 0, std::string("cannot open: ") + std::strerror(errno));
  std::vector<char> fixed(48);
  const size_t got = std::fread(fixed.data(), 1, fixed.size(), f_);
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
  if (header_bytes < 48 || header_bytes > (1u << 26) || iterations > slots ||
      header_.threads == 0 || header_.threads > 256 ||
      48 + 8ull * slots * (1 + tables * header_.threads) > header_bytes)
    throw InputError(path_, 0, "corrupt trace header");
  std::vector<char> all(header_bytes);
  std::memcpy(all.data(), fixed.data(), 48);
  if (std::fread(all.data() + 48, 1, header_bytes - 48, f_) != header_bytes - 48)
    throw InputError(path_, 0, "truncated trace header");
  Cursor h{all, 48, path_};
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
  struct stat st {};
  if (::fstat(::fileno(f_), &st) != 0) throw InputError(path_, 0, "cannot stat");
  const uint64_t body = static_cast<uint64_t>(st.st_size) - header_bytes;
  if (body != header_.records * sizeof(TraceRecord))
    throw InputError(path_, 0,
                     "truncated trace: the header says " + std::to_string(header_.records) +
                         " records (" + std::to_string(header_.records * sizeof(TraceRecord)) +
                         " bytes), the file holds " + std::to_string(body) + " bytes of records");
  left_ = header_.records;
}

TraceReader::~TraceReader() {
  if (f_) std::fclose(f_);
}

bool TraceReader::Next(std::vector<TraceRecord>* out, size_t max) {
  out->resize(std::min<uint64_t>(max, left_));
  if (out->empty()) return false;
  if (std::fread(out->data(), sizeof(TraceRecord), out->size(), f_) != out->size())
    throw InputError(path_, 0, "truncated trace (read failed)");
  left_ -= out->size();
  return true;
}

}  // namespace meshreuse
