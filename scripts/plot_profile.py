#!/usr/bin/env python3
"""The paper's profile figure: mean reuse distance over the sweeps, each sweep cut into 100 time
steps; one panel per ordering (the paper shows ORI alone), sweeps separated by dotted lines.

  scripts/plot_profile.py PROFILE.csv OUT   (writes OUT.png, OUT.pdf)
"""
import sys

from plot_common import colour, grid, num, read_rows, save, unique


def main(data, out):
    rows = read_rows(data, " (a trace without sweeps has no profile)")
    mesh = rows[0]["mesh"]
    ords = unique(rows, "ordering")
    fig, axes = grid(len(ords), width=5.0, height=3.2, max_cols=3)
    for ax, o in zip(axes, ords):
        rs = [r for r in rows if r["ordering"] == o]
        steps = max(int(r["step"]) for r in rs) + 1
        xs = [(int(r["iteration"]) - 1) * steps + int(r["step"]) for r in rs]
        ys = [num(r["mean_distance"]) for r in rs]
        ax.plot(xs, [y if y is not None else float("nan") for y in ys], color=colour(o), lw=0.9)
        for it in range(1, max(int(r["iteration"]) for r in rs)):
            ax.axvline(it * steps, color="0.8", lw=0.6, ls=":")
        ax.set_yscale("log")
        ax.set_title(o)
        ax.set_xlabel(f"time step ({steps} per sweep)")
        ax.set_ylabel("mean reuse distance")
    fig.suptitle(f"Reuse-distance profile of {mesh}", fontsize=11)
    fig.tight_layout()
    save(fig, out)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
