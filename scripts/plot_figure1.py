#!/usr/bin/env python3
"""The paper's first figure: the reuse distance of every access of the first sweep, one panel per
ordering (random, ORI, BFS on ocean), as a density in time x log2(distance) so ten million points
stay readable; the caption of each panel gives the average distance, the modelled L1 miss rate and
the time to convergence, ours and the paper's.

  scripts/plot_figure1.py FIGURE1.csv FIGURE1_SUMMARY.csv OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
import matplotlib.colors as mcolors

from plot_common import cli, num, plt, read_csv, read_rows, save, unique


def plot(inputs, out, title="", variant=""):
    data, summary = inputs
    rows = read_rows(data)
    summ = {r["ordering"]: r for r in read_csv(summary)}
    ords = unique(rows, "ordering")
    fig, axes = plt.subplots(len(ords), 1, figsize=(9, 2.9 * len(ords)), squeeze=False)
    tmax = max(int(r["time_bin"]) for r in rows) + 1
    finite = [r for r in rows if r["distance_lo"] != "cold"]
    dmax = max(int(r["distance_hi"]) for r in finite) if finite else 1
    vmax = max(int(r["count"]) for r in rows)
    for ax, o in zip([a[0] for a in axes], ords):
        xs, ys, ws = [], [], []
        for r in rows:
            if r["ordering"] != o or r["distance_lo"] == "cold":
                continue
            lo, hi = int(r["distance_lo"]), int(r["distance_hi"])
            xs.append(int(r["time_bin"]) + 0.5)
            ys.append(max(0.5, (lo + hi) / 2) if lo > 0 else 0.5)
            ws.append(int(r["count"]))
        ybins = [0.35] + [2 ** (k / 4) for k in range(0, int(4 * (dmax.bit_length() + 1)))]
        h = ax.hist2d(xs, ys, bins=[range(tmax + 1), ybins], weights=ws,
                      norm=mcolors.LogNorm(vmin=1, vmax=vmax), cmap="viridis")
        # The PDF holds the density as an image (the PNG's resolution), not tens of thousands of
        # cells as paths: 1.5-1.9 MB and half the figure's drawing time otherwise.
        h[3].set_rasterized(True)
        ax.set_yscale("log")
        ax.set_ylabel("reuse distance\n(distinct vertices)")
        s = summ.get(o, {})
        ours = (f"average distance {num(s.get('mean_distance')) or 0:,.0f}, "
                f"modelled L1 miss rate {num(s.get('model_l1_miss_rate_pct')) or 0:.2f}%")
        t = num(s.get("seconds"))
        if t is not None:
            ours += f", time {t:.3g} s"
        paper = ""
        if s.get("paper_mean_distance"):
            paper = (f"\npaper: {num(s['paper_mean_distance']):,.0f}, "
                     f"{num(s['paper_l1_miss_rate_pct']):.2f}% (measured), "
                     f"{num(s['paper_seconds']):.3g} s")
        ax.set_title(f"{o.upper() if o in ('ori', 'bfs', 'rdr') else o}: {ours}{paper}",
                     fontsize=9)
        fig.colorbar(h[3], ax=ax, label="accesses per cell")
    axes[-1][0].set_xlabel(f"time: position in the first sweep ({tmax} bins)")
    fig.suptitle(title[:1].upper() + title[1:] if title else
                 "Reuse distance of every access of the first sweep", fontsize=11)
    fig.tight_layout()
    save(fig, out)


if __name__ == "__main__":
    cli(plot, __doc__, 2)
