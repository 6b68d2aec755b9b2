// The chunk summary file; see summary_file.h.
#include "reports/chunks/summary_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "core/error.h"
#include "core/input_file.h"
#include "core/mix.h"
#include "core/output_file.h"

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

}  // namespace

// Checksum over bytes that arrive in pieces: equal to Checksum of their concatenation (`n`, the
// total, is known before the first piece: the header announces it). Not in the anonymous
// namespace: SummaryHasher::State holds one (GCC warns of a class with external linkage holding a
// file-local type where the file is included, as a unity build includes it).
namespace summary_file_detail {
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
}  // namespace summary_file_detail

using summary_file_detail::ChecksumStream;

namespace {

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
  size_t at() const { return at_; }  // payload bytes consumed
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
      const size_t got = f_->Read(dst, k);
      sum_.Add(static_cast<const char*>(dst), got);
      at_ += got;
      if (got != k) Fail("truncated summary: the file ends inside its payload");
      return;
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

}  // namespace

uint64_t SummaryChecksum(const char* payload, size_t n) { return Checksum(payload, n); }

struct SummaryHasher::State {
  explicit State(uint64_t n) : c(n) {}
  ChecksumStream c;
};
SummaryHasher::SummaryHasher(uint64_t n) : s_(std::make_unique<State>(n)) {}
SummaryHasher::~SummaryHasher() = default;
void SummaryHasher::Add(const char* p, size_t n) { s_->c.Add(p, n); }
uint64_t SummaryHasher::Finish() const { return s_->c.Finish(); }

bool SummaryIdentity::operator==(const SummaryIdentity& o) const {
  return format == o.format && input_bytes == o.input_bytes && fingerprint == o.fingerprint &&
         granularity == o.granularity && line_bytes == o.line_bytes &&
         instructions == o.instructions && chunks == o.chunks && exact == o.exact &&
         sample == o.sample && rate == o.rate && seed == o.seed;
}

std::string ChunkName(uint32_t r, uint32_t p) {
  return std::to_string(r) + "/" + std::to_string(p);
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
  // Streamed, a regular file or a pipe alike: the header first (a wrong magic or version is
  // refused at once, before anything else is read), then the payload parsed as it is read, never
  // held whole beside what it decodes to, at most the announced bytes taken; the checksum,
  // computed on the way, is compared once the parse is done (and, when the parse fails, over the
  // rest of the payload first, so a damaged file is reported as damaged). A regular file's size is
  // checked against the header before the payload; a pipe must end where the payload does.
  InputFile f(path);
  if (f.size() > (int64_t{1} << 40)) throw InputError(path, 0, "not a chunk summary: too large");
  char head[kHeaderBytes];
  const size_t got = f.Read(head, kHeaderBytes);
  uint64_t bytes = 0, sum = 0;
  CheckHeader(path, head, got, &bytes, &sum);
  if (f.size() >= 0 && bytes != static_cast<uint64_t>(f.size()) - kHeaderBytes)
    SizeMismatch(path, bytes, static_cast<uint64_t>(f.size()) - kHeaderBytes);
  if (bytes > (uint64_t{1} << 40)) throw InputError(path, 0, "not a chunk summary: too large");
  Reader r(path, &f, bytes);
  SummaryFile s;
  try {
    s = ParsePayload(r, false);
  } catch (const InputError&) {
    r.Drain();
    if (!r.done() && f.size() < 0) SizeMismatch(path, bytes, r.at());  // a pipe that ended early
    if (r.done() && r.Checksum() != sum) ChecksumMismatch(path);
    throw;
  }
  if (r.Checksum() != sum) ChecksumMismatch(path);
  char extra;
  if (f.size() < 0 && f.Read(&extra, 1) == 1)
    throw InputError(path, 0,
                     "truncated or extended summary: bytes follow the " + std::to_string(bytes) +
                         " payload bytes the header announces");
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

}  // namespace meshreuse
