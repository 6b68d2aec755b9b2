#!/usr/bin/env python3
"""Reuse-distance profiles (the paper's Figure 6): mean reuse distance over the sweeps, each sweep
cut into time steps, sweeps separated by dotted lines; one panel per input x ordering x thread x
granularity. Reads the one profile schema every command writes (`analyze --profile-csv`, the
report's data/profile.csv): input, ordering, thread, granularity, iteration, step, accesses,
cold, mean.

  scripts/plot_profile.py PROFILE.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
from plot_common import cli, colour, grid, num, read_rows, save, short, unique

KEY = ("input", "ordering", "thread", "granularity")


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0], " (a trace without sweeps has no profile)")
    keys = unique([dict(r, key=tuple(r[k] for k in KEY)) for r in rows], "key")
    varies = [i for i, k in enumerate(KEY) if len({key[i] for key in keys}) > 1]
    fig, axes = grid(len(keys), width=5.0, height=3.2, max_cols=3)
    for ax, key in zip(axes, keys):
        rs = [r for r in rows if tuple(r[k] for k in KEY) == key]
        steps = max(int(r["step"]) for r in rs) + 1
        xs = [(int(r["iteration"]) - 1) * steps + int(r["step"]) for r in rs]
        ys = [num(r["mean"]) for r in rs]
        ax.plot(xs, [y if y is not None else float("nan") for y in ys], color=colour(key[1]),
                lw=0.9)
        for it in range(1, max(int(r["iteration"]) for r in rs)):
            ax.axvline(it * steps, color="0.8", lw=0.6, ls=":")
        ax.set_yscale("log")
        names = [short(key[0]) if i == 0 else ("thread " + key[i] if i == 2 else key[i])
                 for i in (varies or [1])]
        ax.set_title(", ".join(names), fontsize=10)
        ax.set_xlabel(f"time step ({steps} per sweep)")
        ax.set_ylabel(f"mean reuse distance ({key[3]}s)")
    inputs_ = unique(rows, "input")
    fig.suptitle(title[:1].upper() + title[1:] if title else
                 "Reuse-distance profile of " + ", ".join(short(i) for i in inputs_), fontsize=11)
    fig.tight_layout()
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
