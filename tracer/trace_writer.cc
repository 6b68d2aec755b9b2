// TraceWriter; see trace_writer.h.
#include "tracer/trace_writer.h"

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace meshreuse {

namespace {
template <class T>
void Put(std::vector<char>& b, T v) {  // little-endian on the x86/ARM hosts we build for
  const char* p = reinterpret_cast<const char*>(&v);
  b.insert(b.end(), p, p + sizeof(T));
}
void PutString(std::vector<char>& b, const std::string& s) {
  const uint16_t n = static_cast<uint16_t>(std::min<size_t>(s.size(), 65535));
  Put(b, n);
  b.insert(b.end(), s.begin(), s.begin() + n);
}
}  // namespace

std::vector<char> EncodeTraceHeader(const TraceHeader& h, int reserve_iterations) {
  std::vector<char> b(kTraceMagic, kTraceMagic + 8);
  Put(b, h.version);
  Put(b, uint32_t{0});  // header bytes, patched below
  Put(b, h.granularity);
  Put(b, h.element_bytes);
  Put(b, h.threads);
  Put(b, static_cast<uint32_t>(h.iteration_starts.size()));
  Put(b, static_cast<uint32_t>(reserve_iterations));
  Put(b, h.vertices);
  Put(b, h.records);
  for (int i = 0; i < reserve_iterations; ++i)
    Put(b, i < static_cast<int>(h.iteration_starts.size()) ? h.iteration_starts[i] : uint64_t{0});
  auto table = [&](const std::vector<std::vector<uint64_t>>& per_sweep) {
    for (int i = 0; i < reserve_iterations; ++i)
      for (uint32_t t = 0; t < h.threads; ++t)
        Put(b, i < static_cast<int>(per_sweep.size()) && t < per_sweep[i].size() ? per_sweep[i][t]
                                                                                 : uint64_t{0});
  };
  table(h.sweep_records);
  if (h.version >= 2) table(h.sweep_elements);
  PutString(b, h.mesh);
  PutString(b, h.ordering);
  while (b.size() % 16) b.push_back(0);  // records start 16-byte aligned
  const uint32_t n = static_cast<uint32_t>(b.size());
  std::memcpy(b.data() + 12, &n, 4);
  return b;
}

TraceWriter::TraceWriter(std::string path, TraceHeader header, int max_sweeps)
    : path_(std::move(path)), header_(std::move(header)), max_sweeps_(max_sweeps) {
  out_ = std::make_unique<AtomicOutput>(path_);
  buf_.reserve((1 << 20) / sizeof(TraceRecord));
}

TraceWriter::~TraceWriter() = default;

void TraceWriter::Begin(const StreamInfo& info) {
  header_.threads = static_cast<uint32_t>(info.threads);
  header_.vertices = static_cast<uint32_t>(info.vertices);
  if (static_cast<int>(header_.iteration_starts.size()) > max_sweeps_)
    max_sweeps_ = static_cast<int>(header_.iteration_starts.size());
  const std::vector<char> h = EncodeTraceHeader(header_, max_sweeps_);
  if (std::fwrite(h.data(), 1, h.size(), out_->file()) != h.size())
    throw EnvironmentError(path_, "write failed (disk full?)");
}

void TraceWriter::BeginSweep(int sweep) {
  if (sweep > max_sweeps_) return;  // only the sweeps the header has room for are marked
  header_.iteration_starts.push_back(records());
  header_.sweep_records.emplace_back(header_.threads, 0);
  header_.sweep_elements.emplace_back(header_.threads, 0);
}

void TraceWriter::Consume(const Access* a, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    const Access& r = a[i];
    if (buf_.size() == buf_.capacity()) Flush();
    if (!header_.sweep_records.empty()) {
      ++header_.sweep_records.back()[r.thread];
      if (r.element != Access::kNoElement) ++header_.sweep_elements.back()[r.thread];
    }
    buf_.push_back(TraceRecord{r.address, static_cast<uint32_t>(r.element), r.kind, r.thread,
                               static_cast<uint8_t>(r.size),
                               static_cast<uint8_t>(r.array | (r.write ? kStoreBit : 0))});
  }
}

void TraceWriter::Flush() {
  if (!buf_.empty() &&
      std::fwrite(buf_.data(), sizeof(TraceRecord), buf_.size(), out_->file()) != buf_.size())
    throw EnvironmentError(path_, "write failed (disk full?)");
  records_ += buf_.size();
  buf_.clear();
}

void TraceWriter::Close() { CloseForSet()->Rename(); }

std::unique_ptr<AtomicOutput> TraceWriter::CloseForSet() {
  Flush();
  header_.records = records_;
  if (!out_->in_place()) {  // a regular file: the final header over the placeholder
    const std::vector<char> h = EncodeTraceHeader(header_, max_sweeps_);
    if (std::fseek(out_->file(), 0, SEEK_SET) != 0 ||
        std::fwrite(h.data(), 1, h.size(), out_->file()) != h.size())
      throw EnvironmentError(path_, "write failed (disk full?)");
  }
  out_->Commit(/*defer_rename=*/true);
  return std::move(out_);
}

}  // namespace meshreuse
