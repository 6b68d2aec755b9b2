"""Shared pieces of the report's plotting scripts (scripts/plot_*.py): reading the CSV files that
`meshreuse report` writes, one colour per ordering across every figure, and writing PNG + PDF
atomically. C++ writes the data; these scripts only draw it. Needs Debian's python3-matplotlib
(/usr/bin/python3; scripts/setup.sh --with-plots installs it)."""
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported)

# One colour per ordering in every figure (the paper's three first).
_FIXED = {"random": "#7f7f7f", "ori": "#1f77b4", "bfs": "#ff7f0e", "rdr": "#2ca02c"}
_OTHERS = ["#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf"]


def colour(ordering, _seen={}):
    if ordering in _FIXED:
        return _FIXED[ordering]
    if ordering not in _seen:
        _seen[ordering] = _OTHERS[len(_seen) % len(_OTHERS)]
    return _seen[ordering]


def read_csv(path):
    """Rows as dicts; raises SystemExit naming the file when it is missing or has no header."""
    if not os.path.isfile(path):
        raise SystemExit(f"plot: {path}: no such file")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows


def read_rows(path, why=""):
    """read_csv, refusing a file without rows (SystemExit naming it, and why that matters)."""
    rows = read_csv(path)
    if not rows:
        raise SystemExit(f"plot: {path}: no rows{why}")
    return rows


def num(s):
    """A CSV cell as a float; None for an empty (missing) cell."""
    return None if s is None or s == "" else float(s)


def unique(rows, key):
    """Values of `key` in first-seen order."""
    out = []
    for r in rows:
        if r[key] not in out:
            out.append(r[key])
    return out


def save(fig, out):
    """Writes out.png and out.pdf, each to a temporary name first."""
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    for ext in ("png", "pdf"):
        tmp = f"{out}.tmp.{os.getpid()}.{ext}"
        fig.savefig(tmp, dpi=130, bbox_inches="tight")
        os.replace(tmp, f"{out}.{ext}")
    plt.close(fig)


def grid(n, width=4.2, height=3.0, max_cols=3):
    """A figure with n panels in rows of at most max_cols; returns (fig, flat list of n axes)."""
    cols = min(n, max_cols)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(width * cols, height * rows), squeeze=False)
    flat = [a for row in axes for a in row]
    for a in flat[n:]:
        a.set_visible(False)
    return fig, flat[:n]


def grouped_bars(ax, groups, series, value, label=None):
    """Side by side within each group, one bar per series of height value(group, series) (None:
    no bar), coloured by series (an ordering)."""
    width = 0.8 / len(series)
    for k, s in enumerate(series):
        ys = [value(g, s) for g in groups]
        ax.bar([i + (k - (len(series) - 1) / 2) * width for i in range(len(groups))],
               [y if y is not None else 0 for y in ys], width=width, color=colour(s),
               label=label(s) if label else s)
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels(groups, fontsize=8)


def legend_below(fig, axes):
    """One legend under the panels, so it hides no line."""
    handles, labels = [], []
    for a in axes:
        for h, l in zip(*a.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 6),
                   bbox_to_anchor=(0.5, -0.02), frameon=False)
        fig.tight_layout(rect=(0, 0.06, 1, 1))
    else:
        fig.tight_layout()
