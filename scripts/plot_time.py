#!/usr/bin/env python3
"""The paper's execution-time figure: time to convergence per mesh and ordering on one thread
(median over the rounds, error bars the 95% interval of the median), with the mean per-sweep
speedup against ORI in the legend; a bar is hatched when its per-sweep speedup against ORI cannot
be told from 1 (not distinguishable).

  scripts/plot_time.py TIME.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
from plot_common import (cli, grouped_bars, interval, legend_below, not_distinguishable, num,
                         plt, read_rows, save, unique)


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    meshes = unique(rows, "mesh")
    ords = unique(rows, "ordering")
    fig, ax = plt.subplots(figsize=(max(6, 0.9 * len(meshes) * max(1, len(ords) / 2)), 3.6))

    def row(m, o):
        return next((r for r in rows if r["mesh"] == m and r["ordering"] == o), None)

    def label(o):
        sp = [num(row(m, o)["speedup_vs_ori"]) for m in meshes
              if row(m, o) and num(row(m, o)["speedup_vs_ori"]) is not None]
        return o + (f" (mean {sum(sp) / len(sp):.2f}x per sweep vs ori)" if sp else "")

    grouped_bars(ax, meshes, ords, lambda m, o: num(row(m, o)["total_s"]) if row(m, o) else None,
                 label, interval=lambda m, o: interval(row(m, o), "total_s"),
                 hatched=lambda m, o: not_distinguishable(row(m, o), "speedup_vs_ori_verdict"))
    ax.set_ylabel("time to convergence (s)")
    ax.set_title("Laplacian smoothing, one thread: median over the rounds, 95% interval; hatched: "
                 "per-sweep time not distinguishable from ORI", fontsize=9)
    legend_below(fig, [ax])
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
