#!/usr/bin/env python3
"""Reads meshreuse's VTK XML output with meshio (Debian's python3-meshio: a reader nobody here
wrote) and compares it with a reference.

  check_vtu.py grid A B                     one grid in any two formats meshio reads (.vtu, .vtk,
                                            .msh): the same points and cells (exactly), and where
                                            both have them the same boundary flags and qualities
                                            (to Float32's precision: .vtu stores them so)
  check_vtu.py pieces SERIAL.vtu PAR.pvtu   a partitioned grid: every point owned by exactly one
                                            piece (vtkGhostType 0), at the serial coordinates;
                                            the owned cells, each once, are the serial cells; each
                                            piece's ghost cells are exactly the serial cells with
                                            a corner it owns that another piece owns; ghosts'
                                            coordinates, flags and qualities are their owners'
  check_vtu.py size A.vtu B.vtk MAX         A's size is at most MAX times B's

Exit 0 when all holds, 1 with the first differences otherwise, 2 on bad usage.
"""
import os
import sys
import xml.etree.ElementTree as ET

try:
    import meshio
    import numpy as np
except ImportError as e:  # a set-up problem, not a pass
    print(f"check_vtu: {e}: install python3-meshio (scripts/setup.sh --with-tests)", file=sys.stderr)
    sys.exit(1)

FLOAT32_TOL = 1e-6  # qualities are in [0, 1]; Float32 keeps 24 bits


def read(path):
    m = meshio.read(path)
    tri = [c.data for c in m.cells if c.type == "triangle"]
    if len(tri) != 1:
        fail(f"{path}: expected one block of triangles, found {[c.type for c in m.cells]}")
    pd = {k: np.asarray(v).ravel() for k, v in m.point_data.items()}
    cd = {k: np.asarray(v[0]).ravel() for k, v in m.cell_data.items()}
    return m.points, tri[0].astype(np.int64), pd, cd


def fail(msg):
    print("check_vtu: " + msg)
    sys.exit(1)


def grid(a, b):
    pa, ta, pda, cda = read(a)
    pb, tb, pdb, cdb = read(b)
    if pa.shape != pb.shape or not np.array_equal(pa, pb):
        fail(f"{a} and {b}: the points differ")
    if ta.shape != tb.shape or not np.array_equal(ta, tb):
        fail(f"{a} and {b}: the triangles differ")
    compared = []
    if "boundary" in pda and "boundary" in pdb:
        if not np.array_equal(pda["boundary"], pdb["boundary"]):
            fail(f"{a} and {b}: the boundary flags differ")
        compared.append("boundary")
    for name, x, y in (("vertex_quality", pda, pdb), ("triangle_quality", cda, cdb)):
        if name not in x or name not in y:
            continue
        d = np.abs(x[name].astype(np.float64) - y[name].astype(np.float64)).max(initial=0)
        if d > FLOAT32_TOL:
            fail(f"{a} and {b}: {name} differs by {d}")
        compared.append(name)
    print(f"check_vtu: {a} == {b}: {len(pa)} points, {len(ta)} triangles"
          + (f", {', '.join(compared)}" if compared else ""))


def pieces(serial, pvtu):
    ps, ts, pds, cds = read(serial)
    n = len(ps)
    root = ET.parse(pvtu).getroot()
    if root.get("type") != "PUnstructuredGrid":
        fail(f"{pvtu}: not a PUnstructuredGrid")
    grid_el = root.find("PUnstructuredGrid")
    if grid_el.get("GhostLevel") != "1":
        fail(f"{pvtu}: GhostLevel {grid_el.get('GhostLevel')}, expected 1")
    srcs = [p.get("Source") for p in grid_el.findall("Piece")]
    folder = os.path.dirname(pvtu)
    owner = np.full(n, -1, dtype=np.int64)
    serial_cells = {tuple(t): k for k, t in enumerate(ts.tolist())}
    owned_cells = np.zeros(len(ts), dtype=np.int64)
    cell_owner = np.full(len(ts), -1, dtype=np.int64)
    ghost_sets = []
    for r, src in enumerate(srcs):
        p, t, pd, cd = read(os.path.join(folder, src))
        gid = pd["GlobalNodeIds"].astype(np.int64)
        ghost = pd["vtkGhostType"]
        if gid.min(initial=0) < 0 or gid.max(initial=0) >= n:
            fail(f"{src}: a global id outside [0, {n})")
        if not np.array_equal(p, ps[gid]):
            fail(f"{src}: points differ from the serial grid's at their global ids")
        if not np.array_equal(pd["boundary"], pds["boundary"][gid]):
            fail(f"{src}: boundary flags differ from the serial grid's")
        d = np.abs(pd["vertex_quality"].astype(np.float64) - pds["vertex_quality"][gid]).max(initial=0)
        if d > FLOAT32_TOL:
            fail(f"{src}: vertex_quality differs from the serial grid's by {d}")
        mine = gid[ghost == 0]
        if (owner[mine] >= 0).any():
            fail(f"{src}: a point owned by two pieces")
        owner[mine] = r
        g = gid[t]
        cghost = cd["vtkGhostType"]
        ranks = cd["rank"]
        ghosts = set()
        for k, tri in enumerate(map(tuple, g.tolist())):
            s = serial_cells.get(tri)
            if s is None:
                fail(f"{src}: cell {tri} (global ids) is not a serial cell")
            d = abs(float(cd["triangle_quality"][k]) - float(cds["triangle_quality"][s]))
            if d > FLOAT32_TOL:
                fail(f"{src}: triangle_quality of {tri} differs by {d}")
            if cghost[k] == 0:
                owned_cells[s] += 1
                cell_owner[s] = r
                if ranks[k] != r:
                    fail(f"{src}: an owned cell marked rank {ranks[k]}")
            else:
                ghosts.add(s)
                if ranks[k] == r:
                    fail(f"{src}: a ghost cell marked as this piece's")
        ghost_sets.append(ghosts)
    if (owner < 0).any():
        fail(f"{pvtu}: {(owner < 0).sum()} points owned by no piece")
    if (owned_cells != 1).any():
        fail(f"{pvtu}: {(owned_cells == 0).sum()} serial cells in no piece, "
             f"{(owned_cells > 1).sum()} in several")
    # The ghost layer: the serial cells with a corner piece r owns that r does not own itself.
    for r, ghosts in enumerate(ghost_sets):
        touches = (owner[ts] == r).any(axis=1)
        expected = set(np.nonzero(touches)[0].tolist())
        expected -= {s for s in expected if cell_owner[s] == r}
        if expected != ghosts:
            fail(f"{srcs[r]}: {len(expected - ghosts)} ghost cells missing, "
                 f"{len(ghosts - expected)} extra")
    print(f"check_vtu: {pvtu} ({len(srcs)} pieces) == {serial}: {n} points, {len(ts)} triangles, "
          f"{sum(len(g) for g in ghost_sets)} ghost cells")


def size(a, b, most):
    sa, sb = os.path.getsize(a), os.path.getsize(b)
    if sa > float(most) * sb:
        fail(f"{a} is {sa} bytes, {sa / sb:.3f} of {b}'s {sb}, above {most}")
    print(f"check_vtu: {a} is {sa} bytes, {sa / sb:.3f} of {b}'s {sb}")


def main(argv):
    if len(argv) == 3 and argv[0] == "grid":
        grid(argv[1], argv[2])
    elif len(argv) == 3 and argv[0] == "pieces":
        pieces(argv[1], argv[2])
    elif len(argv) == 4 and argv[0] == "size":
        size(argv[1], argv[2], argv[3])
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main(sys.argv[1:])
