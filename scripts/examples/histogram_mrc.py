#!/usr/bin/python3
"""The reuse-distance histogram and miss-ratio curve of a numpy trace, plotted with matplotlib.

A trace held as a numpy array is analysed where it lies (no file, no copy): exact LRU stack
distances, the histogram as (distances, counts) arrays, the curve of misses against capacity.
Usage: PYTHONPATH=build/release/python scripts/examples/histogram_mrc.py [--out mrc.png]
       [--ids N] [--seed S]
"""
import argparse

import matplotlib
import numpy as np

import meshreuse as mr

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--out", default="mrc.png")
ap.add_argument("--ids", type=int, default=2_000_000, help="accesses in the synthetic trace")
ap.add_argument("--seed", type=int, default=1)
a = ap.parse_args()

# A skewed trace: a hot set reused often, a long tail touched rarely (any integer array works).
rng = np.random.default_rng(a.seed)
ids = (rng.zipf(1.2, a.ids) % 100_000).astype(np.uint64)

r = mr.analyze(ids, granularity="element")
distances, counts = r.histogram
print(f"{r.accesses} accesses, {r.cold} cold, median distance {r.q50}, mean {r.mean:.1f}")
mrc = r.tables["mrc"]

fig, (h, m) = plt.subplots(1, 2, figsize=(10, 4))
h.loglog(distances + 1, counts, ".", ms=2)
h.set_xlabel("reuse distance + 1")
h.set_ylabel("accesses")
h.set_title("exact LRU stack distances")
m.semilogx(mrc["capacity"], mrc["miss_ratio"])
m.set_xlabel("capacity (ids)")
m.set_ylabel("miss ratio")
m.set_title("miss-ratio curve (fully associative LRU)")
fig.tight_layout()
fig.savefig(a.out, dpi=120)
print(f"wrote {a.out}")
