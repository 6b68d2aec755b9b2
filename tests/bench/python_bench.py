#!/usr/bin/python3
"""The Python module against the command line on the same work, side by side, in turn:
analyze of N ids from a numpy array (the call) against `meshreuse analyze FILE --format u64` on
the same ids in a file (the whole process, the file in the page cache), and smoothing from Python
against `meshreuse smooth` (per-sweep times, each side's median). Prints each pair's ratio
(Python / command: below 1 is faster) with the median and range over the rounds.
Usage: PYTHONPATH=build/release/python tests/bench/python_bench.py [--ids N] [--distinct D]
       [--rounds R] [--mesh MESH] [--bin build/release/cli/meshreuse] [--threads T]
"""
import argparse
import csv
import io
import os
import statistics
import subprocess
import tempfile
import time

import numpy as np

import meshreuse as mr

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--ids", type=int, default=100_000_000)
ap.add_argument("--distinct", type=int, default=1 << 20)
ap.add_argument("--rounds", type=int, default=3)
ap.add_argument("--mesh", default=None, help="a mesh for the smoothing pair (none: skipped)")
ap.add_argument("--bin", default="build/release/cli/meshreuse")
ap.add_argument("--threads", type=int, default=1)
a = ap.parse_args()


def spread(xs):
    return f"{statistics.median(xs):.3f} ({min(xs):.3f}-{max(xs):.3f})"


with tempfile.TemporaryDirectory() as tmp:
    ids = np.random.default_rng(1).integers(0, a.distinct, a.ids, dtype=np.uint64)
    path = os.path.join(tmp, "ids.u64")
    ids.tofile(path)
    cmd = [a.bin, "analyze", path, "--format", "u64", "--granularity", "element", "--threads",
           str(a.threads), "--csv", "--quiet"]
    py_s, cli_s, ratios = [], [], []
    for r in range(a.rounds):
        t0 = time.perf_counter()
        res = mr.analyze(ids, granularity="element", threads=a.threads)
        t1 = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
        t2 = time.perf_counter()
        theirs = list(csv.DictReader(io.StringIO(out)))[0]
        assert int(theirs["sum"]) == res.sum and int(theirs["cold"]) == res.cold
        py_s.append(t1 - t0), cli_s.append(t2 - t1), ratios.append((t1 - t0) / (t2 - t1))
        print(f"round {r + 1}: python {t1 - t0:.3f} s, command {t2 - t1:.3f} s", flush=True)
    print(f"analyze {a.ids} ids over {a.distinct} ({a.threads} thread(s)): python {spread(py_s)} s,"
          f" command {spread(cli_s)} s, python/command {spread(ratios)}")

    if a.mesh:
        mesh = mr.Mesh.read(a.mesh)
        laid = mesh.permute(mesh.ordering("ori"))
        py_sw, cli_sw, ratios = [], [], []
        for r in range(a.rounds):
            s = mr.smooth(laid, max_iters=20, tol=-1)
            py = statistics.median(s.seconds)
            out = subprocess.run([a.bin, "smooth", a.mesh, "--max-iters", "20", "--tol", "-1",
                                  "--csv", "--quiet"], capture_output=True, text=True,
                                 check=True).stdout
            rows = list(csv.DictReader(io.StringIO(out)))
            theirs = statistics.median(float(x["ms"]) / 1000 for x in rows)
            py_sw.append(py), cli_sw.append(theirs), ratios.append(py / theirs)
        print(f"smooth {a.mesh} (20 sweeps, per-sweep medians): python {spread(py_sw)} s, "
              f"command {spread(cli_sw)} s, python/command {spread(ratios)}")
