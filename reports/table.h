// A result table rendered as aligned text (for people), CSV (for scripts) or Markdown (for notes).
// Cells are strings: the caller decides the precision, so every output shows the same digits.
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
  // Row r as a JSON object keyed by the header; numeric-looking cells become numbers.
  std::string RowJson(size_t r) const;
  std::string Json() const;  // all rows as a JSON array, one object per line

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

std::string Fixed(double v, int decimals);  // "%.*f"
std::string Grouped(long long v);           // 1234567 -> "1,234,567"

}  // namespace meshreuse
