// Table rendering; see table.h.
#include "reports/table.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace meshreuse {

void Table::AddRow(std::vector<std::string> row) {
  if (row.size() != header_.size())
    throw std::logic_error("table row has the wrong number of cells");
  rows_.push_back(std::move(row));
}

namespace {
bool LooksNumeric(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == ',' || c == '-' ||
          c == '+' || c == 'e' || c == '%' || c == 'x'))
      return false;
  return std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '-' || s[0] == '+';
}
}  // namespace

std::string Table::Aligned() const {
  std::vector<size_t> w(header_.size());
  for (size_t c = 0; c < header_.size(); ++c) {
    w[c] = header_[c].size();
    for (const auto& r : rows_) w[c] = std::max(w[c], r[c].size());
  }
  std::vector<bool> right(header_.size(), true);
  for (size_t c = 0; c < header_.size(); ++c)
    for (const auto& r : rows_)
      if (!LooksNumeric(r[c])) right[c] = false;
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (size_t c = 0; c < cells.size(); ++c) {
      const std::string pad(w[c] - cells[c].size(), ' ');
      s += (c ? "  " : "") +
           (right[c] ? pad + cells[c] : cells[c] + (c + 1 < cells.size() ? pad : ""));
    }
    return s + "\n";
  };
  std::string out = line(header_);
  size_t total = 0;
  for (size_t c = 0; c < w.size(); ++c) total += w[c] + (c ? 2 : 0);
  out += std::string(total, '-') + "\n";
  for (const auto& r : rows_) out += line(r);
  return out;
}

std::string Table::Csv() const {
  auto cell = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (size_t c = 0; c < cells.size(); ++c) s += (c ? "," : "") + cell(cells[c]);
    return s + "\n";
  };
  std::string out = line(header_);
  for (const auto& r : rows_) out += line(r);
  return out;
}

std::string Table::Markdown() const {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const auto& c : cells) s += " " + c + " |";
    return s + "\n";
  };
  std::string out = line(header_) + "|";
  for (size_t c = 0; c < header_.size(); ++c) out += "---|";
  out += "\n";
  for (const auto& r : rows_) out += line(r);
  return out;
}

std::string Table::Json() const {
  std::string s = "[";
  for (size_t r = 0; r < rows_.size(); ++r) s += std::string(r ? ",\n " : "\n ") + RowJson(r);
  return s + "\n]\n";
}

std::string Table::RowJson(size_t r) const {
  std::string s = "{";
  for (size_t c = 0; c < header_.size(); ++c) {
    const std::string& v = rows_[r][c];
    char* end = nullptr;
    std::strtod(v.c_str(), &end);
    const bool number = !v.empty() && end && *end == '\0' && v.find(',') == std::string::npos &&
                        v != "inf" && v != "nan";
    std::string quoted = "\"";
    for (char ch : v)
      quoted += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
    s += (c ? ", \"" : "\"") + header_[c] + "\": " + (number ? v : quoted + "\"");
  }
  return s + "}";
}

std::string Fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string Grouped(long long v) {
  std::string s = std::to_string(v < 0 ? -v : v);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(i, ",");
  return v < 0 ? "-" + s : s;
}

}  // namespace meshreuse
