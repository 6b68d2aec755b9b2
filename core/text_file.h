// Line-oriented reading of text input with exact line numbers for error messages. The file is
// streamed in 1 MiB blocks, so memory does not grow with the file: a line may be at most 1 MiB
// (longer: the file is not a mesh or trace; an endless stream without newlines fails there), and a
// NUL byte is refused as binary data. A UTF-8 byte-order mark at the start is skipped. Numbers are
// parsed with std::from_chars, which is locale-independent and does not accept trailing garbage.
// Reservable() caps what a reader sets aside for a header's count by what the file can still hold.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "core/input_file.h"

namespace meshreuse {

class TextFile {
 public:
  static constexpr size_t kMaxLine = size_t{1} << 20;

  // Throws InputError(path, 0, ...) when the file cannot be read (input_file.h). `comment` starts
  // a comment that runs to the end of the line ('\0' for none).
  explicit TextFile(std::string path, char comment = '#');

  // The next line with something on it, without comment and surrounding blanks. False at the end.
  // The view is valid until the next call.
  bool NextDataLine(std::string_view* line);
  // The next raw line (blank lines included), without the trailing newline. False at the end.
  bool NextLine(std::string_view* line);

  const std::string& path() const { return in_->path(); }
  int64_t line() const { return line_; }  // 1-based number of the last line returned
  // Bytes after the last line returned, or -1 when unknown (a pipe).
  int64_t BytesLeft() const;
  [[noreturn]] void Fail(const std::string& problem) const;
  // The words after the last "# meshreuse pair " comment seen so far ("" if none): files written
  // as a pair carry the same one (triangle_io.cc), so a reader can tell a mismatched pair.
  const std::string& pair_mark() const { return pair_mark_; }

  // Parsing helpers that fail at the current line, naming what was expected.
  int64_t ParseInt(std::string_view token, const char* what) const;
  double ParseDouble(std::string_view token, const char* what) const;
  // How many of a header's `count` items, `min_bytes` each at least, can still follow: what a
  // reader may reserve before the items arrive (for a pipe: at most 2^16; containers then grow as
  // records come). A hostile count then costs nothing until its lines are really there.
  int64_t Reservable(int64_t count, int64_t min_bytes) const;

 private:
  bool Fill();  // reads the next block; false at the end of the file

  std::unique_ptr<InputFile> in_;
  std::string buf_;
  size_t pos_ = 0;
  int64_t consumed_ = 0;  // bytes of the file before buf_[0]
  bool eof_ = false, first_ = true;
  int64_t line_ = 0;
  char comment_;
  std::string pair_mark_;
};

// The most tokens a line of the text mesh formats is split into (their readers' limit).
inline constexpr int kMaxCols = 64;

// Splits a line on blanks (spaces, tabs, carriage returns).
class Tokens {
 public:
  explicit Tokens(std::string_view s) : s_(s) {}
  bool Next(std::string_view* tok);
  // Fills up to n tokens; returns how many there were in all (may exceed n).
  int Split(std::string_view* out, int n);

 private:
  std::string_view s_;
  size_t pos_ = 0;
};

}  // namespace meshreuse
