// ReadExternalTrace (template, used with a lambda per value); see trace_analysis.h.
#pragma once

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"

namespace meshreuse {

template <class F>
void ReadExternalTrace(const std::string& path, ExternalFormat fmt, F&& add) {
  const bool is_stdin = path == "-";
  std::FILE* f = is_stdin ? stdin : std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  struct Closer {
    std::FILE* f;
    bool own;
    ~Closer() {
      if (own) std::fclose(f);
    }
  } closer{f, !is_stdin};
  std::vector<char> buf(1 << 20);
  if (fmt != ExternalFormat::kText) {
    const size_t w = fmt == ExternalFormat::kU32 ? 4 : 8;
    uint64_t offset = 0;
    size_t carry = 0;
    while (true) {
      const size_t n = std::fread(buf.data() + carry, 1, buf.size() - carry, f) + carry;
      if (n == 0) break;
      const size_t whole = n / w * w;
      for (size_t i = 0; i < whole; i += w) {
        uint64_t v = 0;
        std::memcpy(&v, buf.data() + i, w);
        add(v);
      }
      offset += whole;
      carry = n - whole;
      if (carry && std::feof(f))
        throw InputError(path, 0,
                         "truncated: " + std::to_string(carry) + " stray bytes after " +
                             std::to_string(offset / w) + " values of " + std::to_string(w) +
                             " bytes");
      std::memmove(buf.data(), buf.data() + whole, carry);
      if (std::feof(f)) break;
    }
    return;
  }
  int64_t line = 0;
  std::string pending;
  auto parse = [&](const char* b, const char* e) {
    ++line;
    const char* hash = static_cast<const char*>(std::memchr(b, '#', e - b));
    if (hash) e = hash;
    while (b < e && (*b == ' ' || *b == '\t' || *b == '\r')) ++b;
    while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) --e;
    if (b == e) return;
    uint64_t v = 0;
    int base = 10;
    if (e - b > 2 && b[0] == '0' && (b[1] == 'x' || b[1] == 'X')) b += 2, base = 16;
    const auto r = std::from_chars(b, e, v, base);
    if (r.ec != std::errc() || r.ptr != e)
      throw InputError(path, line,
                       "expected a decimal or 0x-hex id, found '" + std::string(b, e) + "'");
    add(v);
  };
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) {
    const char* p = buf.data();
    const char* end = p + n;
    while (p < end) {
      const char* nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
      if (!nl) {
        pending.append(p, end);
        break;
      }
      if (!pending.empty()) {
        pending.append(p, nl);
        parse(pending.data(), pending.data() + pending.size());
        pending.clear();
      } else {
        parse(p, nl);
      }
      p = nl + 1;
    }
  }
  if (!pending.empty()) parse(pending.data(), pending.data() + pending.size());
}

}  // namespace meshreuse
