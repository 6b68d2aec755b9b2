// libFuzzer harness: a chunk summary's payload (reports/chunks/summary_file.h) behind a header
// whose size and checksum are made to match, so the fuzzer reaches the parser instead of the
// checksum; an accepted summary of one chunk is then merged into a whole analysis and its tables
// built. The same bytes are also read back as a file and through a pipe (ReadSummary parses as it
// streams, a pipe without a size to check): the verdict and message must be those of the
// in-memory decoder, or the harness aborts.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "core/error.h"
#include "reports/analyze.h"
#include "reports/chunks/merge_summaries.h"
#include "reports/chunks/summary_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  std::string file(32, '\0');
  std::memcpy(&file[0], "MRSUMRY", 8);
  const uint32_t version = 1;
  const uint64_t bytes = size;
  const uint64_t sum = SummaryChecksum(reinterpret_cast<const char*>(data), size);
  std::memcpy(&file[8], &version, 4);
  std::memcpy(&file[16], &bytes, 8);
  std::memcpy(&file[24], &sum, 8);
  file.append(reinterpret_cast<const char*>(data), size);
  static const std::string path = [] {
    char t[] = "/tmp/meshreuse-fuzz-summary-XXXXXX";
    const int fd = mkstemp(t);
    if (fd < 0) std::abort();
    close(fd);
    return std::string(t);
  }();
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(file.data(), 1, file.size(), f) != file.size()) std::abort();
    std::fclose(f);
  }
  std::string streamed = "read", whole = "read";
  try {
    meshreuse::ReadSummary(path);
  } catch (const meshreuse::InputError& e) {
    streamed = e.problem();
  }
  try {
    meshreuse::DecodeSummary(path, file);
  } catch (const meshreuse::InputError& e) {
    whole = e.problem();
  }
  if (streamed != whole) {
    std::fprintf(stderr, "streamed read: %s\nin memory: %s\n", streamed.c_str(), whole.c_str());
    std::abort();
  }
  // Through a pipe: the writer is a thread; a reader that stops early closes its end (EPIPE).
  static const bool no_sigpipe = (std::signal(SIGPIPE, SIG_IGN), true);
  (void)no_sigpipe;
  int fds[2];
  if (::pipe(fds) != 0) std::abort();
  std::thread writer([&] {
    for (size_t at = 0; at < file.size();) {
      const ssize_t n = ::write(fds[1], file.data() + at, file.size() - at);
      if (n <= 0) break;
      at += static_cast<size_t>(n);
    }
    ::close(fds[1]);
  });
  std::string piped = "read";
  try {
    meshreuse::ReadSummary("/proc/self/fd/" + std::to_string(fds[0]));
  } catch (const meshreuse::InputError& e) {
    piped = e.problem();
  }
  ::close(fds[0]);
  writer.join();
  if (piped != whole) {
    std::fprintf(stderr, "through a pipe: %s\nin memory: %s\n", piped.c_str(), whole.c_str());
    std::abort();
  }
  try {
    SummaryFile s = DecodeSummary("fuzz", file);
    if (s.id.chunks != 1) return 0;
    SummaryMerger m(true);
    m.Add(std::move(s), "fuzz", 1);
    AnalyzeConfig cfg;
    const AnalyzeResult r = m.Finish();
    AnalyzeTable(r, cfg, false);
    HistogramTable(r);
    ProfileTable(r);
    MrcTable(r);
  } catch (const InputError&) {
  }
  return 0;
}
