// Errors that reach the user. An InputError names the file and (when known) the line where the
// input went wrong, so the CLI can print "FILE:LINE: problem" and exit with code 2. Kernels throw;
// only the CLI prints and chooses the exit code.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace meshreuse {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int64_t line, const std::string& problem)
      : std::runtime_error(Format(file, line, problem)),
        file_(std::move(file)),
        line_(line),
        problem_(problem) {}

  const std::string& file() const { return file_; }
  int64_t line() const { return line_; }  // 1-based; 0 when the problem has no single line
  const std::string& problem() const { return problem_; }

 private:
  static std::string Format(const std::string& file, int64_t line, const std::string& problem) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) s += ":" + std::to_string(line);
    return s + ": " + problem;
  }
  std::string file_;
  int64_t line_;
  std::string problem_;
};

}  // namespace meshreuse
