// An input file read as a byte stream, plain or zstd-compressed, told apart by zstd's magic number
// (28 B5 2F FD, or a skippable frame's 5X 2A 4D 18) at its start: every trace reader reads through
// it, so a `.zst` trace (ours from `trace --compress`, libCacheSim's oracleGeneral `.zst`, or any
// other format compressed with the zstd tool) reads like the plain file. Opening follows InputFile
// (directories and devices refused, "-" for standard input). A corrupt or truncated compressed
// stream is an InputError naming the file and the compressed byte offset; decompression memory is
// bounded (a frame needing a window above 32 MiB, zstd --long or --ultra -22, is refused by name).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/input_file.h"

namespace meshreuse {

class InputStream {
 public:
  explicit InputStream(const std::string& path);
  ~InputStream();
  InputStream(const InputStream&) = delete;
  InputStream& operator=(const InputStream&) = delete;

  // Up to n bytes of the (decompressed) content; fewer only at its end.
  size_t Read(void* buf, size_t n);
  const std::string& path() const { return file_.path(); }
  bool compressed() const { return zstd_ != nullptr; }
  // Content bytes when known: a plain regular file's size, or the sum of the sizes its zstd
  // frame headers record (every frame must: `trace --compress` and `zstd FILE` do, pzstd does
  // not); -1 otherwise. Several frames and skippable frames (pzstd) read as `zstd -d` reads them.
  int64_t size() const { return size_; }
  // Reading by range (a chunk of a trace, reports/chunk_summary.h): continue at byte `offset` of
  // the content, and read at most `limit` bytes from there. A plain regular file only: a zstd
  // stream cannot be entered in the middle, a pipe cannot seek (InputError saying so).
  void SeekTo(uint64_t offset);
  void SetLimit(uint64_t limit) { limit_ = limit; }
  // Where the first line that begins at or after byte `offset` begins (the size at the end): a
  // text trace's chunk is the lines that begin in its byte range. Seeks (SeekTo's rules); a line
  // longer than max_line bytes is an InputError.
  uint64_t NextLineStart(uint64_t offset, size_t max_line = 4096);

 private:
  size_t ReadRaw(void* buf, size_t n);  // the file's bytes, after the peeked ones
  size_t ReadAll(void* buf, size_t n);  // Read without the limit
  InputFile file_;
  std::vector<char> peek_;  // bytes read to look for the magic, served first
  size_t peek_at_ = 0;
  int64_t size_ = -1;
  uint64_t limit_ = ~uint64_t{0};  // bytes Read may still return
  struct Zstd;
  std::unique_ptr<Zstd> zstd_;
};

// Compresses `src` into `dst` (core/output_file.h) at zstd level `level`, recording the content
// size in the frame header. Throws EnvironmentError when it cannot be written.
void CompressFile(const std::string& src, const std::string& dst, int level = 3);

}  // namespace meshreuse
