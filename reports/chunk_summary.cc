// Chunk summaries, their file format, the chunk run and the merge; see chunk_summary.h.
#include "reports/chunk_summary.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>

#include "analysis/streamed_chain.h"
#include "core/access.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/mix.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/smoother.h"
#include "reports/inputs.h"
#include "reports/run_info.h"
#include "tracer/foreign_trace.h"
#include "tracer/trace_formats.h"
#include "tracer/trace_reader.h"

namespace meshreuse {

namespace {

constexpr char kMagic[8] = {'M', 'R', 'S', 'U', 'M', 'R', 'Y', '\0'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 32;

// A 64-bit checksum of bytes, 8 at a time (detects corruption; not cryptographic).
uint64_t Checksum(const char* p, size_t n) {
  uint64_t h = 0x9E3779B97F4A7C15ull ^ n;
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = Mix64(h ^ w) + i;
  }
  uint64_t w = 0;
  if (n > i) std::memcpy(&w, p + i, n - i);
  return Mix64(h ^ w ^ (n - i));
}

// Checksum over bytes that arrive in pieces: equal to Checksum of their concatenation (`n`, the
// total, is known before the first piece: the header announces it).
class ChecksumStream {
 public:
  explicit ChecksumStream(uint64_t n) : h_(0x9E3779B97F4A7C15ull ^ n) {}
  void Add(const char* p, size_t n) {
    if (held_) {  // complete a word begun by the last piece
      const size_t k = std::min(8 - held_, n);
      std::memcpy(buf_ + held_, p, k);
      held_ += k, p += k, n -= k;
      if (held_ < 8) return;
      Word(buf_), held_ = 0;
    }
    for (; n >= 8; p += 8, n -= 8) Word(p);
    std::memcpy(buf_, p, n);
    held_ = n;
  }
  uint64_t Finish() const {
    uint64_t w = 0;
    if (held_) std::memcpy(&w, buf_, held_);
    return Mix64(h_ ^ w ^ held_);
  }

 private:
  void Word(const char* p) {
    uint64_t w;
    std::memcpy(&w, p, 8);
    h_ = Mix64(h_ ^ w) + i_;
    i_ += 8;
  }
  uint64_t h_, i_ = 0;
  char buf_[8] = {};
  size_t held_ = 0;
};

// Serialises into a sink through a 64 KiB buffer (arrays go straight through), so a summary is
// encoded without a second copy of it in memory.
class Writer {
 public:
  using Sink = std::function<void(const char*, size_t)>;
  explicit Writer(Sink sink) : sink_(std::move(sink)) { buf_.reserve(kBuffer); }
  ~Writer() = default;
  template <class T>
  void Put(T v) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values");
    Bytes(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void Str(const std::string& s) {
    Put<uint64_t>(s.size());
    Bytes(s.data(), s.size());
  }
  void U64s(const std::vector<uint64_t>& v) {
    Put<uint64_t>(v.size());
    Bytes(reinterpret_cast<const char*>(v.data()), v.size() * 8);
  }
  void Flush() {
    if (!buf_.empty()) sink_(buf_.data(), buf_.size());
    buf_.clear();
  }

 private:
  static constexpr size_t kBuffer = size_t{1} << 16;
  void Bytes(const char* p, size_t n) {
    if (n == 0) return;
    if (buf_.size() + n <= kBuffer) {
      buf_.insert(buf_.end(), p, p + n);
      return;
    }
    Flush();
    if (n >= kBuffer)
      sink_(p, n);
    else
      buf_.insert(buf_.end(), p, p + n);
  }
  Sink sink_;
  std::vector<char> buf_;
};

// Parses a payload of `n` bytes from memory or, streamed, from a file (ReadSummary): then every
// byte consumed goes through the checksum, which the caller compares once the parse is done.
class Reader {
 public:
  Reader(const std::string& path, const char* p, size_t n) : path_(path), p_(p), n_(n), sum_(n) {}
  Reader(const std::string& path, InputFile* f, size_t n) : path_(path), f_(f), n_(n), sum_(n) {}
  template <class T>
  T Get() {
    Need(sizeof(T), "a value");
    T v;
    Read(&v, sizeof v);
    return v;
  }
  uint64_t Count(uint64_t each, const char* what) {  // a count of items of `each` bytes
    const uint64_t n = Get<uint64_t>();
    if (each && n > (n_ - at_) / each)
      Fail(std::string("corrupt: ") + what + " count " + std::to_string(n) +
           " exceeds the bytes left");
    return n;
  }
  std::string Str() {
    const uint64_t n = Count(1, "string");
    std::string s(n, '\0');
    if (n) Read(&s[0], n);
    return s;
  }
  std::vector<uint64_t> U64s(const char* what) {
    const uint64_t n = Count(8, what);
    std::vector<uint64_t> v(n);
    if (n) Read(v.data(), n * 8);
    return v;
  }
  bool done() const { return at_ == n_; }
  // Streamed: reads what the parse left (after a failure) so the checksum covers the payload;
  // short only when the file is.
  void Drain() {
    char b[1 << 16];
    while (f_ && at_ < n_) {
      const size_t got = f_->Read(b, std::min<size_t>(sizeof b, n_ - at_));
      if (got == 0) return;
      sum_.Add(b, got);
      at_ += got;
    }
  }
  uint64_t Checksum() const { return sum_.Finish(); }  // of the bytes streamed so far
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(path_, 0, what + " (payload byte " + std::to_string(at_) + ")");
  }

 private:
  void Need(size_t k, const char* what) {
    if (n_ - at_ < k) Fail(std::string("corrupt: ") + what + " runs past the end");
  }
  void Read(void* dst, size_t k) {
    if (!f_) {
      std::memcpy(dst, p_ + at_, k);
    } else {
      if (f_->Read(dst, k) != k) Fail("truncated summary: the file ends inside its payload");
      sum_.Add(static_cast<const char*>(dst), k);
    }
    at_ += k;
  }
  const std::string& path_;
  const char* p_ = nullptr;
  InputFile* f_ = nullptr;
  size_t n_, at_ = 0;
  ChecksumStream sum_;
};

void PutInfo(Writer& w, const StreamInfo& i) {
  w.Str(i.ordering);
  w.Put<uint32_t>(static_cast<uint32_t>(i.threads));
  w.Put<int64_t>(i.vertices);
  w.Put<uint32_t>(i.element_bytes);
  w.Put<uint32_t>(i.canonical);
  w.Put<uint64_t>(i.records);
  w.Put<uint64_t>(i.sweep_records.size());
  for (const auto& s : i.sweep_records) w.U64s(s);
  w.Put<uint64_t>(i.sweep_elements.size());  // none for Jacobi meshes (not known up front)
  for (const auto& s : i.sweep_elements) w.U64s(s);
}

StreamInfo GetInfo(Reader& r) {
  StreamInfo i;
  i.ordering = r.Str();
  const uint32_t threads = r.Get<uint32_t>();
  if (threads < 1 || threads > static_cast<uint32_t>(kMaxThreads))
    r.Fail("corrupt: " + std::to_string(threads) + " threads");
  i.threads = static_cast<int>(threads);
  i.vertices = r.Get<int64_t>();
  i.element_bytes = r.Get<uint32_t>();
  i.canonical = r.Get<uint32_t>() != 0;
  i.records = r.Get<uint64_t>();
  for (auto* table : {&i.sweep_records, &i.sweep_elements}) {
    const uint64_t sweeps = r.Count(8, "sweep");
    for (uint64_t k = 0; k < sweeps; ++k) {
      table->push_back(r.U64s("sweep table"));
      if (table->back().size() != threads)
        r.Fail("corrupt: a sweep table does not have one entry per thread");
    }
  }
  if (!i.sweep_elements.empty() && i.sweep_elements.size() != i.sweep_records.size())
    r.Fail("corrupt: the sweep tables differ in length");
  return i;
}

// The input's size and a hash of its first and last 64 KiB: ties summaries to one trace file
// without reading it all (a copy elsewhere, under another name, is the same trace).
uint64_t Fingerprint(const std::string& path, uint64_t* bytes) {
  InputFile f(path);
  if (f.size() < 0) throw InputError(path, 0, "a chunk needs a regular file (not a pipe)");
  *bytes = static_cast<uint64_t>(f.size());
  std::vector<char> b(std::min<uint64_t>(*bytes, 1 << 16));
  const size_t head = f.Read(b.data(), b.size());
  uint64_t h = Checksum(b.data(), head);
  if (*bytes > b.size()) {
    if (fseeko(f.get(), static_cast<off_t>(*bytes - b.size()), SEEK_SET) != 0)
      throw InputError(path, 0, "cannot seek");
    const size_t tail = f.Read(b.data(), b.size());
    h = Mix64(h ^ Checksum(b.data(), tail));
  }
  return h;
}

// A laid-out mesh's content hash (coordinates and triangles) and its size in bytes: ties the
// chunks of one mesh analysis together whatever file or copy each run read.
uint64_t MeshFingerprint(const Mesh& m, uint64_t* bytes) {
  const size_t xy = m.xy.size() * sizeof(double), tri = m.tri.size() * sizeof(int32_t);
  *bytes = xy + tri;
  return Mix64(Checksum(reinterpret_cast<const char*>(m.xy.data()), xy) ^
               Checksum(reinterpret_cast<const char*>(m.tri.data()), tri) * 3);
}

std::string ChunkName(uint32_t r, uint32_t p) {
  return std::to_string(r) + "/" + std::to_string(p);
}

}  // namespace

uint64_t SummaryChecksum(const char* payload, size_t n) { return Checksum(payload, n); }

bool SummaryIdentity::operator==(const SummaryIdentity& o) const {
  return format == o.format && input_bytes == o.input_bytes && fingerprint == o.fingerprint &&
         granularity == o.granularity && line_bytes == o.line_bytes &&
         instructions == o.instructions && chunks == o.chunks && exact == o.exact &&
         sample == o.sample && rate == o.rate && seed == o.seed;
}

std::pair<uint32_t, uint32_t> ParseChunk(const std::string& s) {
  const size_t slash = s.find('/');
  auto num = [&](const std::string& x) -> uint64_t {
    if (x.empty() || x.size() > 9 || x.find_first_not_of("0123456789") != std::string::npos)
      throw UsageError("--chunk '" + s + "': expected r/P with 0 <= r < P (e.g. 3/8)");
    return std::stoull(x);
  };
  if (slash == std::string::npos)
    throw UsageError("--chunk '" + s + "': expected r/P with 0 <= r < P (e.g. 3/8)");
  const uint64_t r = num(s.substr(0, slash)), p = num(s.substr(slash + 1));
  if (p < 1 || p > (1u << 20) || r >= p)
    throw UsageError("--chunk '" + s + "': expected 0 <= r < P <= 1048576");
  return {static_cast<uint32_t>(r), static_cast<uint32_t>(p)};
}

namespace {

// The payload, in the order DecodeSummary reads it.
void EncodePayload(const SummaryFile& s, Writer& w) {
  w.Str(s.id.format);
  w.Put<uint64_t>(s.id.input_bytes);
  w.Put<uint64_t>(s.id.fingerprint);
  w.Put<uint32_t>(s.id.granularity);
  w.Put<uint32_t>(s.id.line_bytes);
  w.Put<uint32_t>(s.id.instructions);
  w.Put<uint32_t>(s.id.chunks);
  w.Put<uint32_t>(s.id.exact);
  w.Put<uint32_t>(s.id.sample);
  w.Put<double>(s.id.rate);
  w.Put<uint64_t>(s.id.seed);
  w.Str(s.input);
  w.Put<uint32_t>(s.chunk);
  w.Put<uint64_t>(s.first);
  w.Put<uint64_t>(s.end);
  w.Put<uint64_t>(s.total);
  PutInfo(w, s.info);
  w.U64s(s.moves);
  w.Put<uint64_t>(s.streams.size());
  for (const StreamSummary& x : s.streams) {
    w.Put<uint32_t>(x.thread);
    w.Put<uint32_t>(static_cast<uint32_t>(x.granularity));
    w.Put<uint32_t>(x.resolved ? (x.hist_apart ? 2 : 1) : 0);
    w.Put<uint32_t>(x.sampled);
    w.Put<uint64_t>(x.stream_accesses);
    w.Put<uint64_t>(x.accesses);
    w.Put<uint64_t>(x.offset);
    w.U64s(x.chunk.first_ids);
    w.U64s(x.chunk.first_positions);
    w.U64s(x.chunk.stack);
    w.Put<uint64_t>(x.hist.size());
    for (const auto& [d, n] : x.hist) w.Put<uint64_t>(d), w.Put<uint64_t>(n);
    w.Put<uint64_t>(x.profile.size());
    for (const StreamSummary::Step& st : x.profile) {
      w.Put<uint64_t>(st.index), w.Put<uint64_t>(st.accesses), w.Put<uint64_t>(st.cold);
      w.Put<uint64_t>(static_cast<uint64_t>(st.sum));
      w.Put<uint64_t>(static_cast<uint64_t>(st.sum >> 64));
    }
  }
  w.Flush();
}

void PutHeader(char* h, uint64_t bytes, uint64_t sum) {
  std::memcpy(h, kMagic, 8);
  const uint32_t version = kVersion;
  std::memset(h + 8, 0, kHeaderBytes - 8);
  std::memcpy(h + 8, &version, 4);
  std::memcpy(h + 16, &bytes, 8);
  std::memcpy(h + 24, &sum, 8);
}

}  // namespace

std::string EncodeSummary(const SummaryFile& s) {
  std::string out(kHeaderBytes, '\0');  // the payload goes straight in after it
  Writer w([&out](const char* p, size_t n) { out.append(p, n); });
  EncodePayload(s, w);
  const uint64_t bytes = out.size() - kHeaderBytes;
  PutHeader(&out[0], bytes, Checksum(out.data() + kHeaderBytes, bytes));
  return out;
}

void WriteSummary(const std::string& path, const SummaryFile& s) {
  // Streamed, never the whole payload in memory beside the summary: one pass for its size, one
  // for its checksum (the header holds both, ahead of the payload), one to write it.
  uint64_t bytes = 0;
  {
    Writer w([&bytes](const char*, size_t n) { bytes += n; });
    EncodePayload(s, w);
  }
  ChecksumStream sum(bytes);
  {
    Writer w([&sum](const char* p, size_t n) { sum.Add(p, n); });
    EncodePayload(s, w);
  }
  char header[kHeaderBytes];
  PutHeader(header, bytes, sum.Finish());
  WriteAtomically(path, [&](std::FILE* f) {
    auto put = [&](const char* p, size_t n) {
      if (std::fwrite(p, 1, n, f) != n) throw EnvironmentError(path, std::strerror(errno));
    };
    put(header, kHeaderBytes);
    Writer w(put);
    EncodePayload(s, w);
  });
}

namespace {

// The header's checks (magic, version); its payload size and checksum.
void CheckHeader(const std::string& path, const char* head, size_t got, uint64_t* bytes,
                 uint64_t* sum) {
  if (got < 8 || std::memcmp(head, kMagic, 8) != 0)
    throw InputError(path, 0,
                     "not a chunk summary (no MRSUMRY magic): give the files that "
                     "`analyze --chunk r/P --summary-out` wrote");
  if (got < kHeaderBytes) throw InputError(path, 0, "truncated summary: the header is cut short");
  uint32_t version;
  std::memcpy(&version, head + 8, 4);
  std::memcpy(bytes, head + 16, 8);
  std::memcpy(sum, head + 24, 8);
  if (version != kVersion)
    throw InputError(path, 0,
                     "summary version " + std::to_string(version) + " (this build reads " +
                         std::to_string(kVersion) + ")");
}

[[noreturn]] void SizeMismatch(const std::string& path, uint64_t announced, uint64_t held) {
  throw InputError(path, 0,
                   "truncated or extended summary: the header announces " +
                       std::to_string(announced) + " payload bytes, the file holds " +
                       std::to_string(held));
}

[[noreturn]] void ChecksumMismatch(const std::string& path) {
  throw InputError(path, 0, "corrupt summary: the checksum does not match its contents");
}

// The payload's fields, checked as they come (see EncodePayload).
SummaryFile ParsePayload(Reader& r, bool from_rank) {
  SummaryFile s;
  s.id.format = r.Str();
  s.id.input_bytes = r.Get<uint64_t>();
  s.id.fingerprint = r.Get<uint64_t>();
  s.id.granularity = r.Get<uint32_t>();
  s.id.line_bytes = r.Get<uint32_t>();
  s.id.instructions = r.Get<uint32_t>();
  s.id.chunks = r.Get<uint32_t>();
  s.id.exact = r.Get<uint32_t>();
  s.id.sample = r.Get<uint32_t>();
  s.id.rate = r.Get<double>();
  s.id.seed = r.Get<uint64_t>();
  if (s.id.exact > 1 || s.id.sample > 1 || (!s.id.exact && !s.id.sample) ||
      (s.id.sample && !(s.id.rate > 0 && s.id.rate <= 1)))
    r.Fail("corrupt: sampling options");
  s.input = r.Str();
  s.chunk = r.Get<uint32_t>();
  s.first = r.Get<uint64_t>();
  s.end = r.Get<uint64_t>();
  s.total = r.Get<uint64_t>();
  if (s.id.chunks < 1 || s.chunk >= s.id.chunks || s.first > s.end || s.end > s.total)
    r.Fail("corrupt: chunk " + ChunkName(s.chunk, s.id.chunks));
  if (s.id.granularity < 1 || s.id.granularity > 3 || s.id.line_bytes == 0 ||
      (s.id.line_bytes & (s.id.line_bytes - 1)))
    r.Fail("corrupt: analysis options");
  s.info = GetInfo(r);
  s.moves = r.U64s("moves");
  if (s.moves.size() != static_cast<size_t>(s.info.threads)) r.Fail("corrupt: moves per thread");
  const uint64_t n = r.Count(32, "stream");
  for (uint64_t k = 0; k < n; ++k) {
    StreamSummary x;
    x.thread = r.Get<uint32_t>();
    const uint32_t g = r.Get<uint32_t>();
    if (x.thread >= static_cast<uint32_t>(s.info.threads) || (g != 1 && g != 2))
      r.Fail("corrupt: a stream's thread or granularity");
    x.granularity = static_cast<Granularity>(g);
    const uint32_t resolved = r.Get<uint32_t>();
    if (resolved > 2) r.Fail("corrupt: a stream's flags");
    // Resolved streams travel only between ranks: their distances reach back before the chunk,
    // so nothing in a file bounds them (a file could claim any, and the merge allocate for it).
    if (resolved && !from_rank) r.Fail("a rank's resolved message, not a chunk summary");
    x.resolved = resolved != 0;
    x.hist_apart = resolved == 2;
    const uint32_t sampled = r.Get<uint32_t>();
    if (sampled > 1 || (sampled && !s.id.sample) || (!sampled && !s.id.exact))
      r.Fail("corrupt: a stream's sampling flag");
    x.sampled = sampled;
    x.stream_accesses = r.Get<uint64_t>();
    x.accesses = r.Get<uint64_t>();
    x.offset = r.Get<uint64_t>();
    x.chunk.first_ids = r.U64s("first touch");
    x.chunk.first_positions = r.U64s("first touch");
    x.chunk.stack = r.U64s("stack");
    const size_t f = x.chunk.first_ids.size();
    if (x.chunk.first_positions.size() != f || x.chunk.stack.size() != f)
      r.Fail("corrupt: a stream's first touches and stack differ in length");
    if (x.resolved && f) r.Fail("corrupt: a resolved stream with first touches");
    for (size_t i = 0; i < f; ++i)
      if (x.chunk.first_positions[i] >= x.accesses ||
          (i && x.chunk.first_positions[i] <= x.chunk.first_positions[i - 1]))
        r.Fail("corrupt: first-touch places out of order");
    const uint64_t h = r.Count(16, "histogram");
    if (x.hist_apart && h) r.Fail("corrupt: a histogram sent apart, and here");
    uint64_t counted = f;
    for (uint64_t i = 0; i < h; ++i) {
      const uint64_t d = r.Get<uint64_t>(), c = r.Get<uint64_t>();
      // Inside a chunk a distance is below its distinct ids (the first touches), so a corrupt
      // distance cannot make the merge allocate beyond what the file holds; resolved, below the
      // stream's accesses up to the chunk's end.
      const uint64_t bound = x.resolved ? x.offset + x.accesses : f;
      if ((d >= bound && !(x.resolved && d == StackDistance::kCold)) || c > x.accesses - counted)
        r.Fail("corrupt: histogram entry");
      counted += c;
      x.hist.emplace_back(d, c);
    }
    if (counted != x.accesses && !x.hist_apart)
      r.Fail("corrupt: the histogram does not add up to the accesses");
    const uint64_t ps = r.Count(40, "profile step");
    for (uint64_t i = 0; i < ps; ++i) {
      StreamSummary::Step st;
      st.index = r.Get<uint64_t>(), st.accesses = r.Get<uint64_t>(), st.cold = r.Get<uint64_t>();
      const uint64_t lo = r.Get<uint64_t>(), hi = r.Get<uint64_t>();
      st.sum = (static_cast<unsigned __int128>(hi) << 64) | lo;
      x.profile.push_back(st);
    }
    s.streams.push_back(std::move(x));
  }
  if (!r.done()) r.Fail("corrupt: bytes after the last stream");
  return s;
}

}  // namespace

SummaryFile ReadSummary(const std::string& path) {
  // A regular file is streamed: parsed as it is read, never held whole beside what it decodes to;
  // the checksum, computed on the way, is compared once the parse is done (and, when the parse
  // fails, over the rest of the payload first, so a damaged file is reported as damaged). Its
  // size, checked against the header first, bounds every count. A pipe has no size to check: it
  // is read whole, so a header's claim never sizes an allocation beyond the bytes that came.
  InputFile f(path);
  if (f.size() > (int64_t{1} << 40)) throw InputError(path, 0, "not a chunk summary: too large");
  if (f.size() < 0) {
    std::string b;
    char buf[1 << 16];
    for (size_t n; (n = f.Read(buf, sizeof buf)) > 0;) {
      b.append(buf, n);
      if (b.size() > (size_t{1} << 40)) throw InputError(path, 0, "not a chunk summary: too large");
    }
    return DecodeSummary(path, b);
  }
  char head[kHeaderBytes];
  const size_t got = f.Read(head, kHeaderBytes);
  uint64_t bytes = 0, sum = 0;
  CheckHeader(path, head, got, &bytes, &sum);
  if (bytes != static_cast<uint64_t>(f.size()) - kHeaderBytes)
    SizeMismatch(path, bytes, static_cast<uint64_t>(f.size()) - kHeaderBytes);
  Reader r(path, &f, bytes);
  SummaryFile s;
  try {
    s = ParsePayload(r, false);
  } catch (const InputError&) {
    r.Drain();
    if (r.done() && r.Checksum() != sum) ChecksumMismatch(path);
    throw;
  }
  if (r.Checksum() != sum) ChecksumMismatch(path);
  return s;
}

SummaryFile DecodeSummary(const std::string& path, const std::string& file, bool from_rank) {
  uint64_t bytes = 0, sum = 0;
  CheckHeader(path, file.data(), std::min<size_t>(file.size(), kHeaderBytes), &bytes, &sum);
  if (bytes != file.size() - kHeaderBytes) SizeMismatch(path, bytes, file.size() - kHeaderBytes);
  const char* payload = file.data() + kHeaderBytes;
  if (Checksum(payload, bytes) != sum) ChecksumMismatch(path);
  Reader r(path, payload, bytes);
  return ParsePayload(r, from_rank);
}

namespace {

// Where records [0, first) leave each thread's element and line streams: whole sweeps from the
// header's tables, the sweep the chunk starts in by reading it up to `first`. Lines assume that no
// access before that sweep straddles two lines (the merge checks).
void TraceOffsets(const std::string& path, uint64_t first, uint32_t line_bytes,
                  std::vector<uint64_t>* element, std::vector<uint64_t>* line) {
  TraceReader r(path);
  const TraceHeader& h = r.header();
  element->assign(h.threads, 0);
  line->assign(h.threads, 0);
  uint64_t from = 0;
  for (size_t i = 0; i < h.iteration_starts.size() && h.iteration_starts[i] <= first; ++i) {
    if (i > 0)
      for (uint32_t t = 0; t < h.threads; ++t)
        (*element)[t] += h.sweep_elements[i - 1][t], (*line)[t] += h.sweep_records[i - 1][t];
    from = h.iteration_starts[i];
  }
  if (from == first) return;
  r.Range(from, first);
  const int shift = __builtin_ctz(line_bytes);
  std::vector<TraceRecord> batch;
  while (r.Next(&batch)) {
    for (const TraceRecord& rec : batch) {
      if (rec.kind < kElementKinds) ++(*element)[rec.thread];
      const uint64_t a = rec.address, b = a + (rec.size ? rec.size - 1 : 0);
      (*line)[rec.thread] += (a >> shift) == (b >> shift) ? 1 : 2;
    }
  }
}

}  // namespace

// What every summary of one analysis shares besides the input: the analysis' options.
void SetAnalysis(const AnalyzeConfig& cfg, Granularity g, SummaryFile* s) {
  s->id.granularity = static_cast<uint32_t>(g);
  s->id.line_bytes = cfg.line_bytes;
  s->id.exact = !cfg.sample || cfg.sample_error;
  s->id.sample = cfg.sample;
  s->id.rate = cfg.sample ? cfg.shards.rate : 0;
  s->id.seed = cfg.sample ? cfg.shards.seed : 0;
}

MeshChunkSweeps SweepsOfMeshChunk(const StreamInfo& whole, UpdateMode mode, uint64_t first,
                                  uint64_t end) {
  MeshChunkSweeps run;
  if (first >= end || whole.sweep_records.empty()) return run;  // nothing to regenerate
  uint64_t per_sweep = 0;
  for (uint64_t n : whole.sweep_records[0]) per_sweep += n;
  if (per_sweep == 0) return run;
  run.from = static_cast<int>(first / per_sweep) + 1;
  run.to = static_cast<int>((end - 1) / per_sweep) + 1;
  if (mode == UpdateMode::kJacobi && run.from % 2 == 0) --run.from;
  run.skipped = static_cast<uint64_t>(run.from - 1) * per_sweep;
  return run;
}

// Chunk r of P of `total` records (or bytes): [total r / P, total (r + 1) / P).
void Cut(uint64_t total, uint32_t r, uint32_t p, SummaryFile* s) {
  using U = unsigned __int128;
  s->first = static_cast<uint64_t>(U{total} * r / p);
  s->end = static_cast<uint64_t>(U{total} * (r + 1) / p);
  s->total = total;
}

ReuseOptions ChunkOptions(const AnalyzeConfig& cfg, const SummaryFile& s) {
  ReuseOptions o;
  o.granularity = static_cast<Granularity>(s.id.granularity);
  o.line_bytes = cfg.line_bytes;
  // A summary file holds a profile and the first touches' places whatever this run writes (its
  // merge may write a profile); a distributed run computes them only for a profile it writes.
  o.profile = cfg.profile || !cfg.transport;
  o.chunk = true;
  o.chunk_positions = !cfg.transport;
  o.exact = s.id.exact;
  o.sample = s.id.sample;
  o.shards = cfg.shards;
  return o;
}

// The chunk's summary entries from its analysis (the exact chunk and the sampled ids' chunk of
// each stream); the first touches are moved out of the analysis, not copied. The last chunk of a
// distributed run passes its stack to no one: `stack` false leaves it out.
void Collect(ReuseAnalysis& a, SummaryFile* out, bool stack) {
  SummaryFile& s = *out;
  s.info = a.info();
  s.info.input.clear();
  for (int t = 0; t < a.threads(); ++t) {
    s.moves.push_back(a.moves(t));
    for (Granularity sg : {Granularity::kElement, Granularity::kLine}) {
      if (!a.stream(t, sg)) continue;
      StreamAnalysis* x = &a.MakeStream(t, sg);  // the same stream: its lists are moved out
      const uint64_t stream_accesses = x->exact ? x->sd.accesses() : x->added;
      // The exact chunk, and the sampled ids' chunk: one entry each.
      for (StreamAnalysis* y : {x->exact ? x : nullptr, x->sampled_chunk.get()}) {
        if (!y) continue;
        StreamSummary ss;
        ss.thread = static_cast<uint32_t>(t);
        ss.granularity = sg;
        ss.sampled = y != x;
        ss.accesses = y->sd.accesses();
        ss.stream_accesses = stream_accesses;
        ss.offset = ss.sampled ? 0 : x->offset;
        ss.chunk.first_ids = std::move(y->first_ids);
        ss.chunk.first_positions = std::move(y->first_positions);
        if (stack) ss.chunk.stack = y->sd.StackBottomUp();
        y->sd = StackDistance();  // its memory, free for what follows
        size_t pairs = 0;  // counted first: 16 MB of pairs at 10^6 distances, grown, touched 32
        y->hist.ForEach([&pairs](uint64_t, uint64_t) { ++pairs; });
        ss.hist.reserve(pairs);
        y->hist.ForEach([&](uint64_t d, uint64_t n) { ss.hist.emplace_back(d, n); });
        const auto& steps = y->profile.steps();
        for (size_t i = 0; i < steps.size(); ++i)
          if (steps[i].accesses)
            ss.profile.push_back({i, steps[i].accesses, steps[i].cold, steps[i].sum});
        s.streams.push_back(std::move(ss));
      }
    }
  }
}

// Passes records [first, end) of a stream on to `to`, counting where the records before them
// leave each thread's element and line streams (the chunk's profile offsets, set on `to` before
// its first access). The stream fed to it may begin after record 0: `skipped` records, which left
// the streams at `element` and `line`, come before it. `to` begins with `whole`, the info of the
// stream from record 0. Records after `end` are dropped (the smoother finishes its last sweep).
class RangeGate : public AccessConsumer {
 public:
  RangeGate(ReuseAnalysis& to, const StreamInfo& whole, uint64_t first, uint64_t end,
            uint32_t line_bytes, uint64_t skipped, std::vector<uint64_t> element,
            std::vector<uint64_t> line)
      : to_(to),
        whole_(whole),
        first_(first),
        end_(end),
        seen_(skipped),
        shift_(__builtin_ctz(line_bytes)),
        element_(std::move(element)),
        line_(std::move(line)) {}
  void Begin(const StreamInfo&) override {
    to_.Begin(whole_);
    element_.resize(whole_.threads, 0);
    line_.resize(whole_.threads, 0);
  }
  void Consume(const Access* a, size_t n) override {
    size_t i = 0;
    for (; i < n && seen_ + i < first_; ++i) {
      const Access& x = a[i];
      if (x.element != Access::kNoElement) ++element_[x.thread];
      const uint64_t b = x.address + (x.size ? x.size - 1 : 0);
      line_[x.thread] += (x.address >> shift_) == (b >> shift_) ? 1 : 2;
    }
    if (i < n && seen_ + i < end_) {
      if (!started_) to_.SetStreamOffsets(element_, line_), started_ = true;
      const size_t k = static_cast<size_t>(std::min<uint64_t>(n, end_ - seen_));
      to_.Consume(a + i, k - i);
    }
    seen_ += n;
  }

 private:
  ReuseAnalysis& to_;
  const StreamInfo& whole_;
  uint64_t first_, end_, seen_;
  int shift_;
  bool started_ = false;
  std::vector<uint64_t> element_, line_;
};

// A chunk of the access stream of a mesh smoothed in the analysis' order: records [N r/P,
// N (r+1)/P) of what `meshreuse trace MESH` would write, regenerated without a file (the stream
// depends on topology and canonical addresses only). Every sweep makes the same accesses, but for
// Jacobi's two buffers, which alternate (sweep s touches what sweep s - 2 touched): so the rank
// runs the traced smoother from the sweep its range starts in (one earlier for an even Jacobi
// sweep) to the one it ends in, at most one sweep more than its range, and counts the sweeps
// before by their closed forms (AccessesPerSweep; one line per access, since no access of the
// smoother straddles two lines: the merge checks each chunk's offset).
SummaryFile SummarizeMeshChunk(const AnalyzeConfig& cfg, uint32_t r, uint32_t p, const Log& log) {
  const std::string& in = cfg.inputs[0];
  const std::string& ord = cfg.orderings[0];
  Mesh m = LayOut(in, ord, cfg.seed, cfg.triangle_order, log);
  const SmoothOptions sweeps = AnalyzeSweeps(cfg);
  SummaryFile s;
  s.input = in;
  s.chunk = r;
  s.id.chunks = p;
  s.id.format = "mesh " + ParseOrderingSpec(ord).label + " seed " + std::to_string(cfg.seed) +
                " sweeps " + std::to_string(cfg.iterations) + " threads " +
                std::to_string(cfg.threads) + " " + UpdateModeName(cfg.mode) + " " +
                TriangleOrderName(cfg.triangle_order);
  s.id.fingerprint = MeshFingerprint(m, &s.id.input_bytes);
  SetAnalysis(cfg, cfg.granularity ? *cfg.granularity : Granularity::kBoth, &s);
  StreamInfo whole = MeshStreamInfo(m, sweeps);
  whole.input = in;
  whole.ordering = ParseOrderingSpec(ord).label;
  const uint64_t total = whole.records;
  Cut(total, r, p, &s);
  const MeshChunkSweeps run = SweepsOfMeshChunk(whole, sweeps.mode, s.first, s.end);
  const std::vector<uint64_t> elements = AccessesPerSweep(m, whole.threads, sweeps.mode);
  std::vector<uint64_t> element_before(whole.threads), line_before(whole.threads);
  const uint64_t before = static_cast<uint64_t>(run.from - 1);
  for (int t = 0; t < whole.threads && before > 0; ++t)
    element_before[t] = before * elements[t], line_before[t] = before * whole.sweep_records[0][t];
  ReuseAnalysis a(ChunkOptions(cfg, s));
  RangeGate gate(a, whole, s.first, s.end, cfg.line_bytes, run.skipped, element_before,
                 line_before);
  log.Say("analysing chunk " + ChunkName(r, p) + " of " + in + " in " + ord + " order: records " +
          std::to_string(s.first) + ".." + std::to_string(s.end) + " of " + std::to_string(total) +
          " (regenerated by the traced smoother, sweeps " + std::to_string(run.from) + ".." +
          std::to_string(run.to) + " of " + std::to_string(sweeps.max_iters) + ")");
  SmoothOptions part = sweeps;
  part.max_iters = run.to - run.from + 1;
  StreamMesh(m, part, in, whole.ordering, gate);
  a.End();
  Collect(a, &s, !(cfg.transport && r + 1 == p));
  return s;
}

SummaryFile SummarizeChunk(const AnalyzeConfig& cfg, uint32_t r, uint32_t p, const Log& log) {
  if (cfg.inputs.size() != 1)
    throw UsageError("a chunked analysis takes one input (a trace file or a mesh)");
  const std::string& in = cfg.inputs[0];
  const TraceFormat* fmt = cfg.format.empty() ? nullptr : &ParseTraceFormat(cfg.format);
  if (in == "-") throw UsageError("a chunked analysis needs a file: standard input cannot be cut");
  const bool mesh = !fmt && ClassifyInput(in) == InputKind::kMesh;
  if (mesh && cfg.orderings.size() != 1)
    throw UsageError("a chunked analysis of a mesh takes one ordering");
  if (cfg.sample && cfg.shards.s_max)
    throw UsageError(
        "a chunked analysis samples at a fixed rate (--sample-rate): a fixed-size sample's "
        "threshold depends on every id before it (run --sample-size serially)");
  if (cfg.sample && cfg.shards.exact_below)
    throw UsageError(
        "--sample-exact-below counts the small distances of the whole stream in order: run it "
        "serially (or with --threads), not in chunks or ranks");
  if (cfg.threads != 1 && !mesh)
    throw UsageError("each chunk is analysed on one thread: run more chunks (ranks) instead");
  if (mesh) return SummarizeMeshChunk(cfg, r, p, log);

  SummaryFile s;
  s.input = in;
  s.chunk = r;
  s.id.chunks = p;
  s.id.format = fmt ? fmt->name : "";
  s.id.fingerprint = Fingerprint(in, &s.id.input_bytes);
  s.id.instructions = cfg.instructions;
  Granularity g = Granularity::kBoth;
  if (cfg.granularity)
    g = *cfg.granularity;
  else if (fmt)
    g = fmt->addresses ? Granularity::kLine : Granularity::kElement;
  SetAnalysis(cfg, g, &s);

  uint64_t total;
  std::vector<uint64_t> eoff, loff;
  const bool text = fmt && fmt->syntax != TraceSyntax::kFixedRecords;
  if (fmt) {
    // A text trace is cut by bytes of its content (decompressed), at line boundaries.
    const int64_t content = InputStream(in).size();
    if (content < 0)
      throw InputError(in, 0,
                       "a zstd-compressed trace whose frames do not all record their sizes cannot "
                       "be cut into chunks: decompress it first (zstd -d)");
    total = static_cast<uint64_t>(content) / (text ? 1 : fmt->record_bytes);
  } else {
    TraceReader tr(in);
    total = tr.header().records;
  }
  Cut(total, r, p, &s);
  if (text) {
    eoff = loff = {0};  // no profile: a text trace's length is not known up front
  } else if (fmt) {
    eoff = loff = {s.first};  // one stream, one access per record (fixed records are 1 byte)
  } else {
    // Only a profile needs the true offsets (reading back to the sweep's start); a distributed
    // run without one sets them from the ranks before (RunDistributed), a summary file must hold
    // them (its merge may write a profile).
    TraceOffsets(in, cfg.profile || !cfg.transport ? s.first : 0, cfg.line_bytes, &eoff, &loff);
  }

  ReuseAnalysis a(ChunkOptions(cfg, s));
  a.SetStreamOffsets(eoff, loff);
  const RecordRange range{s.first, s.end};
  log.Say("analysing chunk " + ChunkName(r, p) + " of " + in + (text ? ": bytes " : ": records ") +
          std::to_string(s.first) + ".." + std::to_string(s.end) + " of " + std::to_string(total));
  if (fmt)
    StreamForeignTrace(in, *fmt, cfg.instructions, a, FileProgress(log), &range);
  else
    StreamTraceFile(in, a, FileProgress(log), &range);
  Collect(a, &s, !(cfg.transport && r + 1 == p));
  return s;
}

void RunChunk(const AnalyzeConfig& cfg, const Log& log) {
  const auto [r, p] = *cfg.chunk;
  WriteSummary(cfg.summary_out, SummarizeChunk(cfg, r, p, log));
  log.Say("wrote " + cfg.summary_out);
}

SummaryMerger::SummaryMerger(bool profile, bool reread) : profile_(profile), reread_(reread) {}
SummaryMerger::~SummaryMerger() = default;

void SummaryMerger::Add(SummaryFile s, const std::string& name, size_t given) {
  if (!a_) {
    id_ = s.id;
    first_name_ = name;
    input_ = s.input;
    granularity_ = static_cast<Granularity>(id_.granularity);
    ReuseOptions o;
    o.granularity = granularity_;
    o.line_bytes = id_.line_bytes;
    o.profile = profile_;
    o.exact = id_.exact;
    o.sample = id_.sample;
    o.shards.rate = id_.sample ? id_.rate : 1;
    o.shards.seed = id_.seed;
    o.reserve = false;  // the summary's vertex and sweep counts are claims, not yet data
    shards_ = o.shards;
    a_ = std::make_unique<ReuseAnalysis>(o);
    StreamInfo info = s.info;
    info.input = s.input;
    a_->Begin(info);
    if (given != id_.chunks)
      throw InputError(name, 0,
                       "a run of " + std::to_string(id_.chunks) + " chunks, and " +
                           std::to_string(given) +
                           " summaries given: give every chunk's summary once, in order 0.." +
                           std::to_string(id_.chunks - 1));
  } else if (!(s.id == id_)) {
    throw InputError(name, 0,
                     "a summary of another analysis: its trace, options or chunk count differ "
                     "from those of " +
                         first_name_);
  }
  if (s.chunk != expect_)
    throw InputError(name, 0,
                     "chunk " + ChunkName(s.chunk, id_.chunks) + " where chunk " +
                         ChunkName(expect_, id_.chunks) +
                         " was expected: give every summary once, in order 0.." +
                         std::to_string(id_.chunks - 1));
  if (s.first != next_record_)
    throw InputError(name, 0, "corrupt: its records do not follow the previous chunk's");
  if (s.info.threads != a_->threads())
    throw InputError(name, 0, "corrupt: a thread count unlike the first summary's");
  ++expect_;
  next_record_ = s.end;
  for (int t = 0; t < a_->threads(); ++t) a_->AddMoves(t, s.moves[t]);
  for (StreamSummary& x : s.streams) {
    any_access_ = any_access_ || x.accesses > 0 || x.stream_accesses > 0;
    StreamAnalysis& st = a_->MakeStream(static_cast<int>(x.thread), x.granularity);
    // The merged distances reach the stream's distinct ids: counted in pages, not in an array as
    // long as the largest (no rank of an MPI run, nor a file merge, holds one of M entries).
    if (!st.hist.paged() && st.hist.accesses() == 0) st.hist.UsePages();
    if (x.sampled) {  // the sampled ids, a stream of their own (no profile)
      Sampled& z = sampled_[{static_cast<int>(x.thread), static_cast<int>(x.granularity)}];
      if (!x.resolved)
        for (uint64_t d : ResolveChunk(x.chunk, &z.stack)) z.hist.Add(d);
      for (const auto& [dist, n] : x.hist) z.hist.AddCount(dist, n);
      z.accesses += x.stream_accesses;
      continue;
    }
    st.batched = true;                       // the stack travels as a list
    const uint64_t at = st.hist.accesses();  // the stream's accesses before this chunk
    const bool prof = st.profile.enabled();
    if (prof && x.offset != at)
      throw InputError(name, 0,
                       "the profile cannot be merged: the chunk counted its stream " +
                           std::to_string(x.thread) + " to start at access " +
                           std::to_string(x.offset) + ", the chunks before it hold " +
                           std::to_string(at) +
                           " (accesses straddling two lines before the chunk); merge without "
                           "profile output");
    if (!x.resolved) {
      const std::vector<uint64_t> d = ResolveChunk(x.chunk, &st.stack);
      for (size_t k = 0; k < d.size(); ++k) {
        st.hist.Add(d[k]);
        if (prof) st.profile.AddAt(at + x.chunk.first_positions[k], d[k]);
      }
    }
    for (const auto& [dist, n] : x.hist) st.hist.AddCount(dist, n);
    if (prof)
      for (const StreamSummary::Step& p : x.profile)
        if (!st.profile.AddToStep(p.index, p.accesses, p.cold, p.sum))
          throw InputError(name, 0, "corrupt: a profile step beyond the sweeps");
  }
}

AnalyzeResult SummaryMerger::Finish() {
  if (!a_) throw std::logic_error("SummaryMerger: nothing added");
  // A whole read refuses a lackey file without records (data, or instructions counted); a chunk
  // cannot tell, so the chunks together do (no access in any chunk is exactly that condition).
  if (id_.format == "lackey" && !any_access_) {
    if (reread_)
      ReadForeignTrace(
          input_, ParseTraceFormat("lackey"), [](uint64_t, uint32_t, bool, bool) {},
          id_.instructions != 0);
    throw InputError(input_, 0,
                     "no lackey records (L, S, M or I lines) in any chunk: run valgrind "
                     "--tool=lackey --trace-mem=yes --log-file=FILE PROGRAM and read FILE");
  }
  // Each sampled stream's estimate, as the serial sampler would have built it (End() then applies
  // SHARDS_adj as it does serially).
  for (const auto& [key, z] : sampled_) {
    StreamAnalysis& st = a_->MakeStream(key.first, static_cast<Granularity>(key.second));
    st.shards = std::make_unique<Shards>(Shards::FromSampled(shards_, z.accesses, z.hist));
  }
  a_->End();
  AnalyzeResult res;
  res.granularity = granularity_;
  if (id_.sample) {
    res.sampling = shards_;
    res.sampling_with_exact = id_.exact;
  }
  res.runs.push_back(std::move(a_));
  return res;
}

AnalyzeResult MergeSummaries(const AnalyzeConfig& cfg, const Log& log) {
  if (cfg.inputs.empty()) throw UsageError("--merge: no summary given");
  SummaryMerger m(cfg.profile);
  for (const std::string& path : cfg.inputs) {
    SummaryFile s = ReadSummary(path);
    log.Say("merging chunk " + ChunkName(s.chunk, s.id.chunks) + " (" + path + ")");
    m.Add(std::move(s), path, cfg.inputs.size());
  }
  return m.Finish();
}

namespace {

// Sorted (key, value) lists added into one sorted list, values of equal keys added.
template <class T, class Key, class Add>
std::vector<T> AddSorted(std::vector<T>&& a, std::vector<T>&& b, Key key, Add add) {
  auto less = [&](const T& x, const T& y) { return key(x) < key(y); };
  if (!std::is_sorted(a.begin(), a.end(), less)) std::sort(a.begin(), a.end(), less);
  if (!std::is_sorted(b.begin(), b.end(), less)) std::sort(b.begin(), b.end(), less);
  std::vector<T> out;
  out.reserve(a.size() + b.size());
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && key(a[i]) < key(b[j]))) {
      out.push_back(a[i++]);
    } else if (i == a.size() || key(b[j]) < key(a[i])) {
      out.push_back(b[j++]);
    } else {
      out.push_back(a[i++]);
      add(&out.back(), b[j++]);
    }
  }
  return out;
}

// Adds the resolved chunks `b` (those right after `a`'s, from the rank named `name`) into `a`.
void AddResolved(SummaryFile* a, SummaryFile&& b, const std::string& name) {
  if (!(b.id == a->id) || b.info.threads != a->info.threads || b.moves.size() != a->moves.size())
    throw InputError(name, 0, "corrupt: a resolved message of another analysis");
  if (b.first != a->end)
    throw InputError(name, 0, "corrupt: its records do not follow the previous chunk's");
  a->end = b.end;
  for (size_t t = 0; t < a->moves.size(); ++t) a->moves[t] += b.moves[t];
  for (StreamSummary& y : b.streams) {
    if (!y.resolved) throw InputError(name, 0, "corrupt: a stream not resolved");
    auto x = std::find_if(a->streams.begin(), a->streams.end(), [&](const StreamSummary& z) {
      return z.thread == y.thread && z.granularity == y.granularity && z.sampled == y.sampled;
    });
    if (x == a->streams.end()) {  // the stream's first accesses are in b's chunks
      a->streams.push_back(std::move(y));
      continue;
    }
    x->accesses += y.accesses;
    x->stream_accesses += y.stream_accesses;
    using Pair = std::pair<uint64_t, uint64_t>;
    x->hist = AddSorted(
        std::move(x->hist), std::move(y.hist), [](const Pair& p) { return p.first; },
        [](Pair* p, const Pair& q) { p->second += q.second; });
    using Step = StreamSummary::Step;
    x->profile = AddSorted(
        std::move(x->profile), std::move(y.profile), [](const Step& p) { return p.index; },
        [](Step* p, const Step& q) {
          p->accesses += q.accesses, p->cold += q.cold, p->sum += q.sum;
        });
  }
}

// What a rank's resolved histograms take (16 bytes a distance it counts).
uint64_t ResolvedBytes(const SummaryFile& s) {
  uint64_t n = 0;
  for (const StreamSummary& x : s.streams) n += x.hist.capacity() * 16;
  return n;
}

using Pair = std::pair<uint64_t, uint64_t>;

// A stream's key in a distributed run: (thread * 2 + granularity - 1) * 2 + sampled.
size_t StreamKey(const StreamSummary& x) {
  return (x.thread * 2 + static_cast<size_t>(x.granularity) - 1) * 2 + x.sampled;
}

// One stream's (distance, count) pairs as bytes, after its key and their number.
void PutPairs(std::string* out, uint64_t key, const Pair* p, size_t n) {
  const size_t at = out->size();
  out->resize(at + 16 * (n + 1));
  char* w = &(*out)[at];
  auto put = [&w](uint64_t v) {
    std::memcpy(w, &v, 8);
    w += 8;
  };
  put(key), put(n);
  for (size_t i = 0; i < n; ++i) put(p[i].first), put(p[i].second);
}

Pair PairAt(const char* p, size_t i) {
  uint64_t v[2];
  std::memcpy(v, p + 16 * i, 16);
  return {v[0], v[1]};
}

// Each stream's pairs in bytes PutPairs wrote, from the rank named `name`: f(key, bytes of its
// n pairs, n) (PairAt reads them), keys below `keys`, each stream once, every count positive and
// the distances increasing.
template <class F>
void ForEachPairs(const std::string& b, const std::string& name, size_t keys, F f) {
  std::vector<bool> seen(keys, false);
  for (size_t at = 0; at < b.size();) {
    if (b.size() - at < 16) throw InputError(name, 0, "corrupt: a histogram slice cut");
    const Pair head = PairAt(b.data() + at, 0);
    at += 16;
    if (head.first >= keys || seen[head.first] || head.second > (b.size() - at) / 16)
      throw InputError(name, 0, "corrupt: a histogram slice's stream or length");
    seen[head.first] = true;
    const char* p = b.data() + at;
    for (size_t i = 0; i < head.second; ++i) {
      const Pair q = PairAt(p, i);
      if (q.second == 0 || (i && q.first <= PairAt(p, i - 1).first))
        throw InputError(name, 0, "corrupt: a histogram slice's pairs");
    }
    f(static_cast<size_t>(head.first), p, static_cast<size_t>(head.second));
    at += 16 * head.second;
  }
}

}  // namespace

void SendIds(Communicator& c, const uint64_t* ids, size_t n) {
  c.Send(c.rank() + 1, PackValues(ids, n));
}

size_t RecvIds(Communicator& c, std::vector<uint64_t>* ids) {
  *ids = UnpackValues<uint64_t>(c.Recv(c.rank() - 1));
  return ids->size();
}

uint64_t SendSummary(Communicator& c, int32_t to, SummaryFile&& s) {
  if (c.SharesMemory()) {  // no bytes: the object changes hands
    c.SendObject(to, std::make_shared<SummaryFile>(std::move(s)));
    return 0;
  }
  std::string b = EncodeSummary(s);
  const uint64_t n = b.size();
  c.Send(to, std::move(b));
  return n;
}

SummaryFile RecvSummary(Communicator& c, int32_t from, const std::string& name) {
  if (c.SharesMemory())
    return std::move(*std::static_pointer_cast<SummaryFile>(c.RecvObject(from)));
  return DecodeSummary(name, c.Recv(from), true);
}

AnalyzeResult RunDistributed(const AnalyzeConfig& cfg, Communicator& tx, const Log& log) {
  const int rank = tx.rank(), ranks = tx.size();
  const Log quiet;
  RankStats stats;
  stats.rank = rank;
  const auto wall0 = std::chrono::steady_clock::now();
  double cpu = ThreadCpuSeconds();
  auto lap = [&cpu] {
    const double now = ThreadCpuSeconds(), d = now - cpu;
    cpu = now;
    return d;
  };
  SummaryFile s = SummarizeChunk(cfg, static_cast<uint32_t>(rank), static_cast<uint32_t>(ranks),
                                 rank == 0 ? log : quiet);
  stats.analyse_cpu = lap();
  stats.records = s.end - s.first;
  for (const StreamSummary& x : s.streams)
    stats.accesses += x.accesses, stats.distinct += x.chunk.first_ids.size();
  // Every rank relays every stream some chunk has, in one order: stream key = (thread * 2 + g - 1)
  // * 2 + sampled.
  const size_t keys = static_cast<size_t>(s.info.threads) * 4;
  std::vector<uint64_t> present(keys, 0), accesses(keys, 0);
  std::vector<StreamSummary*> mine(keys, nullptr);
  for (StreamSummary& x : s.streams) {
    const size_t k = StreamKey(x);
    present[k] = 1, accesses[k] = x.accesses, mine[k] = &x;
  }
  present = tx.AllReduceMax(present);
  const std::vector<uint64_t> offsets = tx.ExclusiveScanSum(accesses);
  if (rank == 0) log.Say("streaming the LRU stacks through " + std::to_string(ranks) + " ranks");
  // A profile for placing first touches at their true positions in each stream.
  ReuseOptions po;
  po.granularity = static_cast<Granularity>(s.id.granularity);
  po.line_bytes = s.id.line_bytes;
  po.profile = cfg.profile;
  ReuseAnalysis places(po);
  places.Begin(s.info);
  constexpr size_t kBlock = size_t{1} << 16;
  std::vector<uint64_t> in, out;
  for (size_t k = 0; k < keys; ++k) {
    if (!present[k]) continue;
    StreamSummary* x = mine[k];
    const ChunkSummary empty;
    ChunkResolver res(x ? x->chunk : empty);
    const bool last = rank + 1 == ranks;
    auto forward = [&](bool flush) {
      if (last) {
        out.clear();
        return;
      }
      if (!out.empty() && (flush || out.size() >= kBlock)) {
        SendIds(tx, out.data(), out.size());
        stats.stack_ids_sent += out.size();
        out.clear();
      }
    };
    const double stream0 = ThreadCpuSeconds();
    if (rank > 0)
      while (RecvIds(tx, &in) > 0) {
        stats.stack_ids_in += in.size();
        res.Filter(in.data(), in.size(), &out);
        forward(false);
      }
    if (x)
      for (size_t at = 0; at < x->chunk.stack.size(); at += kBlock) {
        out.insert(out.end(), x->chunk.stack.begin() + at,
                   x->chunk.stack.begin() + std::min(x->chunk.stack.size(), at + kBlock));
        forward(false);
      }
    forward(true);
    if (!last) SendIds(tx, nullptr, 0);  // end of this stream
    stats.stream_cpu += ThreadCpuSeconds() - stream0;
    if (!x) continue;
    const double resolve0 = ThreadCpuSeconds();
    // Off the critical path: this chunk's first touches, folded into its histogram and profile.
    StreamAnalysis& st = places.MakeStream(static_cast<int>(x->thread), x->granularity);
    const bool prof = !x->sampled && st.profile.enabled();
    if (prof && x->offset != offsets[k])
      throw InputError(s.input, 0,
                       "the profile cannot be computed: chunk " + std::to_string(rank) +
                           " counted its stream " + std::to_string(x->thread) +
                           " to start at access " + std::to_string(x->offset) +
                           ", the chunks before it hold " + std::to_string(offsets[k]) +
                           " (accesses straddling two lines)");
    // The first touches' distances reach the whole stream's distinct ids: counted in pages.
    ReuseHistogram h;
    h.UsePages();
    for (const auto& [dist, n] : x->hist) h.AddCount(dist, n);
    const std::vector<uint64_t>& places_in_chunk = x->chunk.first_positions;
    if (prof && places_in_chunk.size() != x->chunk.first_ids.size())
      throw std::logic_error("RunDistributed: a chunk with a profile kept no first-touch places");
    res.ForEachFirstTouchDistance([&](size_t i, uint64_t d) {
      h.Add(d);
      if (prof) st.profile.AddAt(offsets[k] + places_in_chunk[i], d);
    });
    stats.histogram_bytes = std::max(stats.histogram_bytes, h.counter_bytes());
    stats.dense_histogram_bytes =
        std::max(stats.dense_histogram_bytes,
                 h.finite() ? ReuseHistogram::kDenseCounterBytes * (h.max() + 1) : 0);
    size_t pairs = 1;  // and the cold count's
    h.ForEach([&pairs](uint64_t, uint64_t) { ++pairs; });
    x->hist.clear();
    x->hist.reserve(pairs);
    h.ForEach([&](uint64_t dist, uint64_t n) { x->hist.emplace_back(dist, n); });
    if (h.cold()) x->hist.emplace_back(StackDistance::kCold, h.cold());
    if (prof) {
      const auto& steps = st.profile.steps();
      for (size_t i = 0; i < steps.size(); ++i)
        if (steps[i].accesses)
          x->profile.push_back({i, steps[i].accesses, steps[i].cold, steps[i].sum});
    }
    x->chunk = ChunkSummary();
    x->resolved = true;
    x->offset = offsets[k];  // the true start, now known
    stats.resolve_cpu += ThreadCpuSeconds() - resolve0;
  }
  lap();
  stats.bytes_sent = stats.stack_ids_sent * 8 + 16 * keys;  // blocks, and the two collectives
  if (rank == 0) log.Say("adding up " + std::to_string(ranks) + " resolved chunks");
  for (const StreamSummary& x : s.streams) stats.pairs += x.hist.size();
  stats.histogram_bytes = std::max(stats.histogram_bytes, ResolvedBytes(s));
  // From cfg.scatter_from_ranks ranks on, the histograms are added up by distance, not by chunk
  // (a reduce-scatter): rank j adds slice j of every stream's distances, d with floor(d P / top)
  // = j (top: one past the stream's largest finite distance on any rank; the cold count with the
  // last slice), from every rank, and rank 0 gathers the disjoint slices in order. Each rank adds
  // at most the distinct distances M and rank 0 receives at most M, whatever P, where the tree
  // below, adding whole lists, takes log2(P) merges of up to M pairs on the way to rank 0. With few
  // ranks the tree is cheaper: the slices are cut, sent, parsed and added twice over (threads on 20
  // M uniform accesses over 10^6 ids, rank 0's reduce CPU by distance and by tree: 0.047 / 0.020 s
  // at 2, 0.052 / 0.035 at 4, 0.051 / 0.047 at 8: the default, 16, where the tree's levels cost
  // more). Integers: exact in any grouping.
  std::vector<uint64_t> top(keys, 0);
  std::vector<std::vector<Pair>> slice(keys);  // this rank's slice of each stream, added up
  using U = unsigned __int128;
  auto lo = [&](size_t k, int j) {  // the least distance of slice j (j < ranks)
    return static_cast<uint64_t>((U{top[k]} * static_cast<unsigned>(j) + ranks - 1) / ranks);
  };
  auto in_slice = [&](size_t k, int j, uint64_t d) {
    if (d == StackDistance::kCold) return j + 1 == ranks;
    return d < top[k] && d >= lo(k, j) && (j + 1 == ranks || d < lo(k, j + 1));
  };
  const bool scatter = ranks >= std::max(cfg.scatter_from_ranks, 2);
  if (scatter) {
    for (const StreamSummary& x : s.streams)
      for (auto p = x.hist.rbegin(); p != x.hist.rend(); ++p)
        if (p->first != StackDistance::kCold) {
          top[StreamKey(x)] = p->first + 1;
          break;
        }
    top = tx.AllReduceMax(top);
    std::vector<std::string> out(static_cast<size_t>(ranks));
    std::vector<std::pair<const Pair*, size_t>> own(keys, {nullptr, 0});
    for (const StreamSummary& x : s.streams) {
      const size_t k = StreamKey(x);
      const Pair* b = x.hist.data();
      const Pair* e = b + x.hist.size();
      for (int j = 0; j < ranks; ++j) {  // pairs are sorted: each slice a run of them
        const Pair* end = j + 1 == ranks
                              ? e
                              : std::lower_bound(b, e, lo(k, j + 1), [](const Pair& q, uint64_t d) {
                                  return q.first < d;
                                });
        if (end == b) continue;
        if (j == rank)
          own[k] = {b, static_cast<size_t>(end - b)};
        else
          PutPairs(&out[static_cast<size_t>(j)], k, b, static_cast<size_t>(end - b));
        b = end;
      }
    }
    for (const std::string& o : out) stats.bytes_sent += o.size();
    const std::vector<std::string> in = tx.AllToAll(std::move(out));
    const double merge0 = ThreadCpuSeconds();
    // Slice `rank` of stream k, added up in pages of distances, each allocated when first
    // touched: memory follows the distances the slice holds (a scan's: one page), not its width.
    std::vector<ReuseHistogram> counts(keys);
    for (ReuseHistogram& h : counts) h.UsePages();
    // This slice's bounds, once per stream (in_slice divides for each call): [from, to).
    std::vector<uint64_t> from(keys), to(keys);
    for (size_t k = 0; k < keys; ++k)
      from[k] = lo(k, rank), to[k] = rank + 1 == ranks ? top[k] : lo(k, rank + 1);
    const bool last = rank + 1 == ranks;
    auto add = [&](size_t k, uint64_t d, uint64_t n, const std::string& name) {
      if (d == StackDistance::kCold ? !last : d < from[k] || d >= to[k])
        throw InputError(name, 0, "corrupt: a distance outside the slice it was sent for");
      counts[k].AddCount(d, n);
    };
    const std::string me = "rank " + std::to_string(rank);
    for (size_t k = 0; k < keys; ++k) {
      for (size_t i = 0; i < own[k].second; ++i)
        add(k, own[k].first[i].first, own[k].first[i].second, me);
      stats.pairs_added += own[k].second;
    }
    for (int j = 0; j < ranks; ++j)
      if (j != rank) {
        const std::string name = "rank " + std::to_string(j);
        ForEachPairs(in[static_cast<size_t>(j)], name, keys,
                     [&](size_t k, const char* p, size_t n) {
                       if (!present[k]) throw InputError(name, 0, "corrupt: a stream no rank has");
                       for (size_t i = 0; i < n; ++i) {
                         const Pair q = PairAt(p, i);
                         add(k, q.first, q.second, name);
                       }
                       stats.pairs_added += n;
                     });
      }
    for (size_t k = 0; k < keys; ++k) {
      counts[k].ForEach([&](uint64_t d, uint64_t n) { slice[k].emplace_back(d, n); });
      if (counts[k].cold()) slice[k].emplace_back(StackDistance::kCold, counts[k].cold());
      stats.histogram_bytes = std::max<uint64_t>(
          stats.histogram_bytes, counts[k].counter_bytes() + slice[k].capacity() * 16);
      counts[k] = ReuseHistogram();
    }
    stats.merge_cpu += ThreadCpuSeconds() - merge0;
    for (StreamSummary& x : s.streams) {
      x.hist = std::vector<Pair>();
      x.hist_apart = true;
    }
  }
  // The resolved chunks (their histograms too, unless scattered above; accesses, profiles, moves)
  // up a binary tree of ranks: at the level of `step`, a rank r with r % 2 step == step sends
  // what it holds (chunks [r, r + step)) to r - step, which adds it to its own.
  for (int step = 1; step < ranks; step *= 2) {
    if (rank % (2 * step) == step) {
      stats.bytes_sent += SendSummary(tx, rank - step, std::move(s));
      s = SummaryFile();
      break;
    }
    if (rank + step < ranks) {
      const std::string name = "rank " + std::to_string(rank + step);
      SummaryFile o = RecvSummary(tx, rank + step, name);
      for (const StreamSummary& x : o.streams) stats.pairs_added += x.hist.size();
      const double merge0 = ThreadCpuSeconds();
      AddResolved(&s, std::move(o), name);
      if (!scatter) {  // the histograms came whole, and were added here
        stats.merge_cpu += ThreadCpuSeconds() - merge0;
        stats.histogram_bytes = std::max(stats.histogram_bytes, ResolvedBytes(s));
      }
    }
  }
  if (rank != 0) {
    if (scatter) {  // this rank's slices to rank 0
      std::string b;
      for (size_t k = 0; k < keys; ++k)
        if (!slice[k].empty()) PutPairs(&b, k, slice[k].data(), slice[k].size());
      stats.bytes_sent += b.size();
      tx.Send(0, std::move(b));
    }
    stats.reduce_cpu = lap();
    stats.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    stats.peak_rss_bytes = PeakRssBytes();
    tx.Send(0, std::string(reinterpret_cast<const char*>(&stats), sizeof stats));
    return AnalyzeResult();
  }
  // Rank 0 holds every chunk, resolved: one summary of one chunk for the merger, its histograms
  // the slices of the ranks in order (each rank's distances above those of the ranks before).
  if (scatter) {
    for (int j = 1; j < ranks; ++j) {
      const std::string name = "rank " + std::to_string(j);
      ForEachPairs(tx.Recv(j), name, keys, [&](size_t k, const char* p, size_t n) {
        for (size_t i = 0; i < n; ++i) {
          const Pair q = PairAt(p, i);
          if (!in_slice(k, j, q.first))
            throw InputError(name, 0, "corrupt: a distance outside its slice");
          slice[k].push_back(q);
        }
      });
    }
    for (StreamSummary& x : s.streams) {
      const size_t k = StreamKey(x);
      uint64_t n = 0;
      for (const Pair& q : slice[k])
        if (__builtin_add_overflow(n, q.second, &n)) n = ~uint64_t{0};
      if (n != x.accesses)
        throw InputError("the ranks", 0,
                         "corrupt: a stream's histogram slices do not add up to its accesses");
      x.hist = std::move(slice[k]);
      x.hist_apart = false;
      stats.histogram_bytes = std::max(stats.histogram_bytes, ResolvedBytes(s));
    }
    for (const std::vector<Pair>& left : slice)
      if (!left.empty())
        throw InputError("the ranks", 0, "corrupt: histogram slices of a stream none holds");
  }
  s.chunk = 0, s.id.chunks = 1;
  SummaryMerger m(cfg.profile, true);
  m.Add(std::move(s), "rank 0", 1);
  std::vector<RankStats> all(1);
  for (int r = 1; r < ranks; ++r) {
    const std::string b = tx.Recv(r);
    if (b.size() != sizeof(RankStats))
      throw InputError("rank " + std::to_string(r), 0, "corrupt statistics message");
    all.emplace_back();
    std::memcpy(&all.back(), b.data(), sizeof(RankStats));
  }
  AnalyzeResult res = m.Finish();
  uint64_t merged = 0, merged_dense = 0;  // every merged stream's, held together
  for (const auto& run : res.runs)
    for (int t = 0; t < run->threads(); ++t)
      for (Granularity g : {Granularity::kElement, Granularity::kLine})
        if (const StreamAnalysis* x = run->stream(t, g)) {
          merged += x->hist.counter_bytes();
          merged_dense +=
              x->hist.finite() ? ReuseHistogram::kDenseCounterBytes * (x->hist.max() + 1) : 0;
        }
  stats.histogram_bytes = std::max(stats.histogram_bytes, merged);
  stats.dense_histogram_bytes = std::max(stats.dense_histogram_bytes, merged_dense);
  stats.reduce_cpu = lap();
  stats.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  stats.peak_rss_bytes = PeakRssBytes();
  all[0] = stats;
  res.ranks = std::move(all);
  return res;
}

}  // namespace meshreuse
