// InputStream and CompressFile; see input_stream.h. Streaming decompression with libzstd's
// ZSTD_decompressStream (1 MiB compressed blocks).
#include "tracer/input_stream.h"

#include <unistd.h>
#include <zstd.h>
#include <zstd_errors.h>

#include <cstdio>
#include <cstring>

namespace meshreuse {

namespace {
constexpr unsigned char kZstdMagic[4] = {0x28, 0xB5, 0x2F, 0xFD};
// 32 MiB: every zstd level up to 19 and --ultra -20/-21 decode within it; a frame asking more
// (--ultra -22, --long) is refused rather than allowed ~100 MB from a few header bytes.
constexpr int kWindowLogMax = 25;
}

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
  if (got >= 4 && std::memcmp(peek_.data(), kZstdMagic, 4) == 0) {
    zstd_ = std::make_unique<Zstd>();
    zstd_->ds = ZSTD_createDStream();
    if (!zstd_->ds) throw InputError(path, 0, "cannot create a zstd decompression stream");
    ZSTD_DCtx_setParameter(zstd_->ds, ZSTD_d_windowLogMax, kWindowLogMax);
    const unsigned long long content = ZSTD_getFrameContentSize(peek_.data(), peek_.size());
    if (content != ZSTD_CONTENTSIZE_UNKNOWN && content != ZSTD_CONTENTSIZE_ERROR &&
        content <= static_cast<unsigned long long>(INT64_MAX))
      size_ = static_cast<int64_t>(content);
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

size_t InputStream::Read(void* buf, size_t n) {
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
  const std::string tmp = dst + ".tmp." + std::to_string(::getpid());
  std::FILE* out = std::fopen(tmp.c_str(), "wb");
  if (!out) throw InputError(dst, 0, std::string("cannot create: ") + std::strerror(errno));
  ZSTD_CCtx* cc = ZSTD_createCCtx();
  auto fail = [&](const std::string& why) {
    ZSTD_freeCCtx(cc);
    std::fclose(out);
    std::remove(tmp.c_str());
    throw InputError(dst, 0, why);
  };
  if (!cc) fail("cannot create a zstd compression context");
  ZSTD_CCtx_setParameter(cc, ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(cc, ZSTD_c_checksumFlag, 1);
  if (in.size() >= 0) ZSTD_CCtx_setPledgedSrcSize(cc, static_cast<unsigned long long>(in.size()));
  std::vector<char> ibuf(1 << 20), obuf(ZSTD_CStreamOutSize());
  while (true) {
    const size_t got = in.Read(ibuf.data(), ibuf.size());
    const ZSTD_EndDirective mode = got < ibuf.size() ? ZSTD_e_end : ZSTD_e_continue;
    ZSTD_inBuffer ib{ibuf.data(), got, 0};
    bool done = false;
    while (!done) {
      ZSTD_outBuffer ob{obuf.data(), obuf.size(), 0};
      const size_t left = ZSTD_compressStream2(cc, &ob, &ib, mode);
      if (ZSTD_isError(left)) fail(std::string("zstd: ") + ZSTD_getErrorName(left));
      if (std::fwrite(obuf.data(), 1, ob.pos, out) != ob.pos)
        fail(std::string("write error: ") + std::strerror(errno));
      done = mode == ZSTD_e_end ? left == 0 : ib.pos == ib.size;
    }
    if (mode == ZSTD_e_end) break;
  }
  ZSTD_freeCCtx(cc);
  if (std::fclose(out) != 0 || std::rename(tmp.c_str(), dst.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(dst, 0, std::string("cannot write: ") + std::strerror(errno));
  }
}

}  // namespace meshreuse
