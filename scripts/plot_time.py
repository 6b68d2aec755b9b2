#!/usr/bin/env python3
"""The paper's execution-time figure: time to convergence per mesh and ordering on one thread
(median over the rounds), with the mean speedup against ORI in the legend.

  scripts/plot_time.py TIME.csv OUT   (writes OUT.png, OUT.pdf)
"""
import sys

from plot_common import grouped_bars, legend_below, num, plt, read_rows, save, unique


def main(data, out):
    rows = read_rows(data)
    meshes = unique(rows, "mesh")
    ords = unique(rows, "ordering")
    fig, ax = plt.subplots(figsize=(max(6, 0.9 * len(meshes) * max(1, len(ords) / 2)), 3.6))

    def row(m, o):
        return next((r for r in rows if r["mesh"] == m and r["ordering"] == o), None)

    def label(o):
        sp = [num(row(m, o)["speedup_vs_ori"]) for m in meshes
              if row(m, o) and num(row(m, o)["speedup_vs_ori"]) is not None]
        return o + (f" (mean {sum(sp) / len(sp):.2f}x vs ori)" if sp else "")

    grouped_bars(ax, meshes, ords, lambda m, o: num(row(m, o)["total_s"]) if row(m, o) else None,
                 label)
    ax.set_ylabel("time to convergence (s)")
    ax.set_title("Laplacian smoothing, one thread (median over the rounds)", fontsize=11)
    legend_below(fig, [ax])
    save(fig, out)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
