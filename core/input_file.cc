// InputFile; see input_file.h.
#include "core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace meshreuse {

InputFile::InputFile(const std::string& path) : path_(path) {
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

InputFile::~InputFile() {
  if (own_ && f_) std::fclose(f_);
}

size_t InputFile::Read(void* buf, size_t n) {
  const size_t got = std::fread(buf, 1, n, f_);
  if (got < n && std::ferror(f_))
    throw InputError(path_, 0, std::string("read error: ") + std::strerror(errno));
  return got;
}

}  // namespace meshreuse
