// Output formats; see output.h.
#include "reports/output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/output_file.h"

namespace meshreuse {

std::string Render(const Table& t, OutputFormat f) {
  switch (f) {
    case OutputFormat::kJson:
      return t.Json();
    case OutputFormat::kCsv:
      return t.Csv();
    case OutputFormat::kMarkdown:
      return t.Markdown();
    case OutputFormat::kText:
      break;
  }
  return t.Aligned();
}

namespace {
// Renders `t` as `f` (a file extension or an output format) piece by piece into `out`.
void RenderTo(const Table& t, const std::string& f, std::FILE* out, const std::string& caption,
              const std::string& label, const std::string& path) {
  const Table::Emit emit = [&](const std::string& piece) {
    if (std::fwrite(piece.data(), 1, piece.size(), out) != piece.size())
      throw EnvironmentError(path, std::string("write failed: ") + std::strerror(errno));
  };
  if (f == "csv")
    t.RenderCsv(emit);
  else if (f == "md")
    t.RenderMarkdown(emit);
  else if (f == "json")
    t.RenderJson(emit);
  else if (f == "tex")
    t.RenderLatex(emit, caption, label);
  else if (f == "text")
    t.RenderAligned(emit);
  else
    throw std::logic_error("unknown table format " + f);
}
}  // namespace

void Print(const Table& t, OutputFormat f) {
  const char* name = f == OutputFormat::kJson       ? "json"
                     : f == OutputFormat::kCsv      ? "csv"
                     : f == OutputFormat::kMarkdown ? "md"
                                                    : "text";
  RenderTo(t, name, stdout, "", "", "standard output");
}

void WriteCsvFile(const std::string& path, const Table& t) {
  WriteAtomically(path, [&](std::FILE* f) { RenderTo(t, "csv", f, "", "", path); });
}

void WriteTableFiles(const std::string& dir, const std::string& name, const Table& t,
                     const std::vector<std::string>& exts, const std::string& caption) {
  for (const std::string& e : exts) {
    if (e != "csv" && e != "md" && e != "json" && e != "tex")
      throw std::logic_error("WriteTableFiles: unknown extension " + e);
    const std::string path = dir + "/" + name + "." + e;
    WriteAtomically(path, [&](std::FILE* f) { RenderTo(t, e, f, caption, "tab:" + name, path); });
  }
}

}  // namespace meshreuse
