#!/usr/bin/env python3
"""The paper's cache figure: L1, L2 and L3 miss rates (misses / accesses reaching the level) per
mesh and ordering, one panel per level; says on the figure whether the misses were measured by
hardware counters or simulated.

  scripts/plot_misses.py MISSES.csv OUT   (writes OUT.png, OUT.pdf)
"""
import sys

from plot_common import grouped_bars, legend_below, num, plt, read_rows, save, unique


def main(data, out):
    rows = read_rows(data)
    levels = unique(rows, "level")
    meshes = unique(rows, "mesh")
    ords = unique(rows, "ordering")
    fig, axes = plt.subplots(len(levels), 1, squeeze=False,
                             figsize=(max(6, 1.1 * len(meshes) * len(ords) / 2), 2.7 * len(levels)))
    axes = [a[0] for a in axes]
    for ax, lv in zip(axes, levels):
        src = unique([r for r in rows if r["level"] == lv], "source")

        def rate(m, o, lv=lv):
            r = next((r for r in rows if r["level"] == lv and r["mesh"] == m
                      and r["ordering"] == o), None)
            v = num(r["local_miss_rate"]) if r else None
            return 100 * v if v is not None else None

        grouped_bars(ax, meshes, ords, rate)
        ax.set_ylabel(f"{lv} miss rate (%)")
        ax.set_title(f"{lv} ({'/'.join(src)})", fontsize=10)
    fig.suptitle("Miss rates per level, last traced sweep, one thread", fontsize=11)
    legend_below(fig, axes)
    save(fig, out)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
