#!/usr/bin/env python3
"""Writes the broken mesh files (core/mesh_file.h) of tests/data/broken from a good one:
    make_mesh_files.py GOOD.mrm OUTDIR
(GOOD.mrm: `meshreuse mesh convert tests/data/two_interior.node -o GOOD.mrm`). Those marked
"mended" get fresh block, page and header hashes, so the damage reaches the checks behind them."""
import os
import struct
import sys

M = (1 << 64) - 1
BLOCK, PAGE, HEADER = 4096, 512, 128


# SplitMix64's finaliser (core/mix.h), shared with the summaries' fixtures.
sys.dont_write_bytecode = True  # no __pycache__ beside the fixtures
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_summaries import mix as mix64  # noqa: E402


def block_hash(b):
    h = mix64(0x6D72626C6F636B ^ len(b))
    n = len(b) // 8 * 8
    for i in range(0, n, 8):
        h = mix64(h ^ struct.unpack_from("<Q", b, i)[0])
    if n < len(b):
        h = mix64(h ^ int.from_bytes(b[n:], "little") ^ 0x8000000000000000)
    return h


def pad8(n):
    return (n + 7) // 8 * 8


def data_end(v, t):
    return HEADER + 16 * v + pad8(v) + 8 * (v + 1) + 2 * pad8(12 * t)


def mend(b):
    b = bytearray(b)
    v, t = struct.unpack_from("<qq", b, 16)
    end = data_end(v, t)
    table = [block_hash(bytes(b[a:min(end, a + BLOCK)])) for a in range(HEADER, end, BLOCK)]
    raw = b"".join(struct.pack("<Q", x) for x in table)
    pages = [block_hash(raw[8 * a:8 * min(len(table), a + PAGE)]) for a in range(0, len(table), PAGE)]
    del b[end:]
    b += raw + b"".join(struct.pack("<Q", x) for x in pages)
    h = mix64((v * 0x9E3779B97F4A7C15 & M) ^ t)
    for p in pages:
        h = (mix64(h ^ p) + 0x632BE59BD9B4E019) & M
    struct.pack_into("<Q", b, 32, h)
    struct.pack_into("<Q", b, 120, block_hash(bytes(b[:120])))
    return bytes(b)


def main():
    good, out = sys.argv[1], sys.argv[2]
    g = open(good, "rb").read()
    v, t = struct.unpack_from("<qq", g, 16)
    flags = HEADER + 16 * v
    tris = flags + pad8(v) + 8 * (v + 1) + pad8(12 * t)
    files = {}
    files["mrm_truncated.mrm"] = g[:-5]
    files["mrm_bad_magic.mrm"] = b"MRMESH2\n" + g[8:]
    b = bytearray(g)
    b[16] ^= 1  # the vertex count, header hash left stale
    files["mrm_header.mrm"] = bytes(b)
    b = bytearray(g)
    b[tris + 5] ^= 0x10  # a triangle's corner, its block's hash left stale
    files["mrm_damaged.mrm"] = bytes(b)
    # A header announcing 2e9 vertices, its hash fresh: refused from the size, nothing allocated.
    b = bytearray(g)
    struct.pack_into("<q", b, 16, 2000000000)
    struct.pack_into("<Q", b, 120, block_hash(bytes(b[:120])))
    files["mrm_huge_count.mrm"] = bytes(b)
    # A triangle count whose 3 T overflows 64 bits (found by fuzz_mesh_file), its hash fresh.
    b = bytearray(g)
    struct.pack_into("<q", b, 24, 7598809990106710024)
    struct.pack_into("<Q", b, 120, block_hash(bytes(b[:120])))
    files["mrm_overflow_count.mrm"] = bytes(b)
    # Mended: a boundary vertex flagged interior, a corner out of range.
    b = bytearray(g)
    b[flags + 0] = 0  # vertex 0 lies on the boundary
    files["mrm_boundary_flag.mrm"] = mend(bytes(b))
    b = bytearray(g)
    struct.pack_into("<i", b, tris + 4, 99)
    files["mrm_corner.mrm"] = mend(bytes(b))
    # Mended: triangle 0's second corner made its first (a repeated corner, which once let a
    # rank's graph rows overrun a row: found by fuzz_mesh_file).
    b = bytearray(g)
    b[tris + 4 : tris + 8] = b[tris : tris + 4]
    files["mrm_repeated_corner.mrm"] = mend(bytes(b))
    for name, data in files.items():
        with open(f"{out}/{name}", "wb") as f:
            f.write(data)


main()
