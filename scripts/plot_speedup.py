#!/usr/bin/env python3
"""The paper's scalability figures, one per VARIANT, on per-sweep medians, error bars the 95%
intervals; a hollow marker is a comparison the interval cannot tell from the reference (not
distinguishable):
  speedup  Speedup(p) = T_ori(1) / T_ord(p) against threads, one panel per mesh (Figure 10), from
           the report's scaling table
  mean     the mean over meshes, one line per ordering, with the ideal line (Figure 12), from
           scaling_mean
  gain     Gain(p) of each ordering against ORI and against BFS: the mean over meshes (thick, from
           scaling_mean) and per mesh (thin, from scaling) (Figure 13)

  scripts/plot_speedup.py SCALING.csv [SCALING_MEAN.csv] OUT TITLE VARIANT   (OUT.png, OUT.pdf)
"""
import sys

from plot_common import (colour, grid, guarded, legend_below, num, plt, read_rows, save, unique,
                         usage_error, wants_help)


def _points(ax, xs, ys, los, his, faint, o, **kw):
    """A line with error bars; each point filled, or hollow when `faint` (not distinguishable)."""
    ax.plot(xs, ys, color=colour(o), **kw)
    for x, y, lo, hi, f in zip(xs, ys, los, his, faint):
        if lo is not None and hi is not None:
            ax.errorbar(x, y, yerr=[[max(0, y - lo)], [max(0, hi - y)]], color=colour(o), lw=0.8,
                        capsize=2)
        ax.plot(x, y, marker="o", color=colour(o), markerfacecolor="white" if f else colour(o))


def _series(rows, key, col, verdict):
    """Points of rows matching key (dict of column -> value) over threads, sorted."""
    pts = []
    for r in rows:
        if all(r[k] == v for k, v in key.items()) and num(r[col]) is not None:
            pts.append((int(r["threads"]), num(r[col]), num(r.get(col + "_lo")),
                        num(r.get(col + "_hi")), r.get(verdict) == "not distinguishable"))
    pts.sort()
    return [list(x) for x in zip(*pts)] if pts else [[], [], [], [], []]


def plot(inputs, out, title="", variant="speedup"):
    per_mesh = read_rows(inputs[0])
    mean = read_rows(inputs[1]) if len(inputs) > 1 else []
    ords = unique(per_mesh, "ordering")
    threads = sorted({int(r["threads"]) for r in per_mesh})
    if variant == "mean":
        fig, ax = plt.subplots(figsize=(5.5, 3.8))
        for o in ords:
            xs, ys, lo, hi, f = _series(mean, {"ordering": o}, "mean_speedup", "mean_speedup_verdict")
            _points(ax, xs, ys, lo, hi, f, o, label=o)
        ax.plot(threads, threads, color="0.7", ls=":", label="ideal (ori)")
        ax.set_xlabel("threads")
        ax.set_ylabel("mean speedup vs ORI, 1 thread")
        ax.set_xticks(threads)
        ax.set_title(f"Mean speedup over {len(unique(per_mesh, 'mesh'))} mesh(es), 95% intervals",
                     fontsize=10)
        legend_below(fig, [ax])
    elif variant == "gain":
        fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), squeeze=False)
        axes = list(axes[0])
        for ax, ref in zip(axes, ("ori", "bfs")):
            for o in ords:
                if o == ref:
                    continue
                for m in unique(per_mesh, "mesh"):
                    xs, ys, _, _, _ = _series(per_mesh, {"ordering": o, "mesh": m},
                                              f"gain_vs_{ref}_pct", "")
                    ax.plot(xs, ys, color=colour(o), lw=0.6, alpha=0.5)
                col = f"mean_gain_vs_{ref}_pct"
                xs, ys, lo, hi, f = _series(mean, {"ordering": o}, col, col + "_verdict")
                _points(ax, xs, ys, lo, hi, f, o, lw=2, label=f"{o} (mean)")
            ax.axhline(0, color="0.5", lw=0.6)
            ax.set_xlabel("threads")
            ax.set_ylabel(f"gain vs {ref.upper()} (%)")
            ax.set_xticks(threads)
            ax.set_title(f"(T_{ref}(p) - T_ord(p)) / T_{ref}(p); thin: per mesh; hollow: not "
                         "distinguishable", fontsize=9)
        legend_below(fig, axes)
    else:
        meshes = unique(per_mesh, "mesh")
        fig, axes = grid(len(meshes), width=3.8, height=2.9)
        for ax, m in zip(axes, meshes):
            for o in ords:
                xs, ys, lo, hi, f = _series(per_mesh, {"ordering": o, "mesh": m}, "speedup",
                                            "speedup_verdict")
                _points(ax, xs, ys, lo, hi, f, o, label=o)
            ax.plot(threads, threads, color="0.7", ls=":", label="ideal (ori)")
            ax.set_title(m, fontsize=10)
            ax.set_xlabel("threads")
            ax.set_ylabel("speedup vs ORI, 1 thread")
            ax.set_xticks(threads)
        fig.suptitle("Speedup(p) = T_ori(1) / T_ord(p) per sweep, 95% intervals; hollow: not "
                     "distinguishable", fontsize=11)
        legend_below(fig, axes)
    save(fig, out)


if __name__ == "__main__":
    wants_help(__doc__)
    a = sys.argv[1:]
    if len(a) not in (4, 5):
        usage_error(__doc__)
    guarded(lambda: plot(a[:-3], a[-3], title=a[-2], variant=a[-1]), a[:-3])
