#!/usr/bin/env python3
"""The paper's closing conjecture, tested: for each mesh kernel (one panel each), the speedup per
sweep of every ordering against ORI of the same kernel, the mean over the meshes with its 95%
interval (tables/kernels_mean.csv). A bar above 1 is faster than ORI; the dashed line is BFS's
speedup, the paper's other reference. Without timing (--no-timing) there is no figure.

  scripts/plot_kernels.py KERNELS_MEAN.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
from plot_common import cli, num, plt, read_rows, save, unique


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    kernels = unique(rows, "kernel")
    ords = unique(rows, "ordering")
    cols = min(3, len(kernels))
    nrows = (len(kernels) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, squeeze=False, figsize=(4.2 * cols, 3.0 * nrows),
                             sharey=True)
    flat = [a for r in axes for a in r]
    for ax, k in zip(flat, kernels):
        mine = {r["ordering"]: r for r in rows if r["kernel"] == k}
        xs, ys, lo, hi = [], [], [], []
        for i, o in enumerate(ords):
            r = mine.get(o)
            v = 1.0 if o == "ori" else (num(r["speedup_vs_ori"]) if r else None)
            if v is None:
                continue
            a = num(r.get("speedup_vs_ori_lo", "")) if r and o != "ori" else None
            b = num(r.get("speedup_vs_ori_hi", "")) if r and o != "ori" else None
            xs.append(i), ys.append(v)
            lo.append(v - a if a is not None else 0), hi.append(b - v if b is not None else 0)
        if len(xs) <= 1:  # ORI alone: the report ran without timing
            ax.text(0.5, 0.5, "not timed (--no-timing)", transform=ax.transAxes, ha="center",
                    va="center", fontsize=9, color="0.3")
        colours = ["C3" if ords[x] == "rdr" else "C0" for x in xs]
        ax.bar(xs, ys, color=colours, yerr=[lo, hi], capsize=2)
        ax.axhline(1.0, color="0.3", lw=0.8)
        bfs = mine.get("bfs")
        if bfs and num(bfs["speedup_vs_ori"]) is not None:
            ax.axhline(num(bfs["speedup_vs_ori"]), color="0.5", lw=0.8, ls="--")
        ax.set_xticks(range(len(ords)))
        ax.set_xticklabels(ords, rotation=45, ha="right", fontsize=8)
        ax.set_title(k, fontsize=10)
    for ax in flat[len(kernels):]:
        ax.axis("off")
    for r in axes:
        r[0].set_ylabel("speedup per sweep\nagainst ORI (x)")
    fig.suptitle(title[:1].upper() + title[1:] if title else
                 "Speedup per sweep against ORI of each kernel (RDR red; dashed: BFS)",
                 fontsize=11)
    fig.tight_layout()
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
