#!/usr/bin/env python3
"""Simulated misses per level: one panel per level, bars per input x ordering (threads summed),
the cold (compulsory) part darker, so the excess an ordering could still remove is the light
part. Reads the one simulation schema every command writes (`simulate --csv` or its --out folder's
simulate.csv): input, ordering, thread, sweep, level, ..., accesses, hits, misses, cold, excess, ...

  scripts/plot_simulation.py SIMULATE.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
from plot_common import cli, colour, plt, read_rows, save, short, unique


def plot(inputs, out, title="", variant=""):
    rows = [r for r in read_rows(inputs[0]) if r["sweep"] == "all"]
    levels = unique(rows, "level")
    keys = unique([dict(r, key=(r["input"], r["ordering"])) for r in rows], "key")
    fig, axes = plt.subplots(1, len(levels), figsize=(3.2 * len(levels) + 1, 3.6), squeeze=False)
    for ax, lv in zip(axes[0], levels):
        for i, (inp, o) in enumerate(keys):
            rs = [r for r in rows if r["level"] == lv and r["input"] == inp and r["ordering"] == o]
            misses = sum(int(r["misses"]) for r in rs)
            cold = sum(int(r["cold"]) for r in rs)
            ax.bar(i, misses, color=colour(o), alpha=0.45)
            ax.bar(i, cold, color=colour(o))
        ax.set_xticks(range(len(keys)))
        ax.set_xticklabels([f"{short(i)}\n{o}" for i, o in keys], fontsize=7)
        ax.set_title(f"{lv} misses (dark: cold)", fontsize=10)
    fig.suptitle(title or "Simulated misses per level", fontsize=11)
    fig.tight_layout()
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
