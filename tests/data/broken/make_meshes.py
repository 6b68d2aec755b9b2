#!/usr/bin/env python3
"""Writes the large hostile meshes of issue 20 (valid meshes that used to take quadratic time),
for the CLI tests and for timing them against an ordinary mesh of the same size.
Usage: make_meshes.py OUTDIR [N]   (N triangles each, default 100000)
  fan_N.node/.ele    one vertex at the centre of N triangles (its degree is N)
  grid_N.node/.ele   a grid of about N triangles (degree 6): the same size, the ordinary case
  blocks_N.msh       Gmsh 4.1 binary, the grid's triangles in one element block each
  blocks1_N.msh      the same mesh in one block
  blocks_ascii_N.msh Gmsh 4.1 ASCII, one block per triangle
"""
import math
import os
import struct
import sys


def write_triangle(prefix, xy, tri):
    with open(prefix + ".node", "w") as f:
        f.write(f"{len(xy)} 2 0 0\n")
        f.writelines(f"{i} {x:.17g} {y:.17g}\n" for i, (x, y) in enumerate(xy))
    with open(prefix + ".ele", "w") as f:
        f.write(f"{len(tri)} 3 0\n")
        f.writelines(f"{i} {a} {b} {c}\n" for i, (a, b, c) in enumerate(tri))


def fan(n):
    xy = [(0.0, 0.0)] + [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n))
                         for i in range(n)]
    return xy, [(0, i + 1, (i + 1) % n + 1) for i in range(n)]


def grid(n):
    k = int(math.sqrt(n / 2)) + 1
    xy = [(x + 0.1 * math.sin(y), y + 0.1 * math.cos(x)) for y in range(k + 1) for x in range(k + 1)]
    tri = []
    for y in range(k):
        for x in range(k):
            a = y * (k + 1) + x
            tri += [(a, a + 1, a + k + 2), (a, a + k + 2, a + k + 1)]
    return xy, tri


def write_gmsh_binary(path, xy, tri, one_block):
    out = [b"$MeshFormat\n4.1 1 8\n", struct.pack("<i", 1), b"\n$EndMeshFormat\n$Nodes\n"]
    n = len(xy)
    out.append(struct.pack("<QQQQ", 1, n, 1, n))
    out.append(struct.pack("<iiiQ", 2, 1, 0, n))
    out.append(struct.pack(f"<{n}Q", *range(1, n + 1)))
    out.append(b"".join(struct.pack("<ddd", x, y, 0.0) for x, y in xy))
    out.append(b"\n$EndNodes\n$Elements\n")
    m = len(tri)
    blocks = 1 if one_block else m
    out.append(struct.pack("<QQQQ", blocks, m, 1, m))
    if one_block:
        out.append(struct.pack("<iiiQ", 2, 1, 2, m))
        out.append(b"".join(struct.pack("<QQQQ", i + 1, a + 1, b + 1, c + 1)
                            for i, (a, b, c) in enumerate(tri)))
    else:
        out.append(b"".join(struct.pack("<iiiQQQQQ", 2, 1, 2, 1, i + 1, a + 1, b + 1, c + 1)
                            for i, (a, b, c) in enumerate(tri)))
    out.append(b"\n$EndElements\n")
    with open(path, "wb") as f:
        f.write(b"".join(out))


def write_gmsh_ascii(path, xy, tri):
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n")
        n = len(xy)
        f.write(f"1 {n} 1 {n}\n2 1 0 {n}\n")
        f.writelines(f"{i + 1}\n" for i in range(n))
        f.writelines(f"{x:.17g} {y:.17g} 0\n" for x, y in xy)
        f.write("$EndNodes\n$Elements\n")
        m = len(tri)
        f.write(f"{m} {m} 1 {m}\n")
        f.writelines(f"2 1 2 1\n{i + 1} {a + 1} {b + 1} {c + 1}\n" for i, (a, b, c) in enumerate(tri))
        f.write("$EndElements\n")


def main():
    out = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 100000
    write_triangle(os.path.join(out, f"fan_{n}"), *fan(n))
    xy, tri = grid(n)
    write_triangle(os.path.join(out, f"grid_{n}"), xy, tri)
    write_gmsh_binary(os.path.join(out, f"blocks_{n}.msh"), xy, tri, False)
    write_gmsh_binary(os.path.join(out, f"blocks1_{n}.msh"), xy, tri, True)
    write_gmsh_ascii(os.path.join(out, f"blocks_ascii_{n}.msh"), xy, tri)


if __name__ == "__main__":
    main()
