#!/usr/bin/env python3
"""The many-core figures, from the report's simulation of the machine (`report --machine`), one per
VARIANT:
  figure11  accesses served by L2, L3 and memory in the warm sweep (summed over the threads)
            against the cores, for the paper's three meshes (carabiner, crake, dialog; else the
            first three), every ordering, compact placement solid and scatter dashed: the paper's
            Figure 11, which draws ORI only (data/machine.csv)
  misses    the mean over the meshes of each level's misses against the cores, both placements
            (tables/machine_misses.csv)
  speedup   Speedup(p) = C_ori(1) / C_ord(p) predicted, a band between the low and the high
            latencies, compact and scatter in two panels, the mean speedups measured here (squares)
            and on another machine (triangles: report --measured) as points, and the paper's claim
            for RDR at 32 cores (tables/predicted_speedup.csv)

  scripts/plot_machine.py INPUT OUT TITLE VARIANT   (OUT.png, OUT.pdf)
"""
from plot_common import cli, colour, grid, legend_below, num, plt, read_rows, save, unique

_STYLE = {"compact": "-", "scatter": "--"}
_PAPER_MESHES = ("carabiner", "crake", "dialog")


def _threads(rows):
    return sorted({int(r["threads"]) for r in rows})


def _line(rows, key, col):
    """(threads, values) of rows matching key over threads; a one-thread row counts for every
    placement (one thread is one run)."""
    pts = {}
    for r in rows:
        if num(r.get(col)) is None:
            continue
        if all(r[k] == v or (k == "placement" and r["threads"] == "1") for k, v in key.items()):
            pts[int(r["threads"])] = num(r[col])
    xs = sorted(pts)
    return xs, [pts[x] for x in xs]


def _xaxis(ax, threads):
    ax.set_xscale("log", base=2)
    ax.set_xticks(threads)
    ax.set_xticklabels([str(t) for t in threads])
    ax.set_xlabel("cores (threads)")


def figure11(path, out):
    rows = [r for r in read_rows(path, " (the report ran without --machine)")
            if r["prefetch"] == "off"]
    meshes = [m for m in _PAPER_MESHES if m in unique(rows, "mesh")] or unique(rows, "mesh")[:3]
    ords = unique(rows, "ordering")
    threads = _threads(rows)
    # Served by level: its hits; memory: local + remote.
    levels = [lv for lv in unique(rows, "level") if not lv.startswith("memory")][1:]
    served = {}
    for r in rows:
        lv = "memory" if r["level"].startswith("memory") else r["level"]
        k = (r["mesh"], r["ordering"], r["placement"], r["threads"], lv)
        served[k] = served.get(k, 0) + int(r["served"])
    cols = levels + ["memory"]
    fig, axes = plt.subplots(len(meshes), len(cols), figsize=(3.6 * len(cols), 2.8 * len(meshes)),
                             squeeze=False)
    for i, m in enumerate(meshes):
        for j, lv in enumerate(cols):
            ax = axes[i][j]
            for o in ords:
                for pl in ("compact", "scatter"):
                    xs = [t for t in threads
                          if (m, o, "compact" if t == 1 else pl, str(t), lv) in served]
                    ys = [served[(m, o, "compact" if t == 1 else pl, str(t), lv)] / 1e3 for t in xs]
                    if xs:
                        ax.plot(xs, ys, _STYLE[pl], color=colour(o), marker="o", ms=3,
                                label=f"{o}, {pl}")
            _xaxis(ax, threads)
            ax.set_title(f"{m}: served by {lv}", fontsize=10)
            ax.set_ylabel("accesses (x10^3)")
    fig.suptitle("Figure 11: where the warm sweep's accesses are served, against the cores "
                 "(simulated; solid compact, dashed scatter)", fontsize=11)
    legend_below(fig, [a for row in axes for a in row])
    save(fig, out)


def misses(path, out):
    rows = read_rows(path, " (the report ran without --machine)")
    ords = unique(rows, "ordering")
    threads = _threads(rows)
    cols = [c for c in rows[0] if c.endswith("_misses_k")]
    fig, axes = grid(len(cols), width=3.8, height=3.0)
    for ax, c in zip(axes, cols):
        for o in ords:
            for pl in ("compact", "scatter"):
                xs, ys = _line(rows, {"ordering": o, "placement": pl}, c)
                ax.plot(xs, ys, _STYLE[pl], color=colour(o), marker="o", ms=3, label=f"{o}, {pl}")
        _xaxis(ax, threads)
        ax.set_title(c.replace("_misses_k", " misses") + (" = memory accesses" if c == cols[-1]
                                                           else ""), fontsize=10)
        ax.set_ylabel("mean over meshes (x10^3)")
    fig.suptitle("Simulated misses of the warm sweep against the cores (solid compact, dashed "
                 "scatter)", fontsize=11)
    legend_below(fig, axes)
    save(fig, out)


def speedup(path, out):
    rows = read_rows(path, " (the report ran without --machine)")
    ords = unique(rows, "ordering")
    threads = _threads(rows)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), squeeze=False)
    axes = list(axes[0])
    for ax, pl in zip(axes, ("compact", "scatter")):
        for o in ords:
            xs, lo = _line(rows, {"ordering": o, "placement": pl}, "speedup_at_low_latency")
            _, hi = _line(rows, {"ordering": o, "placement": pl}, "speedup_at_high_latency")
            if not xs:
                continue
            ax.fill_between(xs, lo, hi, color=colour(o), alpha=0.25, lw=0)
            ax.plot(xs, [(a + b) / 2 for a, b in zip(lo, hi)], color=colour(o),
                    label=f"{o} predicted")
            mx, my = _line(rows, {"ordering": o, "placement": "compact"}, "measured_speedup")
            if mx:
                ax.plot(mx, my, "s", color=colour(o), mfc="white", label=f"{o} measured here")
            ex, ey = _line(rows, {"ordering": o, "placement": "compact"}, "measured_elsewhere")
            if ex:
                ax.plot(ex, ey, "^", color=colour(o), ms=7, ls="--", lw=0.8,
                        label=f"{o} measured elsewhere (--measured)")
        if "rdr" in ords and 32 in threads:
            ax.plot([32], [75], "*", color=colour("rdr"), ms=12, label="paper: RDR > 75")
        ax.plot(threads, threads, color="0.7", ls=":", label="ideal (ori)")
        _xaxis(ax, threads)
        ax.set_yscale("log", base=2)
        ax.set_ylabel("Speedup(p) = C_ori(1) / C_ord(p)")
        ax.set_title(f"{pl} placement (band: low to high latencies)", fontsize=10)
    fig.suptitle("Speedup(p) predicted by the simulated machine's cost model, mean over the "
                 "meshes", fontsize=11)
    legend_below(fig, axes)
    save(fig, out)


def plot(inputs, out, title="", variant="figure11"):
    {"figure11": figure11, "misses": misses, "speedup": speedup}[variant or "figure11"](inputs[0],
                                                                                       out)


if __name__ == "__main__":
    cli(plot, __doc__, 1)
