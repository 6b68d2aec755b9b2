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

// The content size of a compressed regular file: every frame walked by its headers alone (RFC
// 8878: frame header, 3-byte block headers, optional checksum; skippable frames skipped), without
// decompressing. -1 when a frame does not record its size. A walk that does not end at the file's
// end (a file cut short, damage) gives the first frame's size, so that the decompressor, not a
// missing size, reports what is wrong.
int64_t ZstdContentSize(std::FILE* f, int64_t file_bytes) {
  const int fd = fileno(f);
  auto at = [&](int64_t off, void* buf, size_t n) {
    return off >= 0 && off + static_cast<int64_t>(n) <= file_bytes &&
           pread(fd, buf, n, off) == static_cast<ssize_t>(n);
  };
  int64_t off = 0, total = 0, first = -1;
  auto broken = [&] { return first; };
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
    if (fcs == 0) return -1;  // this frame does not record its size
    uint64_t content = 0;
    for (size_t i = 0; i < fcs; ++i) content |= uint64_t{h[header - fcs + i]} << (8 * i);
    if (fcs == 2) content += 256;
    if (content > static_cast<uint64_t>(INT64_MAX - total)) return broken();
    if (first < 0) first = static_cast<int64_t>(content);
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
  return off == file_bytes ? total : broken();
}
}  // namespace

struct InputStream::Zstd {
  ZSTD_DStream* ds = nullptr;
  std::vector<char> in = std::vector<char>(1 << 20);
  ZSTD_inBuffer ib{nullptr, 0, 0};
  uint64_t consumed = 0;  // compressed bytes handed to zstd before the current block
  bool eof = false;
  size_t last_ret = 0;  // 0 when the last frame ended cleanly
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
    if (file_.size() >= 0) size_ = ZstdContentSize(file_.get(), file_.size());
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

void InputStream::SeekTo(uint64_t offset) {
  if (zstd_)
    throw InputError(path(), 0,
                     "a zstd-compressed trace cannot be read from the middle (a chunk): "
                     "decompress it first (zstd -d)");
  if (file_.size() < 0)
    throw InputError(path(), 0,
                     "a chunk needs a regular file: a pipe or standard input cannot seek");
  if (offset > static_cast<uint64_t>(file_.size()))
    throw InputError(path(), 0, "byte offset " + std::to_string(offset) + " is past the end");
  if (offset < peek_.size()) {
    peek_at_ = offset;
    if (fseeko(file_.get(), static_cast<off_t>(peek_.size()), SEEK_SET) != 0)
      throw InputError(path(), 0, std::string("cannot seek: ") + std::strerror(errno));
    return;
  }
  peek_at_ = peek_.size();
  if (fseeko(file_.get(), static_cast<off_t>(offset), SEEK_SET) != 0)
    throw InputError(path(), 0, std::string("cannot seek: ") + std::strerror(errno));
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
  return got;
}

size_t InputStream::ReadAll(void* buf, size_t n) {
  if (!zstd_) return ReadRaw(buf, n);
  Zstd& z = *zstd_;
  ZSTD_outBuffer ob{buf, n, 0};
  while (ob.pos < ob.size) {
    if (z.ib.pos == z.ib.size) {
      if (z.eof) break;
      z.consumed += z.ib.size;
      const size_t got = ReadRaw(z.in.data(), z.in.size());
      if (got == 0) {
        z.eof = true;
        if (z.last_ret != 0)
          throw InputError(path(), 0,
                           "truncated zstd stream: it ends inside a frame at compressed byte " +
                               std::to_string(z.consumed));
        break;
      }
      z.ib = ZSTD_inBuffer{z.in.data(), got, 0};
    }
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
  }
  return ob.pos;
}

void CompressFile(const std::string& src, const std::string& dst, int level) {
  InputFile in(src);
  AtomicOutput out(dst);
  struct Ctx {
    ZSTD_CCtx* cc = ZSTD_createCCtx();
    ~Ctx() { ZSTD_freeCCtx(cc); }
  } ctx;
  if (!ctx.cc) throw std::runtime_error("cannot create a zstd compression context");
  ZSTD_CCtx_setParameter(ctx.cc, ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(ctx.cc, ZSTD_c_checksumFlag, 1);
  if (in.size() >= 0)
    ZSTD_CCtx_setPledgedSrcSize(ctx.cc, static_cast<unsigned long long>(in.size()));
  std::vector<char> ibuf(1 << 20), obuf(ZSTD_CStreamOutSize());
  while (true) {
    const size_t got = in.Read(ibuf.data(), ibuf.size());
    const ZSTD_EndDirective mode = got < ibuf.size() ? ZSTD_e_end : ZSTD_e_continue;
    ZSTD_inBuffer ib{ibuf.data(), got, 0};
    bool done = false;
    while (!done) {
      ZSTD_outBuffer ob{obuf.data(), obuf.size(), 0};
      const size_t left = ZSTD_compressStream2(ctx.cc, &ob, &ib, mode);
      if (ZSTD_isError(left))
        throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(left));
      if (std::fwrite(obuf.data(), 1, ob.pos, out.file()) != ob.pos)
        throw EnvironmentError(dst, std::string("write failed: ") + std::strerror(errno));
      done = mode == ZSTD_e_end ? left == 0 : ib.pos == ib.size;
    }
    if (mode == ZSTD_e_end) break;
  }
  out.Commit();
}

}  // namespace meshreuse
