#!/usr/bin/env python3
"""Smoothing before and after: a window of triangles around a mesh's centre in the file's
coordinates and after smoothing to convergence, each triangle coloured by its quality (shortest
edge / longest edge), the window's mean quality in each panel's title (the report's
data/smoothing.csv: mesh, stage, triangle, x1, y1, x2, y2, x3, y3).

  scripts/plot_smoothing.py SMOOTHING.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
import math

from matplotlib.collections import PolyCollection

from plot_common import cli, num, plt, read_rows, save, unique


def quality(t):
    d = [math.dist(t[i], t[(i + 1) % 3]) for i in range(3)]
    return min(d) / max(d) if max(d) > 0 else 0


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    stages = unique(rows, "stage")
    fig, axes = plt.subplots(1, len(stages), figsize=(5 * len(stages), 4.6), squeeze=False)
    for ax, st in zip(axes[0], stages):
        tris = [[(num(r[f"x{i}"]), num(r[f"y{i}"])) for i in (1, 2, 3)]
                for r in rows if r["stage"] == st]
        qs = [quality(t) for t in tris]
        pc = PolyCollection(tris, array=qs, cmap="viridis", edgecolors="white", linewidths=0.4)
        pc.set_clim(0, 1)
        ax.add_collection(pc)
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_axis_off()
        ax.set_title(f"{st}: mean quality {sum(qs) / len(qs):.3f}, worst {min(qs):.3f}", fontsize=10)
    fig.colorbar(pc, ax=list(axes[0]), label="triangle quality (shortest / longest edge)",
                 shrink=0.8)
    fig.suptitle(title[:1].upper() + title[1:] if title else "Smoothing, before and after",
                 fontsize=11)
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
