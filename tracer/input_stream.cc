// InputStream and CompressFile; see input_stream.h. Streaming decompression with libzstd's
// ZSTD_decompressStream (1 MiB compressed blocks).
#include "tracer/input_stream.h"

#include <unistd.h>
#include <zstd.h>
#include <zstd_errors.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "core/output_file.h"

namespace meshreuse {

namespace {
constexpr unsigned char kZstdMagic[4] = {0x28, 0xB5, 0x2F, 0xFD};
// 32 MiB: every zstd level up to 19 and --ultra -20/-21 decode within it; a frame asking more
// (--ultra -22, --long) is refused rather than allowed ~100 MB from a few header bytes.
constexpr int kWindowLogMax = 25;

bool IsZstd(const std::vector<char>& b) {  // a zstd frame or a skippable one (pzstd starts so)
  if (b.size() < 4) return false;
  if (std::memcmp(b.data(), kZstdMagic, 4) == 0) return true;
  return (static_cast<unsigned char>(b[0]) & 0xF0) == 0x50 &&
         static_cast<unsigned char>(b[1]) == 0x2A && static_cast<unsigned char>(b[2]) == 0x4D &&
         static_cast<unsigned char>(b[3]) == 0x18;
}

// A place a compressed file can be entered at: a frame's start, in the content and in the file.
struct ZstdEntry {
  uint64_t content;
  uint64_t file;
};
constexpr size_t kMaxEntries = size_t{1} << 16;  // 1 MiB of places, whatever the frame count

struct ZstdWalk {
  int64_t size = -1;      // the content's size, or -1 (see below)
  bool complete = false;  // the size is every frame's (not the first's of a damaged file)
  std::vector<ZstdEntry> entries;
};

// Places at most kMaxEntries: beyond, every other one dropped and every other frame noted, so
// they stay evenly spread whatever the frame count.
class EntryList {
 public:
  explicit EntryList(std::vector<ZstdEntry>* out) : out_(out) { out->clear(); }
  void Frame(uint64_t content, uint64_t file) {
    if (frames_++ % stride_ != 0) return;
    out_->push_back({content, file});
    if (out_->size() < kMaxEntries) return;
    for (size_t i = 0; i < kMaxEntries / 2; ++i) (*out_)[i] = (*out_)[2 * i];
    out_->resize(kMaxEntries / 2);
    stride_ *= 2;
  }

 private:
  std::vector<ZstdEntry>* out_;
  uint64_t frames_ = 0, stride_ = 1;
};

// How many places begin at or before content byte `offset`: the last of them is where a read of
// `offset` starts decompressing (none: the file's start).
size_t PlacesUpTo(const std::vector<ZstdEntry>& entries, uint64_t offset) {
  auto e = std::upper_bound(entries.begin(), entries.end(), offset,
                            [](uint64_t o, const ZstdEntry& x) { return o < x.content; });
  return static_cast<size_t>(e - entries.begin());
}

uint32_t Le32(const unsigned char* p) {
  return p[0] | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

// zstd's seekable format (facebook/zstd contrib/seekable_format): a skippable frame at the end
// (magic 0x184D2A5E) holding each frame's compressed and decompressed size (u32 each, a u32
// checksum after them when the descriptor's bit 7 says so), then the frame count (u32), the
// descriptor (u8, bits 2-6 reserved zero) and the magic 0x8F92EAB1. `meshreuse compress` writes
// one; so do t2sz and zstd's own seekable compressor. Read in one pass of 96 KiB reads instead of
// a read per block (the table's own checksums are not read: the frames carry theirs); a table
// that is not well formed (reserved bits, its sizes not adding up to the file) is
// ignored, as the zstd tool ignores it (the frames are then walked). What the table says of each
// place is checked where the decompressor passes it (InputStream::Step), so a table that lies
// fails a whole read, and some chunk of any cut, like damage.
constexpr uint32_t kSeekTableMagic = 0x8F92EAB1, kSeekFrameMagic = 0x184D2A5E;
constexpr uint64_t kMaxTableFrames = uint64_t{1} << 27;  // the seekable format's own bound
constexpr uint64_t kMaxWrittenTableFrames = uint64_t{1} << 24;
bool ReadSeekTable(std::FILE* f, int64_t file_bytes, ZstdWalk* w) {
  const int fd = fileno(f);
  const uint64_t bytes = static_cast<uint64_t>(file_bytes);
  unsigned char foot[9], head[8];
  if (bytes < 17 || pread(fd, foot, 9, file_bytes - 9) != 9 || Le32(foot + 5) != kSeekTableMagic)
    return false;
  if (foot[4] & 0x7C) return false;  // reserved bits
  const uint64_t n = Le32(foot), width = foot[4] & 0x80 ? 12 : 8;
  if (n > kMaxTableFrames || 17 + n * width > bytes) return false;
  const uint64_t table = 17 + n * width, data = bytes - table;
  if (pread(fd, head, 8, static_cast<off_t>(data)) != 8 || Le32(head) != kSeekFrameMagic ||
      Le32(head + 4) != n * width + 9)
    return false;
  std::vector<ZstdEntry> entries;
  EntryList list(&entries);
  std::vector<unsigned char> buf(8190 * 12);  // a whole number of entries of either width
  uint64_t file = 0, content = 0;
  for (uint64_t i = 0; i < n;) {
    const uint64_t k = std::min<uint64_t>(n - i, buf.size() / width);
    const off_t at = static_cast<off_t>(data + 8 + i * width);
    if (pread(fd, buf.data(), k * width, at) != static_cast<ssize_t>(k * width)) return false;
    for (uint64_t j = 0; j < k; ++j) {
      list.Frame(content, file);
      file += Le32(&buf[j * width]);
      content += Le32(&buf[j * width + 4]);
    }
    i += k;
  }
  if (file != data || content > static_cast<uint64_t>(INT64_MAX)) return false;
  w->size = static_cast<int64_t>(content);
  w->complete = true;
  w->entries = std::move(entries);
  return true;
}

// The content size of a compressed regular file: every frame walked by its headers alone (RFC
// 8878: frame header, 3-byte block headers, optional checksum; skippable frames skipped), without
// decompressing, noting where each frame begins (EntryList). A read per block, so a file with a
// seek table (ReadSeekTable) is not walked. Size -1 when a frame does not record its size: such a
// file cannot be entered in the middle. A walk that does not end at the file's end (a file cut
// short, damage) gives the first frame's size and no places, so that the decompressor, not a
// missing size, reports what is wrong.
ZstdWalk WalkZstdFrames(std::FILE* f, int64_t file_bytes) {
  const int fd = fileno(f);
  auto at = [&](int64_t off, void* buf, size_t n) {
    return off >= 0 && off + static_cast<int64_t>(n) <= file_bytes &&
           pread(fd, buf, n, off) == static_cast<ssize_t>(n);
  };
  ZstdWalk w;
  EntryList list(&w.entries);
  int64_t off = 0, total = 0, first = -1;
  auto broken = [&] {
    w.size = first;
    w.entries.clear();
    return std::move(w);
  };
  while (off < file_bytes) {
    unsigned char h[18] = {};  // the largest frame header
    const size_t n = static_cast<size_t>(std::min<int64_t>(sizeof h, file_bytes - off));
    if (n < 8 || !at(off, h, n)) return broken();
    if ((h[0] & 0xF0) == 0x50 && h[1] == 0x2A && h[2] == 0x4D && h[3] == 0x18) {
      off += 8 + (int64_t{h[4]} | int64_t{h[5]} << 8 | int64_t{h[6]} << 16 | int64_t{h[7]} << 24);
      continue;
    }
    if (std::memcmp(h, kZstdMagic, 4) != 0) return broken();
    const unsigned d = h[4];  // Frame_Header_Descriptor
    const bool single = (d >> 5) & 1, checksum = (d >> 2) & 1;
    if ((d >> 3) & 1) return broken();  // reserved bit
    const size_t did = std::array<size_t, 4>{0, 1, 2, 4}[d & 3];
    const size_t fcs = std::array<size_t, 4>{single ? 1u : 0u, 2, 4, 8}[d >> 6];
    const size_t header = 5 + (single ? 0 : 1) + did + fcs;
    if (header > n) return broken();
    if (fcs == 0) {  // this frame does not record its size
      w.entries.clear();
      return w;
    }
    uint64_t content = 0;
    for (size_t i = 0; i < fcs; ++i) content |= uint64_t{h[header - fcs + i]} << (8 * i);
    if (fcs == 2) content += 256;
    if (content > static_cast<uint64_t>(INT64_MAX - total)) return broken();
    if (first < 0) first = static_cast<int64_t>(content);
    // A frame that names a dictionary: the decompressor (no dictionary loaded) refuses it, or
    // what follows it in the same session, so a chunk entering past it must not read on where a
    // whole read fails. Like damage: entered only at the start, the decompressor judging.
    uint32_t dict = 0;
    for (size_t i = 0; i < did; ++i) dict |= uint32_t{h[5 + (single ? 0 : 1) + i]} << (8 * i);
    if (dict != 0) return broken();
    list.Frame(static_cast<uint64_t>(total), static_cast<uint64_t>(off));
    total += static_cast<int64_t>(content);
    off += static_cast<int64_t>(header);
    for (bool last = false; !last;) {
      unsigned char b[3];
      if (!at(off, b, 3)) return broken();
      const uint32_t word = b[0] | uint32_t{b[1]} << 8 | uint32_t{b[2]} << 16;
      last = word & 1;
      const uint32_t type = (word >> 1) & 3, size = word >> 3;
      if (type == 3) return broken();  // reserved
      off += 3 + (type == 1 ? 1 : size);
    }
    if (checksum) off += 4;
  }
  if (off != file_bytes) return broken();
  w.size = total;
  w.complete = true;
  return w;
}
}  // namespace

struct InputStream::Zstd {
  ZSTD_DStream* ds = nullptr;
  std::vector<char> in = std::vector<char>(1 << 20);
  ZSTD_inBuffer ib{nullptr, 0, 0};
  uint64_t consumed = 0;  // the file offset of the current block (compressed bytes before it)
  bool eof = false;
  size_t last_ret = 0;  // 0 when the last frame ended cleanly
  bool seekable = false;
  bool complete = false;  // size is every frame's: checked at the file's end
  std::vector<ZstdEntry> entries;
  size_t check = 1;     // the next place to check where the decompressor passes it
  uint64_t pos = 0;     // content bytes before the next one Read returns
  bool ranged = false;  // entered by SeekTo: Read drains at the limit (Drain)
  bool drained = false;
  ~Zstd() { ZSTD_freeDStream(ds); }
};

InputStream::InputStream(const std::string& path) : file_(path) {
  peek_.resize(18);  // magic + the largest frame header (ZSTD_FRAMEHEADERSIZE_MAX)
  size_t got = 0;
  while (got < peek_.size()) {
    const size_t n = file_.Read(peek_.data() + got, peek_.size() - got);
    if (n == 0) break;
    got += n;
  }
  peek_.resize(got);
  if (IsZstd(peek_)) {
    zstd_ = std::make_unique<Zstd>();
    zstd_->ds = ZSTD_createDStream();
    if (!zstd_->ds) throw InputError(path, 0, "cannot create a zstd decompression stream");
    ZSTD_DCtx_setParameter(zstd_->ds, ZSTD_d_windowLogMax, kWindowLogMax);
    if (file_.size() >= 0) {
      ZstdWalk w;
      size_from_table_ = ReadSeekTable(file_.get(), file_.size(), &w);
      if (!size_from_table_) w = WalkZstdFrames(file_.get(), file_.size());
      size_ = w.size;
      zstd_->complete = w.complete;
      // A damaged file (the walk stopped short) is entered only at its start: the decompressor,
      // reading on from there, reports the damage as a whole read does.
      zstd_->seekable = w.size >= 0;
      zstd_->entries = std::move(w.entries);
    }
  } else {
    size_ = file_.size();
  }
}

InputStream::~InputStream() = default;

size_t InputStream::ReadRaw(void* buf, size_t n) {
  size_t got = 0;
  if (peek_at_ < peek_.size()) {
    got = std::min(n, peek_.size() - peek_at_);
    std::memcpy(buf, peek_.data() + peek_at_, got);
    peek_at_ += got;
  }
  if (got < n) got += file_.Read(static_cast<char*>(buf) + got, n - got);
  return got;
}

bool InputStream::seekable() const { return file_.size() >= 0 && (!zstd_ || zstd_->seekable); }

uint64_t InputStream::entry_points() const {
  if (!seekable()) return 0;
  return zstd_ ? zstd_->entries.size() : static_cast<uint64_t>(file_.size());
}

void InputStream::SeekRaw(uint64_t offset) {
  if (offset < peek_.size()) {
    peek_at_ = offset;
    offset = peek_.size();
  } else {
    peek_at_ = peek_.size();
  }
  if (fseeko(file_.get(), static_cast<off_t>(offset), SEEK_SET) != 0)
    throw InputError(path(), 0, std::string("cannot seek: ") + std::strerror(errno));
}

void InputStream::SeekTo(uint64_t offset) {
  if (file_.size() < 0)
    throw InputError(path(), 0,
                     "a chunk needs a regular file: a pipe or standard input cannot seek");
  if (zstd_ && !zstd_->seekable)
    throw InputError(path(), 0,
                     "a zstd-compressed trace whose frames do not all record their sizes cannot "
                     "be read from the middle (a chunk): decompress it first (zstd -d)");
  if (offset > static_cast<uint64_t>(size_))
    throw InputError(path(), 0, "byte offset " + std::to_string(offset) + " is past the end");
  if (!zstd_) return SeekRaw(offset);
  Zstd& z = *zstd_;
  const size_t after = PlacesUpTo(z.entries, offset);
  const ZstdEntry from = after == 0 ? ZstdEntry{0, 0} : z.entries[after - 1];
  z.check = after;
  SeekRaw(from.file);
  ZSTD_DCtx_reset(z.ds, ZSTD_reset_session_only);
  z.ib = ZSTD_inBuffer{nullptr, 0, 0};
  z.consumed = from.file;
  z.eof = false;
  z.last_ret = 0;
  z.pos = from.content;
  z.ranged = true;
  z.drained = false;
  std::vector<char> skip(1 << 16);
  while (z.pos < offset) {
    const size_t want = static_cast<size_t>(std::min<uint64_t>(skip.size(), offset - z.pos));
    if (ReadAll(skip.data(), want) < want)
      throw InputError(path(), 0,
                       "the zstd frames hold fewer bytes than their seek table or headers "
                       "record (compressed byte " +
                           std::to_string(z.consumed + z.ib.pos) + ")");
  }
}

uint64_t InputStream::NextLineStart(uint64_t offset, size_t max_line) {
  if (offset == 0) return 0;
  SeekTo(offset - 1);  // a line begins at `offset` when the byte before it ends one
  std::vector<char> b(max_line + 2);
  const size_t got = ReadAll(b.data(), b.size());
  const void* nl = std::memchr(b.data(), '\n', got);
  if (nl) return offset + static_cast<uint64_t>(static_cast<const char*>(nl) - b.data());
  if (got < b.size()) return offset - 1 + got;  // the last line runs to the end
  throw InputError(path(), 0,
                   "no line ends within " + std::to_string(max_line) + " bytes of byte offset " +
                       std::to_string(offset) + ": not a text trace");
}

size_t InputStream::Read(void* buf, size_t n) {
  n = static_cast<size_t>(std::min<uint64_t>(n, limit_));
  const size_t got = ReadAll(buf, n);
  limit_ -= got;
  if (limit_ == 0 && zstd_ && zstd_->ranged && !zstd_->drained) {
    zstd_->drained = true;
    Drain(*zstd_);
  }
  return got;
}

bool InputStream::Step(Zstd& z, void* buf, size_t n, size_t* pos) {
  if (z.ib.pos == z.ib.size) {
    if (z.eof) return false;
    z.consumed += z.ib.size;
    const size_t got = ReadRaw(z.in.data(), z.in.size());
    if (got == 0) {
      z.eof = true;
      if (z.last_ret != 0)
        throw InputError(path(), 0,
                         "truncated zstd stream: it ends inside a frame at compressed byte " +
                             std::to_string(z.consumed));
      if (z.complete && z.pos != static_cast<uint64_t>(size_))
        throw InputError(path(), 0,
                         "the zstd frames hold " + std::to_string(z.pos) +
                             " bytes where their seek table or headers say " +
                             std::to_string(size_));
      return false;
    }
    z.ib = ZSTD_inBuffer{z.in.data(), got, 0};
  }
  ZSTD_outBuffer ob{buf, n, *pos};
  const size_t ret = ZSTD_decompressStream(z.ds, &ob, &z.ib);
  if (ZSTD_isError(ret) && ZSTD_getErrorCode(ret) == ZSTD_error_frameParameter_windowTooLarge)
    throw InputError(path(), 0,
                     "the zstd frame near compressed byte " +
                         std::to_string(z.consumed + z.ib.pos) +
                         " needs a window above 32 MiB (zstd --long or --ultra -22): "
                         "decompress it first");
  if (ZSTD_isError(ret))
    throw InputError(path(), 0,
                     std::string("corrupt zstd stream near compressed byte ") +
                         std::to_string(z.consumed + z.ib.pos) + ": " + ZSTD_getErrorName(ret));
  z.last_ret = ret;
  z.pos += ob.pos - *pos;
  *pos = ob.pos;
  // At a frame's end: the places up to here must begin where a frame ends, at the content offset
  // the decompressor has reached (a seek table's word checked against the frames).
  const uint64_t at = z.consumed + z.ib.pos;
  for (; ret == 0 && z.check < z.entries.size() && z.entries[z.check].file <= at; ++z.check)
    if (z.entries[z.check].file != at || z.entries[z.check].content != z.pos)
      throw InputError(path(), 0,
                       "the zstd seek table does not match the frames: a frame said to begin at "
                       "compressed byte " +
                           std::to_string(z.entries[z.check].file) + " (content byte " +
                           std::to_string(z.entries[z.check].content) + ")");
  return true;
}

size_t InputStream::ReadAll(void* buf, size_t n) {
  if (!zstd_) return ReadRaw(buf, n);
  size_t pos = 0;
  while (pos < n && Step(*zstd_, buf, n, &pos)) {
  }
  return pos;
}

// The frames a range's reader left unread up to where the next range begins decompressing (the
// last frame starting at or before the range's end; the file's end after the last range), so that
// each frame's remaining blocks and checksum, and any frame lying between two entry points, are
// checked by some range as the whole read checks them. At most a frame's worth beyond the range.
void InputStream::Drain(Zstd& z) {
  uint64_t target = ~uint64_t{0};  // the file's end
  if (z.pos < static_cast<uint64_t>(size_)) {
    const size_t after = PlacesUpTo(z.entries, z.pos);
    target = after == 0 ? 0 : z.entries[after - 1].file;
  }
  std::vector<char> sink(1 << 16);
  while (z.last_ret != 0 || z.consumed + z.ib.pos < target) {
    size_t pos = 0;
    if (!Step(z, sink.data(), sink.size(), &pos)) break;
  }
}

uint64_t CompressFile(const std::string& src, const std::string& dst, int level,
                      uint64_t frame_bytes, const std::function<void(uint64_t)>& progress) {
  if (frame_bytes == 0 || frame_bytes > kZstdMaxFrameBytes)
    throw std::invalid_argument("CompressFile: frames of 1 byte to 256 MiB");
  InputStream in(src);
  AtomicOutput out(dst);
  struct Ctx {
    ZSTD_CCtx* cc = ZSTD_createCCtx();
    ~Ctx() { ZSTD_freeCCtx(cc); }
  } ctx;
  if (!ctx.cc) throw std::runtime_error("cannot create a zstd compression context");
  ZSTD_CCtx_setParameter(ctx.cc, ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(ctx.cc, ZSTD_c_checksumFlag, 1);
  // A whole frame is read before it is compressed, so that its header records its size whatever
  // the input (a pipe, a zstd file being re-framed).
  // The buffers grow with what arrives (a small input with large frames takes little).
  std::vector<char> frame, packed;
  const size_t most = static_cast<size_t>(frame_bytes);
  uint64_t total = 0;
  // Each frame's compressed and content sizes, for the seek table (8 bytes a frame, up to 2^24
  // frames: 128 MiB for 16 GiB in frames of 1 KiB; 128 KiB for 64 GiB in the default frames).
  std::vector<uint32_t> table;
  bool tabled = true;
  for (bool first = true;; first = false) {
    size_t got = 0;
    while (got < most) {
      if (frame.size() == got) frame.resize(std::min(most, got + (size_t{1} << 20)));
      const size_t n = in.Read(frame.data() + got, frame.size() - got);
      if (n == 0) break;
      got += n;
    }
    if (got == 0 && !first) break;  // an empty input still gets a (empty) frame
    packed.resize(std::max(packed.size(), ZSTD_compressBound(got)));
    const size_t z = ZSTD_compress2(ctx.cc, packed.data(), packed.size(), frame.data(), got);
    if (ZSTD_isError(z)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(z));
    if (std::fwrite(packed.data(), 1, z, out.file()) != z)
      throw EnvironmentError(dst, std::string("write failed: ") + std::strerror(errno));
    total += got;
    if (tabled && table.size() / 2 < kMaxWrittenTableFrames) {
      table.push_back(static_cast<uint32_t>(z));
      table.push_back(static_cast<uint32_t>(got));
    } else if (tabled) {  // too many frames for a table in memory: readers walk the frames
      tabled = false;
      std::vector<uint32_t>().swap(table);
    }
    if (progress) progress(total);
    if (got < most) break;
  }
  if (tabled) {  // zstd's seekable format (ReadSeekTable), little-endian words
    const uint64_t n = table.size() / 2;
    std::vector<uint32_t> words = {kSeekFrameMagic, static_cast<uint32_t>(n * 8 + 9)};
    words.insert(words.end(), table.begin(), table.end());
    words.push_back(static_cast<uint32_t>(n));
    std::string t;
    t.reserve(words.size() * 4 + 5);
    auto put = [&t](uint32_t v) {
      for (int i = 0; i < 4; ++i) t += static_cast<char>((v >> (8 * i)) & 0xFF);
    };
    for (uint32_t v : words) put(v);
    t += '\0';  // the descriptor: no checksums
    put(kSeekTableMagic);
    if (std::fwrite(t.data(), 1, t.size(), out.file()) != t.size())
      throw EnvironmentError(dst, std::string("write failed: ") + std::strerror(errno));
  }
  out.Commit();
  return total;
}

}  // namespace meshreuse
