// An input file read as a byte stream, plain or zstd-compressed, told apart by zstd's magic number
// (28 B5 2F FD, or a skippable frame's 5X 2A 4D 18) at its start: every trace reader reads through
// it, so a `.zst` trace (ours from `trace --compress`, libCacheSim's oracleGeneral `.zst`, or any
// other format compressed with the zstd tool) reads like the plain file. Opening follows InputFile
// (directories and devices refused, "-" for standard input). A corrupt or truncated compressed
// stream is an InputError naming the file and the compressed byte offset; decompression memory is
// bounded (a frame needing a window above 32 MiB, zstd --long or --ultra -22, is refused by name).
// A compressed file is entered in the middle (a chunk) at the start of a zstd frame: frames are
// independent (RFC 8878). Where each begins, in the file and in the content, comes from the seek
// table of zstd's seekable format when the file ends in one (`meshreuse compress` and `trace
// --compress` write it, with 4 MiB frames), else from the frame headers, walked once at opening
// (a read per 128 KiB block); what the table says is checked as the frames are decompressed.
// Reading by range decompresses from the last frame that begins at or before the range and, at the
// range's end, on to where the next range's frame begins (or the file's end): together the ranges
// decompress every frame exactly as a whole read does, so a damaged frame or checksum fails some
// chunk whenever it fails the whole read.
#pragma once

#include <cstdint>
#include <functional>
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
  // Whether size() is a seek table's sum, a claim checked only as the decompressor passes its
  // places: a size that cannot be right (part of a record) then blames the table, not the file.
  bool size_from_table() const { return size_from_table_; }
  // Whether SeekTo works: a plain regular file, or a compressed regular file that ends in a seek
  // table or whose frames all record their sizes.
  bool seekable() const;
  // The places SeekTo starts decompressing from: frame starts (at most 2^16 of them, evenly
  // thinned beyond; none in a damaged file, which is entered at its start); for a plain file,
  // its size in bytes (any byte).
  uint64_t entry_points() const;
  // Reading by range (a chunk of a trace, reports/chunks/summarize_chunk.h): continue at byte
  // `offset` of the content, and read at most `limit` bytes from there. A regular file that is
  // seekable() only: a pipe cannot seek, a zstd stream without a seek table whose frames do not
  // record their sizes cannot be entered in the middle (InputError saying so).
  void SeekTo(uint64_t offset);
  void SetLimit(uint64_t limit) { limit_ = limit; }
  // Where the first line that begins at or after byte `offset` begins (the size at the end): a
  // text trace's chunk is the lines that begin in its byte range. Seeks (SeekTo's rules); a line
  // longer than max_line bytes is an InputError.
  uint64_t NextLineStart(uint64_t offset, size_t max_line = 4096);

 private:
  size_t ReadRaw(void* buf, size_t n);  // the file's bytes, after the peeked ones
  size_t ReadAll(void* buf, size_t n);  // Read without the limit
  void SeekRaw(uint64_t offset);        // the file's bytes from `offset` on
  struct Zstd;
  // One call of the decompressor into buf[*pos, n), the file read on when its input is used up;
  // false at the file's end.
  bool Step(Zstd& z, void* buf, size_t n, size_t* pos);
  void Drain(Zstd& z);  // at a range's end: on to the next range's first frame, or the file's end
  InputFile file_;
  std::vector<char> peek_;  // bytes read to look for the magic, served first
  size_t peek_at_ = 0;
  int64_t size_ = -1;
  bool size_from_table_ = false;
  uint64_t limit_ = ~uint64_t{0};  // bytes Read may still return
  std::unique_ptr<Zstd> zstd_;
};

// Compresses `src` (whatever InputStream reads: a plain file, a zstd one, which is re-framed, or
// "-" for standard input) into `dst` (core/output_file.h) at zstd level `level`, in independent
// frames of `frame_bytes` of content each (the last shorter; 1 byte to kZstdMaxFrameBytes), each
// recording its content size and a checksum: a chunk of the trace then decompresses at most one
// frame it does not use. The file ends in a seek table (zstd's seekable format, 8 bytes a frame;
// up to 2^24 frames), so readers find the frames without walking their blocks; `zstd -d` skips
// it. At level 3 (a 2 MiB window) 4 MiB frames cost little where a sweep outgrows the window (a
// 1.46 GB mesh trace: 141.8 MB against 141.6 MB for `zstd -3` in one frame; 160 MB of uniform u64
// ids: 66.69 against 66.73 MB), but a trace whose sweeps fit the window, compressed from the
// second sweep on by reference to the first, starts over in each frame (a 15.8 MB trace of 1.3
// MB sweeps: 0.49 MB against 0.22 MB). Memory: two frames' worth and the table.
// `progress` (when given) gets the content bytes written after each frame. Returns them all.
// Throws InputError for a bad input, EnvironmentError when `dst` cannot be written.
constexpr uint64_t kZstdFrameBytes = uint64_t{4} << 20;
constexpr uint64_t kZstdMaxFrameBytes = uint64_t{256} << 20;
uint64_t CompressFile(const std::string& src, const std::string& dst, int level = 3,
                      uint64_t frame_bytes = kZstdFrameBytes,
                      const std::function<void(uint64_t)>& progress = {});

}  // namespace meshreuse
