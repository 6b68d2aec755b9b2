// ReadExternalTrace (template, used with a lambda per access); see trace_analysis.h.
#pragma once

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "tracer/input_stream.h"

namespace meshreuse {

namespace external_detail {

constexpr uint64_t kReserved = ~uint64_t{0};

// One lackey line: "I  0023C790,2", " L BE80199C,4", " S ...", " M ..." (hex address without 0x,
// decimal size). valgrind's own messages ("==PID== ...", "--PID-- ...") and blank lines are
// skipped.
template <class F>
void LackeyLine(const std::string& path, int64_t line, const char* b, const char* e,
                bool instructions, F& add) {
  if (e - b >= 2 && ((b[0] == '=' && b[1] == '=') || (b[0] == '-' && b[1] == '-'))) return;
  while (b < e && (*b == ' ' || *b == '\t')) ++b;
  while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) --e;
  if (b == e) return;
  const char op = *b++;
  if (op != 'I' && op != 'L' && op != 'S' && op != 'M')
    throw InputError(path, line,
                     std::string("expected a lackey record (I, L, S or M), found '") +
                         std::string(b - 1, e) + "'");
  while (b < e && (*b == ' ' || *b == '\t')) ++b;
  const char* comma = static_cast<const char*>(std::memchr(b, ',', e - b));
  if (!comma)
    throw InputError(path, line, "expected ADDRESS,SIZE after '" + std::string(1, op) + "'");
  uint64_t addr = 0;
  uint32_t size = 0;
  auto r = std::from_chars(b, comma, addr, 16);
  if (r.ec != std::errc() || r.ptr != comma || b == comma)
    throw InputError(path, line, "bad hex address '" + std::string(b, comma) + "'");
  r = std::from_chars(comma + 1, e, size, 10);
  if (r.ec != std::errc() || r.ptr != e || comma + 1 == e || size == 0 || size > 4096)
    throw InputError(path, line,
                     "bad access size '" + std::string(comma + 1, e) + "' (1..4096 bytes)");
  if (addr == kReserved || addr > kReserved - size)
    throw InputError(path, line, "the access runs past the end of the 64-bit address space");
  if (op == 'I' && !instructions) return;
  add(addr, size);
  if (op == 'M') add(addr, size);  // a modify: the load, then the store
}

// Fixed-size little-endian records of W bytes, the value (VW bytes) at offset AT.
template <size_t W, size_t AT, size_t VW, class F>
void Binary(const std::string& path, InputStream& in, std::vector<char>& buf, F& add) {
  const size_t block = buf.size() / W * W;
  uint64_t offset = 0;
  size_t carry = 0;
  while (true) {
    const size_t got = in.Read(buf.data() + carry, block - carry);
    const size_t n = got + carry;
    if (n == 0) break;
    const size_t whole = n / W * W;
    for (size_t i = 0; i < whole; i += W) {
      uint64_t v = 0;
      std::memcpy(&v, buf.data() + i + AT, VW);  // little-endian hosts (x86-64, arm64)
      if (v == kReserved)
        throw InputError(path, 0,
                         "record " + std::to_string((offset + i) / W) + " (byte offset " +
                             std::to_string(offset + i) +
                             "): the value 2^64-1 is reserved: ids and addresses must be below it");
      add(v, 1u);
    }
    offset += whole;
    carry = n - whole;
    if (got == 0) {
      if (carry)
        throw InputError(path, 0,
                         "truncated: " + std::to_string(carry) + " stray bytes at byte offset " +
                             std::to_string(offset) + ", after " + std::to_string(offset / W) +
                             " records of " + std::to_string(W) + " bytes");
      break;
    }
    std::memmove(buf.data(), buf.data() + whole, carry);
  }
}

}  // namespace external_detail

// Reads through InputStream (plain or zstd; directories and devices refused, read errors
// reported), streams in 1 MiB blocks (a text line may be at most 4096 bytes, so an endless line
// fails instead of growing), skips a UTF-8 byte-order mark, refuses NUL bytes in text, and refuses
// the value 2^64-1, which the analyzer reserves, with the line or record number where it stands.
template <class F>
void ReadExternalTrace(const std::string& path, ExternalFormat fmt, F&& add, bool instructions) {
  using external_detail::kReserved;
  InputStream in(path);
  std::vector<char> buf(1 << 20);
  if (fmt != ExternalFormat::kText && fmt != ExternalFormat::kLackey) {
    // The record width, the value's offset and width are constants of each format's loop (a
    // memcpy of a variable width is a library call per record).
    switch (fmt) {
      case ExternalFormat::kU32:
        return external_detail::Binary<4, 0, 4>(path, in, buf, add);
      case ExternalFormat::kOracle:
        return external_detail::Binary<24, 4, 8>(path, in, buf, add);
      default:
        return external_detail::Binary<8, 0, 8>(path, in, buf, add);
    }
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
    if (fmt == ExternalFormat::kLackey)
      return external_detail::LackeyLine(path, line, b, e, instructions, add);
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
    add(v, 1u);
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
