// meshreuse compress: any trace (ours or another tool's, plain, zstd or on standard input) into
// zstd frames that record their sizes, ended by a seek table (zstd's seekable format;
// tracer/input_stream.h), so that chunks, threads and MPI ranks can enter it at frames; a trace in
// one zstd frame (as the zstd tool writes it) is re-framed without a step of its own.
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/common.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/table.h"
#include "tracer/input_stream.h"

namespace meshreuse::cli {

int CompressCommand(const Args& args) {
  po::options_description desc("options");
  std::string in, out, level_text = "3", frame_text = std::to_string(kZstdFrameBytes >> 10);
  desc.add_options()("input", po::value(&in)->required(),
                     "the trace: any file (plain, zstd, or '-' for standard input)")(
      "output,o", po::value(&out)->required(), "the compressed trace")(
      "level", po::value(&level_text)->default_value("3"), "zstd level, 1-19")(
      "frame-kib", po::value(&frame_text)->default_value(frame_text),
      "content per frame in KiB (1 to 262144): a chunk decompresses at most one frame it does "
      "not use")("quiet,q", "no progress on stderr");
  po::positional_options_description pos;
  pos.add("input", 1);
  po::variables_map vm;
  if (!ParseOptions(args, "compress INPUT -o OUTPUT",
                    "Compresses a trace with zstd in independent frames that record their sizes "
                    "(4 MiB of content each by default), ended by a seek table (zstd's seekable "
                    "format), as `trace --compress` writes ours: `analyze --threads`, `--chunk` "
                    "and meshreuse-mpi then start each chunk at a frame. A zstd input is "
                    "decompressed and re-framed. The output is a zstd file like any other (`zstd "
                    "-d` reads it).",
                    desc, pos, vm))
    return 0;
  const int level = static_cast<int>(ParseCount(level_text, "--level", 1, 19));
  const uint64_t frame = ParseCount(frame_text, "--frame-kib", 1, kZstdMaxFrameBytes >> 10) << 10;
  CheckOutputPath(out, "-o", {in});
  const Progress progress(vm.count("quiet") > 0);
  const Log log = MakeLog(progress);
  uint64_t said = 0;
  const uint64_t bytes = CompressFile(in, out, level, frame, [&](uint64_t done) {
    if (done - said >= (uint64_t{256} << 20)) {
      said = done;
      log.Say("compressed " + Fixed(static_cast<double>(done) / 1e6, 0) + " MB");
    }
  });
  std::error_code ec;
  const auto packed = std::filesystem::file_size(out, ec);
  const uint64_t frames = bytes == 0 ? 1 : (bytes + frame - 1) / frame;
  std::printf("wrote %s: %s MB in %llu frame(s) of %llu KiB, %s MB compressed\n", out.c_str(),
              Fixed(static_cast<double>(bytes) / 1e6, 1).c_str(),
              static_cast<unsigned long long>(frames), static_cast<unsigned long long>(frame >> 10),
              ec ? "?" : Fixed(static_cast<double>(packed) / 1e6, 1).c_str());
  return 0;
}

}  // namespace meshreuse::cli
