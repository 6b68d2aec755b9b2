#!/usr/bin/env python3
"""Miss-ratio curves (fully associative LRU): miss ratio against cache capacity, the exact step
curve of `analyze --mrc-csv` (SHARDS estimates dashed), one line per input x ordering x thread x
granularity, capacities marked when given as NAME=CAPACITY,... (in elements or lines). Reads the
one MRC schema: input, ordering, thread, granularity, capacity, misses, accesses, miss_ratio,
estimated.

  scripts/plot_mrc.py MRC.csv OUT [TITLE] [NAME=CAP,...]   (writes OUT.png, OUT.pdf)
"""
from plot_common import cli, colour, plt, read_rows, save, short, unique

KEY = ("input", "ordering", "thread", "granularity")


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key in unique([dict(r, key=tuple(r[k] for k in KEY)) for r in rows], "key"):
        rs = [r for r in rows if tuple(r[k] for k in KEY) == key]
        xs = [max(int(r["capacity"]), 0.5) for r in rs]
        ys = [float(r["miss_ratio"]) for r in rs]
        estimated = rs[0].get("estimated") == "1"
        name = f"{short(key[0])} {key[1]}" + (f" t{key[2]}" if key[2] != "0" else "")
        ax.step(xs, ys, where="post", lw=1, ls="--" if estimated else "-", color=colour(key[1]),
                label=f"{name} ({key[3]})" + (" SHARDS" if estimated else ""))
    for mark in filter(None, variant.split(",")):  # NAME=CAP,...
        name, cap = mark.split("=")
        ax.axvline(float(cap), color="grey", lw=0.8, ls=":")
        ax.text(float(cap), 1.0, f" {name}", fontsize=8, va="top", color="grey")
    ax.set_xscale("log")
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("cache capacity (distinct elements or lines; 0 plotted at 0.5)")
    ax.set_ylabel("miss ratio (fully associative LRU)")
    ax.set_title(title or "Miss-ratio curves", fontsize=11)
    ax.legend(fontsize=8, loc="center")
    ax.grid(alpha=0.3)
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
