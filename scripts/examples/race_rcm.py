#!/usr/bin/python3
"""A scipy ordering raced against BFS and grid-wave: reuse distances, simulated misses, time.

scipy's reverse Cuthill-McKee over the mesh's own neighbour rows (zero-copy CSR views) is saved
as a permutation file, so every meshreuse tool takes it by name beside the registered orderings.
Usage: PYTHONPATH=build/release/python scripts/examples/race_rcm.py MESH [--repeat 5]
       [--out DIR]
"""
import argparse
import csv
import os

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import reverse_cuthill_mckee

import meshreuse as mr

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("mesh")
ap.add_argument("--repeat", type=int, default=5, help="timed rounds per ordering (at least 3)")
ap.add_argument("--out", default="race")
a = ap.parse_args()
os.makedirs(a.out, exist_ok=True)

mesh = mr.Mesh.read(a.mesh)
off, nbr = mesh.neighbours
n = mesh.num_vertices
graph = csr_matrix((np.ones(len(nbr), dtype=np.int8), nbr, off), shape=(n, n))
perm = reverse_cuthill_mckee(graph, symmetric_mode=True)  # new position k holds old vertex perm[k]
path = os.path.join(a.out, "scipy_rcm.perm")
mr.save_permutation(mesh, perm, path, "scipy.sparse.csgraph.reverse_cuthill_mckee")

orderings = ["ori", "bfs", "grid-wave", f"scipy-rcm=file:{path}"]
reuse = mr.analyze(mesh, orderings=orderings, granularity="element")
sim = mr.simulate(mesh, orderings=orderings)
timed = mr.compare(mesh, orderings=orderings, repeat=a.repeat, max_iters=10)

rows = []
misses = sim.table
for s in reuse.streams:
    at = [i for i in range(misses.nrows)
          if misses["ordering"][i] == s.ordering and misses["level"][i] == "L1"]
    t = [i for i in range(timed.table.nrows) if timed.table["ordering"][i] == s.ordering][0]
    rows.append({"ordering": s.ordering, "q50": s.q50, "q90": s.q90, "mean": round(s.mean, 1),
                 "L1_misses_simulated": int(misses["misses"][at[0]]),
                 "sweep_ms": round(float(timed.table["sweep_ms"][t]), 4),
                 "speedup_vs_ori1": round(float(timed.table["speedup_vs_ori1"][t]), 3)})
with open(os.path.join(a.out, "race.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
for r in rows:
    print("  ".join(f"{k}={v}" for k, v in r.items()))
print(f"wrote {os.path.join(a.out, 'race.csv')}")
