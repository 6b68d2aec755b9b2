#!/usr/bin/env python3
"""Each ordering as a picture: one panel per ordering, a sample of the mesh's vertices coloured
by their position in the ordering (dark first, bright last), so the way an ordering walks the
mesh shows: BFS's wavefront, RDR's chains, a curve's blocks (the report's
data/order_positions.csv: mesh, ordering, x, y, position).

  scripts/plot_orderings.py ORDER_POSITIONS.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
from plot_common import cli, grid, num, read_rows, save, unique


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    ords = unique(rows, "ordering")
    fig, axes = grid(len(ords), width=4.0, height=3.6)
    for ax, o in zip(axes, ords):
        mine = [r for r in rows if r["ordering"] == o]
        sc = ax.scatter([num(r["x"]) for r in mine], [num(r["y"]) for r in mine],
                        c=[num(r["position"]) for r in mine], s=1.2, cmap="viridis", vmin=0,
                        vmax=1, rasterized=True)
        ax.set_aspect("equal")
        ax.set_axis_off()
        ax.set_title(o, fontsize=10)
    cb = fig.colorbar(sc, ax=axes, shrink=0.8, pad=0.02)
    cb.set_label("position (0 first, 1 last)", fontsize=9)
    fig.suptitle(title[:1].upper() + title[1:] if title else "The orderings as pictures",
                 fontsize=11)
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
