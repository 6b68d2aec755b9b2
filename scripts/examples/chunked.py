#!/usr/bin/python3
"""A chunked analysis driven from Python, as a batch array would run it: the trace file cut into
P chunks, each summarised on its own (any machine, any order), the summaries merged into exactly
the whole analysis -- checked here against the whole run.
Usage: PYTHONPATH=build/release/python scripts/examples/chunked.py [--chunks P] [--ids N]
       [--dir DIR]
"""
import argparse
import os

import numpy as np

import meshreuse as mr

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--chunks", type=int, default=4)
ap.add_argument("--ids", type=int, default=1_000_000)
ap.add_argument("--dir", default="chunks")
a = ap.parse_args()
os.makedirs(a.dir, exist_ok=True)

trace = os.path.join(a.dir, "trace.u64")
np.random.default_rng(5).integers(0, 50_000, a.ids, dtype=np.uint64).tofile(trace)
summaries = []
for k in range(a.chunks):  # each iteration is one task of a batch array
    out = os.path.join(a.dir, f"chunk{k}.summary")
    mr.summarize(trace, (k, a.chunks), out, format="u64")
    summaries.append(out)
merged = mr.merge(summaries)
whole = mr.analyze(trace, format="u64")
assert np.array_equal(merged.histogram[0], whole.histogram[0])
assert np.array_equal(merged.histogram[1], whole.histogram[1])
assert merged.sum == whole.sum and merged.cold == whole.cold
print(f"{a.chunks} chunks merged = the whole analysis: {merged.accesses} accesses, "
      f"{merged.cold} cold, exact sum {merged.sum}, q50 {merged.q50}")
