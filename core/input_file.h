// Opening an input file for reading, the one way every reader does it: a RAII handle (no
// descriptor leaks when a reader rejects the file in its constructor), "-" for standard input,
// and refusal, naming the file, of what cannot be a finite input: a directory (fread would
// silently give nothing) and a character or block device such as /dev/zero (an endless stream).
// Pipes and standard input are accepted; their size is unknown.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace meshreuse {

class InputFile {
 public:
  // Throws InputError(path, 0, ...) when the file cannot be opened or is not a regular file,
  // pipe or socket.
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  std::FILE* get() const { return f_; }
  const std::string& path() const { return path_; }
  // Bytes in the file when it is a regular file, -1 for pipes and standard input.
  int64_t size() const { return size_; }
  // fread that turns a read error into InputError(path, 0, "read error: ...").
  size_t Read(void* buf, size_t n);

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  bool own_ = false;
  int64_t size_ = -1;
};

}  // namespace meshreuse
