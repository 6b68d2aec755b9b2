// TextFile and Tokens; see text_file.h.
#include "core/text_file.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace meshreuse {

namespace {
bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view Trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && IsBlank(s[b])) ++b;
  while (e > b && IsBlank(s[e - 1])) --e;
  return s.substr(b, e - b);
}
}  // namespace

TextFile::TextFile(std::string path, char comment) : path_(std::move(path)), comment_(comment) {
  std::FILE* f = std::fopen(path_.c_str(), "rb");
  if (!f) throw InputError(path_, 0, std::string("cannot open: ") + std::strerror(errno));
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) data_.append(buf, n);
  const bool bad = std::ferror(f);
  std::fclose(f);
  if (bad) throw InputError(path_, 0, "read error");
}

bool TextFile::NextLine(std::string_view* line) {
  if (pos_ >= data_.size()) return false;
  const size_t nl = data_.find('\n', pos_);
  const size_t end = nl == std::string::npos ? data_.size() : nl;
  *line = std::string_view(data_).substr(pos_, end - pos_);
  if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
  pos_ = nl == std::string::npos ? data_.size() : nl + 1;
  ++line_;
  return true;
}

bool TextFile::NextDataLine(std::string_view* line) {
  std::string_view l;
  while (NextLine(&l)) {
    if (comment_ != '\0') {
      const size_t c = l.find(comment_);
      if (c != std::string_view::npos) l = l.substr(0, c);
    }
    l = Trim(l);
    if (!l.empty()) {
      *line = l;
      return true;
    }
  }
  return false;
}

void TextFile::Fail(const std::string& problem) const { throw InputError(path_, line_, problem); }

int64_t TextFile::ParseInt(std::string_view tok, const char* what) const {
  int64_t v = 0;
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') ++b;
  const auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e || b == e)
    Fail(std::string("expected an integer for ") + what + ", found '" + std::string(tok) + "'");
  return v;
}

double TextFile::ParseDouble(std::string_view tok, const char* what) const {
  double v = 0;
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') ++b;
  const auto r = std::from_chars(b, e, v);
  if (r.ec == std::errc::result_out_of_range)
    Fail(std::string(what) + " '" + std::string(tok) + "' is out of the range of a double");
  if (r.ec != std::errc() || r.ptr != e || b == e)
    Fail(std::string("expected a number for ") + what + ", found '" + std::string(tok) + "'");
  if (!std::isfinite(v))
    Fail(std::string(what) + " is not a finite number: '" + std::string(tok) + "'");
  return v;
}

bool Tokens::Next(std::string_view* tok) {
  while (pos_ < s_.size() && IsBlank(s_[pos_])) ++pos_;
  if (pos_ >= s_.size()) return false;
  const size_t b = pos_;
  while (pos_ < s_.size() && !IsBlank(s_[pos_])) ++pos_;
  *tok = s_.substr(b, pos_ - b);
  return true;
}

int Tokens::Split(std::string_view* out, int n) {
  int count = 0;
  std::string_view t;
  while (Next(&t)) {
    if (count < n) out[count] = t;
    ++count;
  }
  return count;
}

}  // namespace meshreuse
