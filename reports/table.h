// A result table rendered as aligned text (for people), CSV (for scripts), Markdown (for notes),
// LaTeX (booktabs, for papers) or JSON. Cells are strings and the caller decides their precision;
// CSV and JSON show them as they are, the formats for reading round full-precision cells to four
// significant digits. An empty cell is a missing value: "-" in aligned text and
// Markdown, "--" in LaTeX, empty in CSV, null in JSON.
#pragma once

#include <string>
#include <vector>

namespace meshreuse {

class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void AddRow(std::vector<std::string> row);
  size_t Rows() const { return rows_.size(); }

  std::string Aligned() const;  // numbers right-aligned, text left-aligned
  std::string Csv() const;      // RFC 4180 quoting
  std::string Markdown() const;
  // A booktabs table (\toprule, \midrule, \bottomrule; needs \usepackage{booktabs}), text
  // escaped, numeric columns right-aligned; `caption` is LaTeX as is.
  std::string Latex(const std::string& caption, const std::string& label) const;
  // Row r as a JSON object keyed by the header; numeric-looking cells become numbers.
  std::string RowJson(size_t r) const;
  std::string Json() const;  // all rows as a JSON array, one object per line

 private:
  std::vector<bool> RightAligned() const;  // columns whose every present cell looks numeric
  // The cells for reading: those written at full precision (more than six decimals, e.g.
  // JsonNumber's) with four significant digits (no decimals from 1000 up). Aligned text, Markdown
  // and LaTeX render these; CSV and JSON keep every digit.
  std::vector<std::vector<std::string>> ReadableRows() const;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

std::string Fixed(double v, int decimals);  // "%.*f"
std::string Grouped(long long v);           // 1234567 -> "1,234,567"
std::string Duration(double seconds);       // 42 -> "42s", 125 -> "2m05s" (progress lines)

}  // namespace meshreuse
