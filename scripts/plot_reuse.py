#!/usr/bin/env python3
"""Plots the reuse-distance CSVs that `meshreuse analyze` writes (C++ writes data, Python plots).

  scripts/plot_reuse.py profile  PROFILE.csv  OUT   # mean distance per time step, each sweep in
                                                    # 100 steps (the paper's carabiner figure)
  scripts/plot_reuse.py histogram HISTOGRAM.csv OUT  # distance distributions, log-log
  scripts/plot_reuse.py mrc MRC.csv OUT [NAME=CAP,...] # miss ratio against cache capacity (the
                                                    # exact step curve of `analyze --mrc-csv`;
                                                    # SHARDS estimates dashed), capacities marked

OUT is a name without extension: OUT.png and OUT.pdf are written (to temporary names, then
renamed). One line per input x ordering x thread x granularity found in the CSV. Needs Debian's
python3-matplotlib (run with /usr/bin/python3; scripts/setup.sh --with-plots installs it).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def series(path, key_fields):
    groups = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            key = tuple(row[k] for k in key_fields)
            groups.setdefault(key, []).append(row)
    if not groups:  # e.g. the profile of a trace without sweeps: say so, draw nothing
        raise ValueError("no rows to plot")
    return groups


def label(key):
    inp, ordering, thread, gran = key
    name = os.path.basename(inp).split(".")[0]
    return f"{name} {ordering}" + (f" t{thread}" if thread != "0" else "") + f" ({gran})"


def save(fig, out):
    for ext in ("png", "pdf"):
        tmp = f"{out}.tmp.{os.getpid()}.{ext}"
        fig.savefig(tmp, dpi=120, bbox_inches="tight")
        os.replace(tmp, f"{out}.{ext}")
    print(f"wrote {out}.png {out}.pdf")


def plot_profile(path, out):
    fig, ax = plt.subplots(figsize=(10, 4))
    for key, rows in series(path, ["input", "ordering", "thread", "granularity"]).items():
        xs, ys = [], []
        for r in rows:
            if r["mean"]:
                xs.append((int(r["iteration"]) - 1) * 100 + int(r["step"]))
                ys.append(float(r["mean"]))
        ax.plot(xs, ys, label=label(key), linewidth=1)
    ax.set_xlabel("time step (each sweep = 100 steps)")
    ax.set_ylabel("mean reuse distance")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    save(fig, out)


def plot_histogram(path, out):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, rows in series(path, ["input", "ordering", "thread", "granularity"]).items():
        total = sum(int(r["count"]) for r in rows) or 1
        xs, ys = [], []
        for r in rows:
            lo, hi, c = int(r["lo"]), int(r["hi"]), int(r["count"])
            if c:  # density per distance value, so log2 bins compare with exact ones
                xs.append(max(lo, 0.5) if lo == hi else (lo * hi) ** 0.5)
                ys.append(c / total / (hi - lo + 1))
        ax.plot(xs, ys, marker=".", linewidth=1, label=label(key))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("reuse distance (distinct elements or lines; 0 plotted at 0.5)")
    ax.set_ylabel("fraction of accesses per distance")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    save(fig, out)


def plot_mrc(path, out, marks=""):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, rows in series(path, ["input", "ordering", "thread", "granularity"]).items():
        xs = [max(int(r["capacity"]), 0.5) for r in rows]
        ys = [float(r["miss_ratio"]) for r in rows]
        estimated = rows[0].get("estimated") == "1"
        ax.step(xs, ys, where="post", linewidth=1, linestyle="--" if estimated else "-",
                label=label(key) + (" SHARDS" if estimated else ""))
    for mark in filter(None, marks.split(",")):
        name, cap = mark.split("=")
        ax.axvline(float(cap), color="grey", linewidth=0.8, linestyle=":")
        ax.text(float(cap), 1.0, f" {name}", fontsize=8, va="top", color="grey")
    ax.set_xscale("log")
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("cache capacity (distinct elements or lines; 0 plotted at 0.5)")
    ax.set_ylabel("miss ratio (fully associative LRU)")
    ax.legend(fontsize=8, loc="center")
    ax.grid(alpha=0.3)
    save(fig, out)


if __name__ == "__main__":
    kinds = {"profile": plot_profile, "histogram": plot_histogram, "mrc": plot_mrc}
    if len(sys.argv) not in (4, 5) or sys.argv[1] not in kinds or (
            len(sys.argv) == 5 and sys.argv[1] != "mrc"):
        sys.exit(__doc__)
    try:
        kinds[sys.argv[1]](*sys.argv[2:])
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"plot_reuse.py: {sys.argv[2]}: {e}")
