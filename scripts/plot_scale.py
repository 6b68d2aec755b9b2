#!/usr/bin/env python3
"""reproduce.sh --scale: one shape meshed at growing sizes; per ordering, the time per vertex per
sweep and the simulated misses per access at each level against the vertex count. Where the
working set leaves a cache, the orderings part.

  scripts/plot_scale.py TABLE1.csv TIME.csv MISSES.csv OUT   (writes OUT.png, OUT.pdf)
"""
from plot_common import cli, colour, legend_below, num, plt, read_csv, read_rows, save, unique


def plot(inputs, out, title="", variant=""):
    table1, time, misses = inputs
    sizes = {r["mesh"]: int(r["vertices"]) for r in read_csv(table1)}
    trows = read_csv(time)
    mrows = read_rows(misses)
    ords = unique(mrows, "ordering")
    levels = unique(mrows, "level")
    fig, axes = plt.subplots(1, 1 + len(levels), figsize=(4.2 * (1 + len(levels)), 3.6),
                             squeeze=False)
    axes = list(axes[0])
    for o in ords:
        pts = sorted((sizes[r["mesh"]], num(r["sweep_ms"]) * 1e6 / sizes[r["mesh"]])
                     for r in trows if r["ordering"] == o and num(r["sweep_ms"]) is not None)
        if pts:
            axes[0].plot(*zip(*pts), marker="o", color=colour(o), label=o)
        for ax, lv in zip(axes[1:], levels):
            pts = sorted((sizes[r["mesh"]], num(r["global_miss_rate"]))
                         for r in mrows if r["ordering"] == o and r["level"] == lv
                         and num(r["global_miss_rate"]) is not None)
            if pts:
                ax.plot(*zip(*pts), marker="o", color=colour(o), label=o)
    axes[0].set_ylabel("time per vertex per sweep (ns)")
    axes[0].set_title("one thread", fontsize=10)
    for ax, lv in zip(axes[1:], levels):
        src = "/".join(unique([r for r in mrows if r["level"] == lv], "source"))
        ax.set_ylabel(f"{lv} misses per access")
        ax.set_title(f"{lv} ({src}, last traced sweep)", fontsize=10)
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("vertices")
    fig.suptitle("Orderings against mesh size", fontsize=11)
    legend_below(fig, axes)
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 3)
