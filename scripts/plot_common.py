"""Shared pieces of the report's plotting scripts (scripts/plot_*.py): reading the CSV files that
`meshreuse report` writes, one colour per ordering across every figure, and writing PNG + PDF
atomically. C++ writes the data; these scripts only draw it. Needs Debian's python3-matplotlib
(/usr/bin/python3; scripts/setup.sh --with-plots installs it); run by another python3 first on
PATH, a script re-runs itself under /usr/bin/python3."""
import contextlib
import csv
import os
import sys

try:
    import matplotlib
except ImportError:
    # A python3 first on PATH without matplotlib (pyenv, conda): run this script again under
    # Debian's, which scripts/setup.sh --with-plots provides.
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and \
            os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise SystemExit("plot: matplotlib is missing: install python3-matplotlib "
                     "(scripts/setup.sh --with-plots) and run with /usr/bin/python3")

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
        refuse(f"{path}: no such file")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows


def read_rows(path, why=""):
    """read_csv, refusing a file without rows (SystemExit naming it, and why that matters)."""
    rows = read_csv(path)
    if not rows:
        refuse(f"{path}: no rows{why}")
    return rows


def num(s):
    """A CSV cell as a float; None for an empty (missing) cell."""
    return None if s is None or s == "" else float(s)


def wants_help(doc):
    """-h or --help anywhere: the script's usage on stdout, exit 0."""
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(doc.strip())
        sys.exit(0)


def refuse(message):
    """One line on stderr naming the script, exit 2 (bad input), as meshreuse does."""
    print(f"{os.path.basename(sys.argv[0])}: {message}", file=sys.stderr)
    sys.exit(2)


def guarded(draw, inputs):
    """Runs draw(); an input it cannot plot (a column missing, a cell not a number) is refused in
    one line naming the inputs, not a traceback."""
    try:
        draw()
    except KeyError as e:
        refuse(f"{', '.join(inputs)}: no column {e}: not the table this script draws (see --help)")
    except (ValueError, IndexError, ZeroDivisionError, TypeError) as e:
        refuse(f"{', '.join(inputs)}: cannot be plotted: {e} (see --help)")


def usage_error(doc):
    """Wrong arguments: the usage lines of `doc` (those naming the script) and exit 2."""
    lines = [ln.strip() for ln in doc.splitlines() if "scripts/" in ln]
    refuse("wrong arguments; usage:\n  " + "\n  ".join(lines or [doc.strip()]))


def cli(plot, doc, n_inputs):
    """The command line of a figure script: INPUT... OUT [TITLE] [VARIANT] -> plot(inputs, out,
    title, variant); --help prints `doc`."""
    wants_help(doc)
    a = sys.argv[1:]
    if not n_inputs + 1 <= len(a) <= n_inputs + 3:
        usage_error(doc)
    rest = a[n_inputs + 1:] + ["", ""]
    guarded(lambda: plot(a[:n_inputs], a[n_inputs], title=rest[0], variant=rest[1]), a[:n_inputs])


def short(path):
    """A mesh's or trace's name from its path: out/meshes/paper/ocean.node -> ocean."""
    return os.path.basename(path).split(".")[0] if path else path


def unique(rows, key):
    """Values of `key` in first-seen order."""
    out = []
    for r in rows:
        if r[key] not in out:
            out.append(r[key])
    return out


def save(fig, out, dpi=130):
    """Writes out.png and out.pdf, each to a temporary name first, both cropped to the figure's
    tight bounding box. The box is found once, by a layout pass at the PNG's resolution, and
    given to both (bbox_inches="tight" would lay the figure out again before each format's
    drawing)."""
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    fig.set_dpi(dpi)
    renderer = fig.canvas.get_renderer()
    # A layout pass draws nothing (as savefig's own for "tight"; a matplotlib without it draws).
    with getattr(renderer, "_draw_disabled", contextlib.nullcontext)():
        fig.draw(renderer)
    box = fig.get_tightbbox(renderer).padded(matplotlib.rcParams["savefig.pad_inches"])
    for ext in ("png", "pdf"):
        tmp = f"{out}.tmp.{os.getpid()}.{ext}"
        fig.savefig(tmp, dpi=dpi, bbox_inches=box)
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


def grouped_bars(ax, groups, series, value, label=None, interval=None, hatched=None):
    """Side by side within each group, one bar per series of height value(group, series) (None:
    no bar), coloured by series (an ordering). interval(group, series) -> (lo, hi) draws an error
    bar (the 95% interval of the median); hatched(group, series) true hatches the bar (a
    comparison the interval cannot tell from the reference)."""
    width = 0.8 / len(series)
    for k, s in enumerate(series):
        xs = [i + (k - (len(series) - 1) / 2) * width for i in range(len(groups))]
        ys = [value(g, s) for g in groups]
        bars = ax.bar(xs, [y if y is not None else 0 for y in ys], width=width, color=colour(s),
                      label=label(s) if label else s)
        if hatched:
            for bar, g in zip(bars, groups):
                if hatched(g, s):
                    bar.set_hatch("///")
                    bar.set_edgecolor("white")
        if interval:
            for x, y, g in zip(xs, ys, groups):
                iv = interval(g, s)
                if y is None or iv is None or None in iv:
                    continue
                ax.errorbar(x, y, yerr=[[max(0, y - iv[0])], [max(0, iv[1] - y)]], color="black",
                            lw=0.8, capsize=2)
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels(groups, fontsize=8)


def interval(row, col, scale=1.0):
    """(lo, hi) of a spread column (COL_lo, COL_hi) of a CSV row, scaled; None when unknown."""
    if row is None:
        return None
    lo, hi = num(row.get(col + "_lo")), num(row.get(col + "_hi"))
    return None if lo is None or hi is None else (scale * lo, scale * hi)


def not_distinguishable(row, verdict_col):
    return row is not None and row.get(verdict_col) == "not distinguishable"


def legend_below(fig, axes):
    """One legend under the panels, so it hides no line."""
    handles, labels = [], []
    for a in axes:
        for h, l in zip(*a.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    if handles:
        ncol = min(len(labels), 6)
        rows = -(-len(labels) // ncol)
        fig.legend(handles, labels, loc="lower center", ncol=ncol, bbox_to_anchor=(0.5, -0.02),
                   frameon=False)
        # Room for the legend's rows (about 0.3 inch each) under the panels' axis labels.
        fig.tight_layout(rect=(0, min(0.4, 0.3 * rows / fig.get_size_inches()[1]), 1, 1))
    else:
        fig.tight_layout()
