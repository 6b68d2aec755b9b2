#!/usr/bin/env python3
"""Writes the broken binary .msh files (issue 12) from tests/data/two_interior41_bin.msh, which
`gmsh two_interior41.msh -save -bin -format msh41` wrote. Run from this folder; the files are
committed, so the tests do not need gmsh."""
import struct

src = open("../two_interior41_bin.msh", "rb").read()
nodes = src.index(b"$Nodes\n") + len(b"$Nodes\n")
elements = src.index(b"$Elements\n") + len(b"$Elements\n")


def put(name, data):
    open(name, "wb").write(data)


# Cut inside the last element block.
put("bin_truncated.msh", src[: len(src) - 40])
# numNodes (the second size_t of $Nodes) far beyond what the file holds.
put("bin_huge_count.msh", src[:nodes + 8] + struct.pack("<Q", 10**12) + src[nodes + 16:])
# The byte-order mark of a big-endian writer.
fmt = src.index(b"4.1 1 8\n") + len(b"4.1 1 8\n")
put("bin_big_endian.msh", src[:fmt] + struct.pack(">i", 1) + src[fmt + 4:])
# The first triangle's first node tag replaced by 55. The first element block holds lines
# (type 1) here, so find the first block of type 2 and patch its first element's first node.
p = elements + 32  # after numEntityBlocks numElements minTag maxTag
while True:
    dim, tag, etype = struct.unpack_from("<iii", src, p)
    n = struct.unpack_from("<Q", src, p + 12)[0]
    per = {1: 2, 2: 3, 15: 1}[etype]
    if etype == 2:
        first_node = p + 20 + 8
        put("bin_unknown_node.msh",
            src[:first_node] + struct.pack("<Q", 55) + src[first_node + 8:])
        break
    p += 20 + n * 8 * (1 + per)
# An element type Gmsh does not have (its size could not be stepped over).
first_type = elements + 32 + 8
put("bin_bad_type.msh", src[:first_type] + struct.pack("<i", 999) + src[first_type + 4:])
