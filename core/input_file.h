// Opening an input file for reading, the one way every reader does it: a RAII handle (no
// descriptor leaks when a reader rejects the file in its constructor), "-" for standard input,
// and refusal, naming the file, of what cannot be a finite input: a directory (fread would
// silently give nothing) and a character or block device such as /dev/zero (an endless stream).
// Pipes and standard input are accepted; their size is unknown. Header-only: the tracer's reader
// uses it too, and the tracer library sits below core.
#pragma once

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.h"

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
  // fread that turns a read error into InputError(path, 0, "read error: ..."), retrying reads
  // a signal interrupted: short only at the end of the file.
  size_t Read(void* buf, size_t n);

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  bool own_ = false;
  int64_t size_ = -1;
};

// Bytes read from standard input to look at it (a trace's magic) and given back: the next
// InputFile("-") reads them first. One process reads stdin once, so one buffer serves.
inline std::string& StdinPushback() {
  static std::string bytes;
  return bytes;
}

inline InputFile::InputFile(const std::string& path) : path_(path) {
  if (path == "-") {
    f_ = stdin;
  } else {
    f_ = std::fopen(path.c_str(), "rb");
    if (!f_) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
    own_ = true;
  }
  struct stat st {};
  if (::fstat(::fileno(f_), &st) != 0) {
    const std::string why = std::strerror(errno);
    if (own_) std::fclose(f_);
    throw InputError(path, 0, "cannot stat: " + why);
  }
  const char* refuse = S_ISDIR(st.st_mode)   ? "is a directory, not a file"
                       : S_ISCHR(st.st_mode) ? "is a character device, not a file"
                       : S_ISBLK(st.st_mode) ? "is a block device, not a file"
                                             : nullptr;
  if (refuse) {
    if (own_) std::fclose(f_);
    throw InputError(path, 0, refuse);
  }
  if (S_ISREG(st.st_mode)) size_ = static_cast<int64_t>(st.st_size);
}

inline InputFile::~InputFile() {
  if (own_ && f_) std::fclose(f_);
}

inline size_t InputFile::Read(void* buf, size_t n) {
  std::string& back = StdinPushback();
  if (f_ == stdin && !back.empty() && n > 0) {
    const size_t k = std::min(n, back.size());
    std::memcpy(buf, back.data(), k);
    back.erase(0, k);
    return k;
  }
  // A signal caught without SA_RESTART (libFuzzer's timer, a host's handler) interrupts a read
  // that waits on a pipe: EINTR is not the file's fault, so the read goes on where it stopped.
  size_t got = 0;
  while (got < n) {
    errno = 0;
    got += std::fread(static_cast<char*>(buf) + got, 1, n - got, f_);
    if (got == n || std::feof(f_)) break;
    if (!std::ferror(f_)) break;
    if (errno != EINTR)
      throw InputError(path_, 0, std::string("read error: ") + std::strerror(errno));
    std::clearerr(f_);
  }
  return got;
}

}  // namespace meshreuse
