// A result table rendered as aligned text (for people), CSV (for scripts), Markdown (for notes),
// LaTeX (booktabs, for papers) or JSON (nlohmann::json, so strings are always escaped). The one
// output shape of every layer: analyses dump their rows into it (analysis/*), runners build theirs
// (reports/*), the CLI prints it. Cells are strings and the caller decides their precision;
// CSV and JSON show them as they are, the formats for reading round full-precision cells to four
// significant digits. An empty cell is a missing value: "-" in aligned text and
// Markdown, "--" in LaTeX, empty in CSV, null in JSON.
#pragma once

#include <functional>
// The JSON type declared only: its 25,000-line header went into every file of analysis/ that
// includes this one (through the histograms and simulators); analysis/ compiled in 17.6 s of
// CPU instead of 20.8 without it (fresh Ninja builds).
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace meshreuse {

// A table row's cells with `more` added at its end.
inline void Append(std::vector<std::string>* row, const std::vector<std::string>& more) {
  row->insert(row->end(), more.begin(), more.end());
}

class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void AddRow(const std::vector<std::string>& row);
  // Every row of `other`, after these (std::logic_error unless the headers are equal).
  void Append(const Table& other);
  size_t Rows() const { return row_start_.size(); }
  const std::vector<std::string>& Header() const { return header_; }
  // Row r's cells (a copy; for tests and small tables).
  std::vector<std::string> Row(size_t r) const;

  std::string Aligned() const;  // numbers right-aligned, text left-aligned
  std::string Csv() const;      // RFC 4180 quoting
  std::string Markdown() const;
  // A booktabs table (\toprule, \midrule, \bottomrule; needs \usepackage{booktabs}), text
  // escaped, numeric columns right-aligned; `caption` is LaTeX as is.
  std::string Latex(const std::string& caption, const std::string& label) const;
  // All rows as a JSON array of objects keyed by the header, in column order: numeric-looking
  // cells become numbers, empty cells null. Json() is its text (one object per line).
  nlohmann::ordered_json JsonValue() const;
  std::string Json() const;
  // The same renderings, piece by piece (a few lines at a time) to `emit`: a large table is
  // written to a file or stdout without its whole text in memory.
  using Emit = std::function<void(const std::string&)>;
  void RenderAligned(const Emit& emit) const;
  void RenderCsv(const Emit& emit) const;
  void RenderMarkdown(const Emit& emit) const;
  void RenderLatex(const Emit& emit, const std::string& caption, const std::string& label) const;
  void RenderJson(const Emit& emit) const;

 private:
  std::vector<bool> RightAligned() const;  // columns whose every present cell looks numeric
  // Calls f(cells) for every row; with `readable`, cells written at full precision (more than
  // six decimals, e.g. ExactNumber's) get four significant digits (no decimals from 1000 up), as
  // aligned text, Markdown and LaTeX show them; CSV and JSON keep every digit.
  template <class F>
  void ForEachRow(bool readable, F&& f) const;
  std::vector<std::string> header_;
  // The cells, each followed by a NUL, row after row, and where each row starts: a table of a
  // million rows is its text plus 8 bytes a row, not a million vectors of strings.
  std::string cells_;
  std::vector<uint64_t> row_start_;
};

// A double as the shortest decimal that reads back exactly (integers in full, no exponent below
// 2^53); "" for NaN and infinities, a missing value in every format. For cells kept at full
// precision.
std::string ExactNumber(double v);
std::string Fixed(double v, int decimals);  // "%.*f"
std::string Grouped(long long v);           // 1234567 -> "1,234,567"
std::string Duration(double seconds);       // 42 -> "42s", 125 -> "2m05s" (progress lines)

}  // namespace meshreuse
