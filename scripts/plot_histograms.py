#!/usr/bin/env python3
"""Reuse-distance histograms, one panel per input x granularity, one line per ordering (and thread
when there are several), with cache capacities marked when given: an access to the right of a
level's line misses it in the fully associative model. Reads the one histogram schema every
command writes (`analyze --histogram-csv`, the report's data/histogram.csv): input, ordering,
thread, granularity, lo, hi, count (a "cold" row counts first touches, shown in the legend).
CAPACITIES.csv (the report's data/capacities.csv: level, bytes, ways, elements, lines) is optional.

  scripts/plot_histograms.py HISTOGRAM.csv [CAPACITIES.csv] OUT [TITLE]   (writes OUT.png, OUT.pdf)
"""
import sys

from plot_common import (colour, grid, guarded, legend_below, read_csv, read_rows, save, short,
                         unique, usage_error, wants_help)


def plot(inputs, out, title="", variant=""):
    rows = read_rows(inputs[0])
    levels = read_csv(inputs[1]) if len(inputs) > 1 else []
    panels = unique([dict(r, panel=(r["input"], r["granularity"])) for r in rows], "panel")
    threads = len(unique(rows, "thread")) > 1
    fig, axes = grid(len(panels), width=4.2, height=3.0)
    for ax, (inp, gran) in zip(axes, panels):
        mine = [r for r in rows if r["input"] == inp and r["granularity"] == gran]
        for o in unique(mine, "ordering"):
            for t in unique([r for r in mine if r["ordering"] == o], "thread"):
                rs = [r for r in mine if r["ordering"] == o and r["thread"] == t]
                cold = sum(int(r["count"]) for r in rs if r["lo"] == "cold")
                rs = [r for r in rs if r["lo"] != "cold" and int(r["count"]) > 0]
                xs = [max(1, (int(r["lo"]) + int(r["hi"])) / 2) for r in rs]
                # counts per distance (bins widen as powers of two)
                ys = [int(r["count"]) / (int(r["hi"]) - int(r["lo"]) + 1) for r in rs]
                label = o + (f" t{t}" if threads else "") + (f" ({cold:,} cold)" if cold else "")
                ax.plot(xs, ys, color=colour(o), lw=1.0, label=label)
        unit = "elements" if gran == "element" else "lines"
        for lv in levels:
            ax.axvline(int(lv[unit]), color="0.4", lw=0.7, ls="--")
            ax.text(int(lv[unit]), 1.0, f" {lv['level']}", transform=ax.get_xaxis_transform(),
                    va="top", fontsize=7, color="0.3")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{short(inp)} ({gran})", fontsize=10)
        ax.set_xlabel(f"reuse distance (distinct {gran}s)")
        ax.set_ylabel("accesses per distance")
        ax.legend(fontsize=7)
    fig.suptitle(title[:1].upper() + title[1:] if title else "Reuse-distance histograms" +
                 ("; dashed: cache capacities" if levels else ""), fontsize=11)
    fig.tight_layout()
    save(fig, out)


if __name__ == "__main__":
    wants_help(__doc__)
    a = sys.argv[1:]
    n = 2 if len(a) >= 3 and a[1].endswith(".csv") else 1  # the capacities are optional
    if not n + 1 <= len(a) <= n + 2:
        usage_error(__doc__)
    guarded(lambda: plot(a[:n], a[n], title=a[n + 1] if len(a) > n + 1 else ""), a[:n])
