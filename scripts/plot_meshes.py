#!/usr/bin/env python3
"""The paper's Figure 7, the meshes: one panel per mesh, its boundary edges and a sample of its
vertices (the report's data/meshes.csv: mesh, kind, x1, y1, x2, y2).

  scripts/plot_meshes.py MESHES.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
from matplotlib.collections import LineCollection

from plot_common import cli, grid, num, read_rows, save, unique


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    meshes = unique(rows, "mesh")
    fig, axes = grid(len(meshes), width=3.4, height=3.0)
    for ax, m in zip(axes, meshes):
        mine = [r for r in rows if r["mesh"] == m]
        edges = [((num(r["x1"]), num(r["y1"])), (num(r["x2"]), num(r["y2"])))
                 for r in mine if r["kind"] == "edge"]
        pts = [(num(r["x1"]), num(r["y1"])) for r in mine if r["kind"] == "vertex"]
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=0.3, color="#9ab", rasterized=True)
        ax.add_collection(LineCollection(edges, colors="#234", linewidths=0.6))
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_axis_off()
        ax.set_title(m, fontsize=10)
    fig.suptitle(title[:1].upper() + title[1:] if title else "The meshes", fontsize=11)
    fig.tight_layout()
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
