#!/usr/bin/env python3
"""First-sweep reuse-distance histograms, one panel per mesh, one line per ordering, with the
cache capacities (in 66-byte elements) marked: an access to the right of a level's line misses it
in the fully associative model.

  scripts/plot_histograms.py HISTOGRAM.csv CAPACITIES.csv OUT   (writes OUT.png, OUT.pdf)
"""
import sys

from plot_common import colour, grid, legend_below, read_csv, read_rows, save, unique


def main(data, caps, out):
    rows = read_rows(data)
    levels = read_csv(caps)
    meshes = unique(rows, "mesh")
    fig, axes = grid(len(meshes), width=4.2, height=3.0)
    for ax, m in zip(axes, meshes):
        for o in unique([r for r in rows if r["mesh"] == m], "ordering"):
            rs = [r for r in rows if r["mesh"] == m and r["ordering"] == o and r["lo"] != "cold"]
            xs = [max(1, (int(r["lo"]) + int(r["hi"])) / 2) for r in rs]
            # counts per distance (bins widen as powers of two)
            ys = [int(r["count"]) / (int(r["hi"]) - int(r["lo"]) + 1) for r in rs]
            ax.plot(xs, ys, color=colour(o), lw=1.0, label=o)
        for lv in levels:
            ax.axvline(int(lv["elements"]), color="0.4", lw=0.7, ls="--")
            ax.text(int(lv["elements"]), 1.0, f" {lv['level']}", transform=ax.get_xaxis_transform(),
                    va="top", fontsize=7, color="0.3")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(m, fontsize=10)
        ax.set_xlabel("reuse distance (distinct vertices)")
        ax.set_ylabel("accesses per distance")
    fig.suptitle("Reuse distances of the first sweep; dashed: cache capacities in 66-byte "
                 "elements", fontsize=11)
    legend_below(fig, axes)
    save(fig, out)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
