// Table rendering; see table.h.
#include "core/table.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace meshreuse {

void Table::AddRow(const std::vector<std::string>& row) {
  if (row.size() != header_.size())
    throw std::logic_error("table row has the wrong number of cells");
  row_start_.push_back(cells_.size());
  for (const std::string& c : row) {
    // A NUL ends a cell here; no cell has one (names from files are made printable).
    cells_.append(c.data(), std::min(c.size(), std::strlen(c.c_str())));
    cells_ += '\0';
  }
}

void Table::Append(const Table& other) {
  if (other.header_ != header_) throw std::logic_error("appending a table of other columns");
  const uint64_t at = cells_.size();
  cells_ += other.cells_;
  for (uint64_t start : other.row_start_) row_start_.push_back(at + start);
}

std::vector<std::string> Table::Row(size_t r) const {
  std::vector<std::string> out;
  const char* p = cells_.data() + row_start_.at(r);
  for (size_t c = 0; c < header_.size(); ++c) {
    out.emplace_back(p);
    p += out.back().size() + 1;
  }
  return out;
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

namespace {
// A cell written at full precision (more than six decimals) shown with four significant digits.
std::string ReadableCell(const std::string& c) {
  const size_t dot = c.find('.');
  if (dot == std::string::npos || c.size() - dot - 1 <= 6 ||
      c.find_first_of("eE,") != std::string::npos)
    return c;
  char* end = nullptr;
  const double v = std::strtod(c.c_str(), &end);
  if (!end || *end != '\0') return c;
  char b[64];
  std::snprintf(b, sizeof b, std::fabs(v) >= 1000 ? "%.0f" : "%.4g", v);
  return b;
}
}  // namespace

template <class F>
void Table::ForEachRow(bool readable, F&& f) const {
  std::vector<std::string> row(header_.size());
  for (size_t r = 0; r < row_start_.size(); ++r) {
    const char* p = cells_.data() + row_start_[r];
    for (size_t c = 0; c < header_.size(); ++c) {
      row[c].assign(p);
      p += row[c].size() + 1;
      if (readable) row[c] = ReadableCell(row[c]);
    }
    f(row);
  }
}

void Table::RenderAligned(const Emit& emit) const {
  std::vector<size_t> w(header_.size());
  for (size_t c = 0; c < header_.size(); ++c) w[c] = header_[c].size();
  ForEachRow(true, [&](const std::vector<std::string>& r) {
    for (size_t c = 0; c < header_.size(); ++c)
      w[c] = std::max(w[c], std::max<size_t>(r[c].size(), 1));
  });
  const std::vector<bool> right = RightAligned();
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (size_t c = 0; c < cells.size(); ++c) {
      const std::string cell = cells[c].empty() ? "-" : cells[c];
      const std::string pad(w[c] - cell.size(), ' ');
      s += (c ? "  " : "") + (right[c] ? pad + cell : cell + (c + 1 < cells.size() ? pad : ""));
    }
    return s + "\n";
  };
  emit(line(header_));
  size_t total = 0;
  for (size_t c = 0; c < w.size(); ++c) total += w[c] + (c ? 2 : 0);
  emit(std::string(total, '-') + "\n");
  ForEachRow(true, [&](const std::vector<std::string>& r) { emit(line(r)); });
}

void Table::RenderCsv(const Emit& emit) const {
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
  emit(line(header_));
  ForEachRow(false, [&](const std::vector<std::string>& r) { emit(line(r)); });
}

std::vector<bool> Table::RightAligned() const {
  std::vector<bool> right(header_.size(), true);
  ForEachRow(false, [&](const std::vector<std::string>& r) {
    for (size_t c = 0; c < header_.size(); ++c)
      if (!r[c].empty() && !LooksNumeric(r[c])) right[c] = false;
  });
  return right;
}

void Table::RenderMarkdown(const Emit& emit) const {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const auto& c : cells) {
      std::string cell;  // a '|' in a cell (a file name) would end it: escaped
      for (char ch : c) ch == '|' ? cell += "\\|" : cell += ch;
      s += " " + (c.empty() ? std::string("-") : cell) + " |";
    }
    return s + "\n";
  };
  const std::vector<bool> right = RightAligned();
  std::string out = line(header_) + "|";
  for (size_t c = 0; c < header_.size(); ++c) out += right[c] ? "---:|" : "---|";
  emit(out + "\n");
  ForEachRow(true, [&](const std::vector<std::string>& r) { emit(line(r)); });
}

void Table::RenderLatex(const Emit& emit, const std::string& caption,
                        const std::string& label) const {
  auto esc = [](const std::string& t) {
    std::string o;
    for (char ch : t) switch (ch) {
        case '_':
        case '%':
        case '&':
        case '#':
        case '$':
        case '{':
        case '}':
          o += '\\', o += ch;
          break;
        case '~':
          o += "\\textasciitilde{}";
          break;
        case '^':
          o += "\\textasciicircum{}";
          break;
        case '\\':
          o += "\\textbackslash{}";
          break;
        default:
          o += ch;
      }
    return o;
  };
  const std::vector<bool> right = RightAligned();
  std::string spec;
  for (bool r : right) spec += r ? 'r' : 'l';
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (size_t c = 0; c < cells.size(); ++c)
      s += (c ? " & " : "") + (cells[c].empty() ? "--" : esc(cells[c]));
    return s + " \\\\\n";
  };
  std::string out =
      "% Generated by meshreuse; needs \\usepackage{booktabs}.\n\\begin{table}[htbp]\n"
      "\\centering\n\\small\n\\begin{tabular}{" +
      spec + "}\n\\toprule\n";
  emit(out + line(header_) + "\\midrule\n");
  ForEachRow(true, [&](const std::vector<std::string>& r) { emit(line(r)); });
  emit("\\bottomrule\n\\end{tabular}\n\\caption{" + caption + "}\n\\label{" + label +
       "}\n\\end{table}\n");
}

namespace {
// A cell as a JSON value: null when empty, a number when it reads as one in full (integers exactly
// as unsigned or signed 64-bit), a string otherwise.
nlohmann::ordered_json CellJson(const std::string& v) {
  if (v.empty()) return nullptr;
  if (v.find_first_not_of("0123456789") == std::string::npos && v.size() <= 20) {
    errno = 0;
    const unsigned long long u = std::strtoull(v.c_str(), nullptr, 10);
    if (errno == 0) return static_cast<uint64_t>(u);
  }
  if (v[0] == '-' && v.size() > 1 && v.find_first_not_of("0123456789", 1) == std::string::npos &&
      v.size() <= 20) {
    errno = 0;
    const long long s = std::strtoll(v.c_str(), nullptr, 10);
    if (errno == 0) return static_cast<int64_t>(s);
  }
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  const bool number = end && *end == '\0' && v.find(',') == std::string::npos &&
                      v.find_first_of("xXnNiI") == std::string::npos && std::isfinite(d);
  if (number) return d;
  return v;
}
}  // namespace

nlohmann::ordered_json Table::JsonValue() const {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  ForEachRow(false, [&](const std::vector<std::string>& row) {
    nlohmann::ordered_json o = nlohmann::ordered_json::object();
    for (size_t c = 0; c < header_.size(); ++c) o[header_[c]] = CellJson(row[c]);
    a.push_back(std::move(o));
  });
  return a;
}

void Table::RenderJson(const Emit& emit) const {  // row by row: no document of the whole table
  emit("[");
  bool first = true;
  ForEachRow(false, [&](const std::vector<std::string>& row) {
    nlohmann::ordered_json o = nlohmann::ordered_json::object();
    for (size_t c = 0; c < header_.size(); ++c) o[header_[c]] = CellJson(row[c]);
    emit((first ? "\n " : ",\n ") + o.dump());
    first = false;
  });
  emit("\n]\n");
}

namespace {
std::string Collect(const std::function<void(const Table::Emit&)>& render) {
  std::string s;
  render([&](const std::string& piece) { s += piece; });
  return s;
}
}  // namespace

std::string Table::Aligned() const {
  return Collect([&](const Emit& e) { RenderAligned(e); });
}
std::string Table::Csv() const {
  return Collect([&](const Emit& e) { RenderCsv(e); });
}
std::string Table::Markdown() const {
  return Collect([&](const Emit& e) { RenderMarkdown(e); });
}
std::string Table::Json() const {
  return Collect([&](const Emit& e) { RenderJson(e); });
}
std::string Table::Latex(const std::string& caption, const std::string& label) const {
  return Collect([&](const Emit& e) { RenderLatex(e, caption, label); });
}

std::string ExactNumber(double v) {
  if (!std::isfinite(v)) return "";
  if (v == std::floor(v) && std::fabs(v) < 9007199254740992.0) {  // an integer: no exponent
    char b[32];
    std::snprintf(b, sizeof b, "%.0f", v);
    return std::string(b) == "-0" ? "0" : b;
  }
  for (int p = 6; p <= 17; ++p) {  // the shortest that reads back exactly
    char b[32];
    std::snprintf(b, sizeof b, "%.*g", p, v);
    if (std::strtod(b, nullptr) == v) return b;
  }
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
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

std::string Duration(double seconds) {
  char b[32];
  if (seconds < 90)
    std::snprintf(b, sizeof b, "%.0fs", seconds);
  else
    std::snprintf(b, sizeof b, "%dm%02ds", static_cast<int>(seconds / 60),
                  static_cast<int>(seconds) % 60);
  return b;
}

}  // namespace meshreuse
