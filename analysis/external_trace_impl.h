// ReadExternalTrace (template, used with a lambda per value); see trace_analysis.h.
#pragma once

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"

namespace meshreuse {

// Reads through InputFile (directories and devices refused, read errors reported), streams in
// 1 MiB blocks (a text line may be at most 4096 bytes, so an endless line fails instead of
// growing), skips a UTF-8 byte-order mark, refuses NUL bytes in text, and refuses the value
// 2^64-1, which the analyzer reserves, with the line or byte offset where it stands.
template <class F>
void ReadExternalTrace(const std::string& path, ExternalFormat fmt, F&& add) {
  InputFile in(path);
  constexpr uint64_t kReserved = ~uint64_t{0};
  std::vector<char> buf(1 << 20);
  if (fmt != ExternalFormat::kText) {
    const size_t w = fmt == ExternalFormat::kU32 ? 4 : 8;
    uint64_t offset = 0;
    size_t carry = 0;
    while (true) {
      const size_t got = in.Read(buf.data() + carry, buf.size() - carry);
      const size_t n = got + carry;
      if (n == 0) break;
      const size_t whole = n / w * w;
      for (size_t i = 0; i < whole; i += w) {
        uint64_t v = 0;
        std::memcpy(&v, buf.data() + i, w);
        if (v == kReserved)
          throw InputError(path, 0,
                           "value 2^64-1 at byte offset " + std::to_string(offset + i) +
                               " (value " + std::to_string((offset + i) / w) +
                               ") is reserved: ids and addresses must be below it");
        add(v);
      }
      offset += whole;
      carry = n - whole;
      if (got == 0) {
        if (carry)
          throw InputError(path, 0,
                           "truncated: " + std::to_string(carry) + " stray bytes at byte offset " +
                               std::to_string(offset) + ", after " + std::to_string(offset / w) +
                               " values of " + std::to_string(w) + " bytes");
        break;
      }
      std::memmove(buf.data(), buf.data() + whole, carry);
    }
    return;
  }
  constexpr size_t kMaxLine = 4096;
  int64_t line = 0;
  std::string pending;
  auto parse = [&](const char* b, const char* e) {
    ++line;
    if (static_cast<size_t>(e - b) > kMaxLine)
      throw InputError(path, line, "line longer than 4096 bytes: not a text trace");
    if (line == 1 && e - b >= 3 && std::memcmp(b, "\xEF\xBB\xBF", 3) == 0) b += 3;  // BOM
    if (std::memchr(b, '\0', e - b))
      throw InputError(path, line, "binary data (a NUL byte): not a text trace");
    const char* hash = static_cast<const char*>(std::memchr(b, '#', e - b));
    if (hash) e = hash;
    while (b < e && (*b == ' ' || *b == '\t' || *b == '\r')) ++b;
    while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) --e;
    if (b == e) return;
    uint64_t v = 0;
    int base = 10;
    if (e - b > 2 && b[0] == '0' && (b[1] == 'x' || b[1] == 'X')) b += 2, base = 16;
    const auto r = std::from_chars(b, e, v, base);
    if (r.ec == std::errc::result_out_of_range)
      throw InputError(path, line, "'" + std::string(b, e) + "' does not fit in 64 bits");
    if (r.ec != std::errc() || r.ptr != e)
      throw InputError(path, line,
                       "expected a decimal or 0x-hex id, found '" + std::string(b, e) + "'");
    if (v == kReserved)
      throw InputError(path, line,
                       "the value 2^64-1 is reserved: ids and addresses must be below it");
    add(v);
  };
  size_t n;
  while ((n = in.Read(buf.data(), buf.size())) > 0) {
    const char* p = buf.data();
    const char* end = p + n;
    while (p < end) {
      const char* nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
      if (!nl) {
        pending.append(p, end);
        if (pending.size() > kMaxLine)
          throw InputError(path, line + 1, "line longer than 4096 bytes: not a text trace");
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
