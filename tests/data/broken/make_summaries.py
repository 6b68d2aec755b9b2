#!/usr/bin/env python3
"""Writes the broken chunk summaries of tests/data/broken (reports/chunk_summary.h: magic
"MRSUMRY\\0", u32 version, u32 0, u64 payload bytes, u64 checksum, payload) from one valid summary,
which `meshreuse analyze ids.u64 --format u64 --granularity element --chunk 0/1 --summary-out
valid.sum` writes (the caller passes it). Usage: make_summaries.py VALID.sum [OUTDIR]
  summary_magic.sum      no MRSUMRY magic (a text file)
  summary_version.sum    version 9
  summary_truncated.sum  the payload cut short of its announced length
  summary_checksum.sum   one payload byte changed, the checksum not
  summary_huge_count.sum the first string's length 2^60, the checksum made to match: refused
                         before anything is allocated
"""
import os
import struct
import sys

M = (1 << 64) - 1


def mix(x):
    x ^= x >> 30
    x = (x * 0xBF58476D1CE4E5B9) & M
    x ^= x >> 27
    x = (x * 0x94D049BB133111EB) & M
    return x ^ (x >> 31)


def checksum(b):  # reports/chunk_summary.cc: Checksum
    n = len(b)
    h = 0x9E3779B97F4A7C15 ^ n
    i = 0
    while i + 8 <= n:
        w = int.from_bytes(b[i:i + 8], "little")
        h = (mix(h ^ w) + i) & M
        i += 8
    w = int.from_bytes(b[i:] + bytes(8 - (n - i)), "little")
    return mix(h ^ w ^ (n - i))


def main():
    valid = open(sys.argv[1], "rb").read()
    out = sys.argv[2] if len(sys.argv) > 2 else os.path.dirname(os.path.abspath(__file__))
    head, payload = valid[:32], valid[32:]
    assert head[:8] == b"MRSUMRY\0" and checksum(payload) == struct.unpack_from("<Q", head, 24)[0]

    def write(name, data):
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)

    write("summary_magic.sum", b"input,ordering\nids.u64,\n")
    write("summary_version.sum", head[:8] + struct.pack("<I", 9) + head[12:] + payload)
    write("summary_truncated.sum", valid[:-5])
    bad = bytearray(payload)
    bad[3] ^= 1
    write("summary_checksum.sum", head + bytes(bad))
    huge = bytearray(payload)
    struct.pack_into("<Q", huge, 0, 1 << 60)
    write("summary_huge_count.sum", head[:24] + struct.pack("<Q", checksum(bytes(huge))) + bytes(huge))


if __name__ == "__main__":
    main()
