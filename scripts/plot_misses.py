#!/usr/bin/env python3
"""The paper's cache figure: L1, L2 and L3 miss rates (misses / accesses reaching the level) per
mesh and ordering, one panel per level; says on the figure whether the misses were measured by
hardware counters or simulated.

  scripts/plot_misses.py MISSES.csv OUT   (writes OUT.png, OUT.pdf)
"""
import sys

from plot_common import colour, legend_below, num, plt, read_csv, save, unique


def main(data, out):
    rows = read_csv(data)
    if not rows:
        raise SystemExit(f"plot_misses: {data}: no rows")
    levels = unique(rows, "level")
    meshes = unique(rows, "mesh")
    ords = unique(rows, "ordering")
    fig, axes = plt.subplots(len(levels), 1, figsize=(max(6, 1.1 * len(meshes) * len(ords) / 2), 2.7 * len(levels)),
                             squeeze=False)
    axes = [a[0] for a in axes]
    width = 0.8 / len(ords)
    for ax, lv in zip(axes, levels):
        src = unique([r for r in rows if r["level"] == lv], "source")
        for k, o in enumerate(ords):
            ys = []
            for m in meshes:
                r = next((r for r in rows if r["level"] == lv and r["mesh"] == m and r["ordering"] == o), None)
                v = num(r["local_miss_rate"]) if r else None
                ys.append(100 * v if v is not None else 0)
            ax.bar([i + (k - (len(ords) - 1) / 2) * width for i in range(len(meshes))], ys,
                   width=width, color=colour(o), label=o)
        ax.set_xticks(range(len(meshes)))
        ax.set_xticklabels(meshes, fontsize=8)
        ax.set_ylabel(f"{lv} miss rate (%)")
        ax.set_title(f"{lv} ({'/'.join(src)})", fontsize=10)
    fig.suptitle("Miss rates per level, last traced sweep, one thread", fontsize=11)
    legend_below(fig, axes)
    save(fig, out)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
