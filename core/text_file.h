// Line-oriented reading of text input with exact line numbers for error messages. The whole file is
// read at once (mesh files are read once, sequentially); numbers are parsed with std::from_chars,
// which is locale-independent and does not accept trailing garbage.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace meshreuse {

class TextFile {
 public:
  // Throws InputError(path, 0, "cannot open ...") when the file cannot be read.
  // `comment` starts a comment that runs to the end of the line ('\0' for none).
  explicit TextFile(std::string path, char comment = '#');

  // The next line with something on it, without comment and surrounding blanks. False at the end.
  bool NextDataLine(std::string_view* line);
  // The next raw line (blank lines included), without the trailing newline. False at the end.
  bool NextLine(std::string_view* line);

  const std::string& path() const { return path_; }
  int64_t line() const { return line_; }  // 1-based number of the last line returned
  [[noreturn]] void Fail(const std::string& problem) const;

  // Parsing helpers that fail at the current line, naming what was expected.
  int64_t ParseInt(std::string_view token, const char* what) const;
  double ParseDouble(std::string_view token, const char* what) const;

 private:
  std::string path_;
  std::string data_;
  size_t pos_ = 0;
  int64_t line_ = 0;
  char comment_;
};

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
