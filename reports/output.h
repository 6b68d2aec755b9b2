// The one output-format helper: which format a command prints its tables in (--json, --csv,
// --markdown or aligned text for people), writing a table's files into a result folder, and what
// a runner produced (RunOutput), which the CLI prints and writes in one place (cli/common.h Emit).
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/table.h"
#include "reports/run_info.h"

namespace meshreuse {

enum class OutputFormat { kText, kJson, kCsv, kMarkdown };

// The table in that format (text: aligned, for people).
std::string Render(const Table& t, OutputFormat f);
// Render to stdout.
void Print(const Table& t, OutputFormat f);

// Writes DIR/NAME.EXT for each of `exts` (csv, md, json, tex; tex needs `caption`), each
// atomically (core/output_file.h).
void WriteTableFiles(const std::string& dir, const std::string& name, const Table& t,
                     const std::vector<std::string>& exts, const std::string& caption = "");
// Writes `path` as the table's CSV, atomically, a few rows at a time.
void WriteCsvFile(const std::string& path, const Table& t);

// What a runner produced, by where it goes: the aligned view for people (tables and lines, in
// order), what --csv and --json print, and the files under --out (tables in their formats, text
// files, run.json). Tables are shared, not copied, between the places they go (a simulation's
// per-sweep rows may be large).
struct RunOutput {
  using TablePtr = std::shared_ptr<const Table>;
  static TablePtr Share(Table t) { return std::make_shared<const Table>(std::move(t)); }
  std::string tool;                                       // "meshreuse analyze": run.json's
  std::vector<std::variant<TablePtr, std::string>> text;  // a string is printed as a line
  TablePtr csv;                                           // --csv (and --markdown)
  std::variant<Json, TablePtr> json;                      // --json: an object (dump(1)), or a table
  struct TableFile {
    std::string name;  // DIR/NAME.EXT
    TablePtr table;
    std::vector<std::string> exts;  // csv, md, json, tex
  };
  std::vector<TableFile> tables;
  std::vector<std::pair<std::string, std::string>> files;  // DIR/NAME: its text
  Json configuration, extra;                               // DIR/run.json
};

}  // namespace meshreuse
