// TextFile and Tokens; see text_file.h.
#include "core/text_file.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.h"
#include "core/progress.h"

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

TextFile::TextFile(std::string path, char comment)
    : in_(std::make_unique<InputFile>(path)), comment_(comment) {}

bool TextFile::Fill() {
  if (eof_) return false;
  if (pos_ > 0) {  // keep the unfinished line, drop what was returned
    consumed_ += static_cast<int64_t>(pos_);
    buf_.erase(0, pos_);
    pos_ = 0;
  }
  const size_t old = buf_.size();
  constexpr size_t kBlock = size_t{1} << 20;
  buf_.resize(old + kBlock);
  const size_t got = in_->Read(buf_.data() + old, kBlock);
  buf_.resize(old + got);
  if (got == 0) eof_ = true;
  ReportProgress(static_cast<uint64_t>(consumed_) + old + got,
                 in_->size() > 0 ? static_cast<uint64_t>(in_->size()) : 0);  // a block read
  if (first_ && consumed_ == 0 && pos_ == 0 && (buf_.size() >= 3 || eof_)) {
    if (buf_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // a UTF-8 byte-order mark
    first_ = false;
  }
  return got > 0;
}

int64_t TextFile::BytesLeft() const {
  if (in_->size() < 0) return -1;
  return in_->size() - consumed_ - static_cast<int64_t>(pos_);
}

bool TextFile::NextLine(std::string_view* line) {
  size_t nl;
  while ((nl = buf_.find('\n', pos_)) == std::string::npos) {
    if (buf_.size() - pos_ > kMaxLine) {
      ++line_;
      Fail("line longer than 1 MiB: not a text mesh, permutation or trace file");
    }
    if (!Fill()) break;
  }
  if (pos_ >= buf_.size()) return false;
  const size_t end = nl == std::string::npos ? buf_.size() : nl;
  ++line_;
  if (end - pos_ > kMaxLine)
    Fail("line longer than 1 MiB: not a text mesh, permutation or trace file");
  *line = std::string_view(buf_).substr(pos_, end - pos_);
  if (line->find('\0') != std::string_view::npos) Fail("binary data (a NUL byte): not a text file");
  if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
  pos_ = nl == std::string::npos ? buf_.size() : nl + 1;
  return true;
}

int64_t TextFile::Reservable(int64_t count, int64_t min_bytes) const {
  const int64_t left = BytesLeft();
  const int64_t cap = left < 0 ? int64_t{1} << 16 : left / min_bytes;
  return count < 0 ? 0 : count < cap ? count : cap;
}

bool TextFile::NextDataLine(std::string_view* line) {
  std::string_view l;
  while (NextLine(&l)) {
    if (comment_ != '\0') {
      const size_t c = l.find(comment_);
      if (c != std::string_view::npos) {
        constexpr std::string_view kPair = "# meshreuse pair ";
        if (c == 0 && l.substr(0, kPair.size()) == kPair)
          pair_mark_ = std::string(Trim(l.substr(kPair.size()).substr(0, 200)));
        l = l.substr(0, c);
      }
    }
    l = Trim(l);
    if (!l.empty()) {
      *line = l;
      return true;
    }
  }
  return false;
}

void TextFile::Fail(const std::string& problem) const {
  throw InputError(in_->path(), line_, problem);
}

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
