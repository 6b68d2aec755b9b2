#!/usr/bin/env python3
"""Writes the hostile binary traces of tests/data/broken (meshreuse trace format, version 2;
layout in tracer/trace_format.h). Usage: make_traces.py [OUTDIR]  (default: this folder)
  vertices_ffffffff.trace  a vertex count of 0xFFFFFFFF in an 80-byte file
  records_2p60.trace       a record count of 2^60 (records * 16 wraps to 0 in 64 bits)
  last_byte.trace          a record at address 2^64-1: the analyzer reserves the last byte
  bad_kind.trace           a record of kind 9 (kinds are 0-3)
  below_base.trace         a record below the canonical arrays' base (valid: its line id must not
                           wrap to the reserved value; written with --sparse, read with exit 0)
  sweeps_50000.trace       50,000 sweeps announced, 65,536 zero records (a hole on disk) in the
                           first; written only with --sparse (the CLI tests make it in a temp
                           folder)
  announce_16352x256.trace 16,352 empty sweeps x 256 streams announced (a 67 MB header of zeros,
                           a hole on disk; 2.9 KB compressed): refused from the fixed header
  streams_256.trace        256 sweeps x 256 streams, one record per stream in the first sweep
                           only: state and rows must follow the 256 records
  (both with --sparse)
"""
import os
import struct
import sys


def header(version=2, threads=1, iterations=0, slots=0, vertices=8, records=0, starts=(),
           per_sweep=(), elements=(), mesh=b"m", ordering=b"ori"):
    body = struct.pack("<8sIIIIIIIIQ", b"MRTRACE\0", version, 0, 3, 66, threads, iterations,
                       slots, vertices, records)
    body += b"".join(struct.pack("<Q", s) for s in starts)
    body += b"".join(struct.pack("<Q", s) for s in per_sweep)
    if version >= 2:
        body += b"".join(struct.pack("<Q", s) for s in elements)
    body += struct.pack("<H", len(mesh)) + mesh + struct.pack("<H", len(ordering)) + ordering
    body += b"\0" * (-len(body) % 16)
    return body[:12] + struct.pack("<I", len(body)) + body[16:]


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    out = args[0] if args else os.path.dirname(os.path.abspath(__file__))
    h = header(iterations=1, slots=1, vertices=0xFFFFFFFF, records=0, starts=[0], per_sweep=[0],
               elements=[0])
    open(os.path.join(out, "vertices_ffffffff.trace"), "wb").write(h)
    rec = struct.pack("<QIBBBB", 64, 1, 0, 0, 8, 8)
    h = header(iterations=1, slots=1, records=2**60, starts=[0], per_sweep=[2**60],
               elements=[2**60])
    open(os.path.join(out, "records_2p60.trace"), "wb").write(h + rec)
    one = header(iterations=1, slots=1, records=1, starts=[0], per_sweep=[1], elements=[0])
    open(os.path.join(out, "last_byte.trace"), "wb").write(
        one + struct.pack("<QIBBBB", 2**64 - 1, 0, 3, 0, 1, 8))
    open(os.path.join(out, "bad_kind.trace"), "wb").write(
        one + struct.pack("<QIBBBB", 64, 0, 9, 0, 8, 8))
    if "--sparse" in sys.argv:
        open(os.path.join(out, "below_base.trace"), "wb").write(
            one + struct.pack("<QIBBBB", (1 << 32) - 64, 0, 3, 0, 8, 8))
        n = 50000
        records = 1 << 16  # 1 MiB of records, a hole on disk
        starts = [0] + [records] * (n - 1)
        h = header(iterations=n, slots=n, records=records, starts=starts,
                   per_sweep=[records] + [0] * (n - 1), elements=[records] + [0] * (n - 1))
        path = os.path.join(out, "sweeps_50000.trace")
        with open(path, "wb") as f:
            f.write(h)
            f.truncate(len(h) + 16 * records)
        # The fixed 48 bytes and the names; the tables between them zeros (sweeps all empty).
        n, t = 16352, 256
        size = 48 + 8 * n * (1 + 2 * t)
        names = struct.pack("<H", 1) + b"m" + struct.pack("<H", 3) + b"ori"
        size += len(names)
        size += -size % 16
        fixed = struct.pack("<8sIIIIIIIIQ", b"MRTRACE\0", 2, size, 3, 66, t, n, n, 8, 0)
        with open(os.path.join(out, "announce_16352x256.trace"), "wb") as f:
            f.write(fixed)
            f.seek(48 + 8 * n * (1 + 2 * t))
            f.write(names)
            f.truncate(size)
        n = 256
        per_sweep = [1] * t + [0] * (t * (n - 1))
        h = header(threads=t, iterations=n, slots=n, records=t, starts=[0] + [t] * (n - 1),
                   per_sweep=per_sweep, elements=[0] * (t * n))
        recs = b"".join(struct.pack("<QIBBBB", (i << 20) + 64 * i, 0, 3, i, 8, 8)
                        for i in range(t))
        open(os.path.join(out, "streams_256.trace"), "wb").write(h + recs)


if __name__ == "__main__":
    main()
