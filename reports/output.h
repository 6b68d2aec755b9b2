// The one output-format helper: which format a command prints its tables in (--json, --csv,
// --markdown or aligned text for people), and writing a table's files into a result folder.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "core/table.h"

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

}  // namespace meshreuse
