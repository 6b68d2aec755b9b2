// A result table rendered as aligned text (for people), CSV (for scripts), Markdown (for notes),
// LaTeX (booktabs, for papers) or JSON. Cells are strings: the caller decides the precision, so
// every output shows the same digits. An empty cell is a missing value: "-" in aligned text and
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

  // A copy for reading: cells written at full precision (more than six decimals, e.g.
  // JsonNumber's) shown with four significant digits (no decimals from 1000 up). Aligned text,
  // Markdown and LaTeX are always rendered from it; CSV and JSON keep every digit.
  Table Readable() const;
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
  Table MarkReadable() && {
    readable_ = true;
    return std::move(*this);
  }
  bool readable_ = false;  // cells already rounded for reading
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

std::string Fixed(double v, int decimals);  // "%.*f"
std::string Grouped(long long v);           // 1234567 -> "1,234,567"

}  // namespace meshreuse
