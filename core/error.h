// The errors that reach the user, and the exit code each one means. Kernels throw; only the CLI's
// main prints and chooses the exit code (cli/main.cc), so no layer converts one error into another.
//   exit 0  done
//   exit 1  a bug: any other exception (std::logic_error, a failed internal check)
//   exit 2  bad input or options: InputError (a file's content, naming the file and the place),
//           UsageError (an option or argument, naming it)
//   exit 3  the environment failed: EnvironmentError (disk full, permission denied on an output,
//           a required program missing or crashing), naming the file or program
//   exit 130, 143  interrupted by SIGINT, SIGTERM (temporaries removed first; core/output_file.h)
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace meshreuse {

inline constexpr int kExitBug = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitEnvironment = 3;

// A file's content is at fault: "FILE:LINE: problem" (LINE omitted when there is no single line;
// binary formats name the byte offset or record in the problem).
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

// An option or argument is at fault; the message names it. A std::invalid_argument, so code that
// parses user strings (cache specs, ordering names, modes) throws it and callers that only care
// about "invalid" catch it as such.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The machine, not the input, failed: writing an output (disk full, permission denied, a
// read-only folder), or an external program (missing, killed). `what` names the file or program.
class EnvironmentError : public std::runtime_error {
 public:
  EnvironmentError(const std::string& what, const std::string& problem)
      : std::runtime_error(what.empty() ? problem : what + ": " + problem) {}
};

}  // namespace meshreuse
