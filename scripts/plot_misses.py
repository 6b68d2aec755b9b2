#!/usr/bin/env python3
"""The paper's cache figure (Figure 9): misses per level, mesh and ordering in the last traced
(warm) sweep, one panel per level, as GLOBAL rates: misses over every access of the sweep, so a
level's bars compare orderings by the misses they cause there. (A local rate, misses over the
accesses reaching the level, is in tables/misses: it rises when the level above filters better,
which made BFS look worst at L2 although it has the fewest L2 misses.) A panel without any miss
says so: the warm sweep's data fit in that level. Each panel says whether its misses were
measured by hardware counters or simulated.

  scripts/plot_misses.py MISSES.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
from plot_common import cli, grouped_bars, legend_below, num, plt, read_rows, save, unique


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    levels = unique(rows, "level")
    meshes = unique(rows, "mesh")
    ords = unique(rows, "ordering")
    fig, axes = plt.subplots(len(levels), 1, squeeze=False,
                             figsize=(max(6, 1.1 * len(meshes) * len(ords) / 2), 2.7 * len(levels)))
    axes = [a[0] for a in axes]
    for ax, lv in zip(axes, levels):
        mine = [r for r in rows if r["level"] == lv]
        src = unique(mine, "source")

        def rate(m, o, mine=mine):
            r = next((r for r in mine if r["mesh"] == m and r["ordering"] == o), None)
            v = num(r["global_miss_rate"]) if r else None
            return 100 * v if v is not None else None

        grouped_bars(ax, meshes, ords, rate)
        ax.set_ylabel(f"{lv} misses per\naccess (%, global)")
        ax.set_title(f"{lv} ({'/'.join(src)})", fontsize=10)
        if all((num(r["misses"]) or 0) == 0 for r in mine):
            ax.text(0.5, 0.5, f"no {lv} miss in any mesh: the warm sweep's data fit in {lv}",
                    transform=ax.transAxes, ha="center", va="center", fontsize=9, color="0.3")
            ax.set_ylim(0, 1)
    fig.suptitle(title[:1].upper() + title[1:] if title else
                 "Misses per access of the last traced (warm) sweep, one thread", fontsize=11)
    legend_below(fig, axes)
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
