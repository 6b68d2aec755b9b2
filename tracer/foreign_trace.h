// Reading other tools' traces (the formats of trace_formats.h): a template over the callback,
// called add(value, size in bytes, is_store, is_fetch) once per access, so the per-access work is
// inlined into whoever consumes it. Reads through InputStream (plain or zstd; directories and
// devices refused, read errors reported), streams in 1 MiB blocks (a text line may be at most 4096
// bytes, so an endless line fails instead of growing), skips a UTF-8 byte-order mark, refuses NUL
// bytes in text, and refuses the value 2^64-1, which the analyzer reserves, naming the line or
// record and byte offset. Lackey: a modify is a load then a store; a file with no data records
// (lackey run without --trace-mem=yes) is refused, naming the cause.
#pragma once

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "tracer/input_stream.h"
#include "tracer/trace_formats.h"

namespace meshreuse {

struct ForeignTraceCounts {
  uint64_t data = 0, instructions = 0;  // records read (lackey: L/S/M lines and I lines)
};

namespace foreign_detail {

constexpr uint64_t kReserved = ~uint64_t{0};

// One lackey line: "I  0023C790,2", " L BE80199C,4", " S ...", " M ..." (hex address without 0x,
// decimal size). valgrind's own messages ("==PID== ...", "--PID-- ...") and blank lines are
// skipped.
template <class F>
void LackeyLine(const std::string& path, int64_t line, const char* b, const char* e,
                bool instructions, F& add, ForeignTraceCounts& n) {
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
  if (op == 'I') {
    ++n.instructions;
    if (!instructions) return;
  } else {
    ++n.data;
  }
  add(addr, size, op == 'S', op == 'I');
  if (op == 'M') add(addr, size, true, false);  // a modify: the load, then the store
}

// A fixed-record file of `size` bytes that ends in part of a record (one message, whether the
// whole file is read or a chunk of it).
inline InputError StrayBytes(const std::string& path, uint64_t size, size_t w) {
  const uint64_t whole = size / w * w;
  return InputError(path, 0,
                    "truncated: " + std::to_string(size - whole) + " stray bytes at byte offset " +
                        std::to_string(whole) + ", after " + std::to_string(whole / w) +
                        " records of " + std::to_string(w) + " bytes");
}

// Fixed-size little-endian records of `w` bytes, the value (VW bytes, a constant so the copy is
// inlined) at offset `at`.
template <size_t VW, class F>
void Fixed(const std::string& path, InputStream& in, std::vector<char>& buf, size_t w, size_t at,
           F& add, ForeignTraceCounts& count, uint64_t offset) {
  const size_t block = buf.size() / w * w;
  size_t carry = 0;
  while (true) {
    const size_t got = in.Read(buf.data() + carry, block - carry);
    const size_t n = got + carry;
    if (n == 0) break;
    const size_t whole = n / w * w;
    for (size_t i = 0; i < whole; i += w) {
      uint64_t v = 0;
      std::memcpy(&v, buf.data() + i + at, VW);  // little-endian hosts (x86-64, arm64)
      if (v == kReserved)
        throw InputError(path, 0,
                         "record " + std::to_string((offset + i) / w) + " (byte offset " +
                             std::to_string(offset + i) +
                             "): the value 2^64-1 is reserved: ids and addresses must be below it");
      add(v, uint32_t{1}, false, false);
    }
    count.data += whole / w;
    offset += whole;
    carry = n - whole;
    if (got == 0) {
      if (carry) throw StrayBytes(path, offset + carry, w);
      break;
    }
    std::memmove(buf.data(), buf.data() + whole, carry);
  }
}

}  // namespace foreign_detail

namespace foreign_detail {

// Text and lackey lines, parsed one by one (called by ReadForeignTrace).
template <class F>
void ReadTextLines(const std::string& path, const TraceFormat& fmt, InputStream& in,
                   std::vector<char>& buf, bool instructions, F& add, ForeignTraceCounts& count,
                   bool at_start, bool whole_file) {
  const bool lackey = fmt.syntax == TraceSyntax::kLackey;
  constexpr size_t kMaxLine = 4096;
  int64_t line = 0;
  std::string pending;
  auto parse = [&](const char* b, const char* e) {
    ++line;
    if (static_cast<size_t>(e - b) > kMaxLine)
      throw InputError(path, line, "line longer than 4096 bytes: not a text trace");
    if (at_start && line == 1 && e - b >= 3 && std::memcmp(b, "\xEF\xBB\xBF", 3) == 0)
      b += 3;  // a byte-order mark
    if (std::memchr(b, '\0', e - b))
      throw InputError(path, line, "binary data (a NUL byte): not a text trace");
    if (lackey) return foreign_detail::LackeyLine(path, line, b, e, instructions, add, count);
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
    ++count.data;
    add(v, uint32_t{1}, false, false);
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
  if (whole_file && lackey && count.data == 0 && !(instructions && count.instructions > 0))
    throw InputError(path, 0,
                     count.instructions
                         ? "no load or store records (L, S, M lines), only instruction fetches: "
                           "was lackey run with --trace-mem=yes? (--instructions counts the I "
                           "lines)"
                         : "no lackey records (L, S, M or I lines): run valgrind --tool=lackey "
                           "--trace-mem=yes --log-file=FILE PROGRAM and read FILE");
}

}  // namespace foreign_detail

// A range (a chunk; a plain regular file, InputStream::SeekTo): records [first, end) of a
// fixed-record format; bytes [first, end) of a text or lackey trace, as the whole lines that begin
// there.
template <class F>
ForeignTraceCounts ReadForeignTrace(const std::string& path, const TraceFormat& fmt, F&& add,
                                    bool instructions = false, uint64_t first = 0,
                                    uint64_t end = ~uint64_t{0}) {
  using foreign_detail::kReserved;
  ForeignTraceCounts count;
  InputStream in(path);
  std::vector<char> buf(1 << 20);
  const bool ranged = first != 0 || end != ~uint64_t{0};
  if (fmt.syntax == TraceSyntax::kFixedRecords) {
    const size_t w = fmt.record_bytes, at = fmt.value_offset;
    if (ranged) {
      // Every chunk refuses a file that ends in part of a record, as a reader from the start
      // does at its end (a chunk reads whole records only).
      const int64_t size = in.size();
      if (size >= 0 && static_cast<uint64_t>(size) % w != 0 && in.size_from_table())
        throw InputError(path, 0,
                         "the zstd seek table does not match the frames: its frames add up to " +
                             std::to_string(size) + " content bytes, not a whole number of " +
                             std::to_string(w) + "-byte records");
      if (size >= 0 && static_cast<uint64_t>(size) % w != 0)
        throw foreign_detail::StrayBytes(path, static_cast<uint64_t>(size), w);
      in.SeekTo(first * w);
      in.SetLimit((end - first) * w);
    }
    switch (fmt.value_bytes) {
      case 1:
        foreign_detail::Fixed<1>(path, in, buf, w, at, add, count, first * w);
        break;
      case 2:
        foreign_detail::Fixed<2>(path, in, buf, w, at, add, count, first * w);
        break;
      case 4:
        foreign_detail::Fixed<4>(path, in, buf, w, at, add, count, first * w);
        break;
      default:
        foreign_detail::Fixed<8>(path, in, buf, w, at, add, count, first * w);
    }
    return count;
  }
  // A chunk of a text trace: first and end are byte offsets; the chunk is the whole lines that
  // begin in [first, end), so consecutive chunks hold every line once.
  uint64_t chunk_start = 0;
  if (ranged) {
    const int64_t size = in.size();
    const uint64_t a = in.NextLineStart(first);
    const uint64_t b =
        size >= 0 && end >= static_cast<uint64_t>(size) ? size : in.NextLineStart(end);
    in.SeekTo(a);
    in.SetLimit(b > a ? b - a : 0);
    chunk_start = a;
  }
  try {
    foreign_detail::ReadTextLines(path, fmt, in, buf, instructions, add, count, chunk_start == 0,
                                  !ranged);
  } catch (const InputError& e) {
    if (!ranged) throw;
    if (e.line() > 0) {  // the line in the whole file, as a reader from the start says it
      InputStream prefix(path);
      prefix.SetLimit(chunk_start);
      int64_t lines = 0;
      for (size_t got; (got = prefix.Read(buf.data(), buf.size())) > 0;)
        lines += std::count(buf.data(), buf.data() + got, '\n');
      throw InputError(path, lines + e.line(), e.problem());
    }
    throw InputError(path, 0,
                     e.problem() + " (in the chunk that begins at byte offset " +
                         std::to_string(chunk_start) + ")");
  }
  return count;
}

}  // namespace meshreuse
