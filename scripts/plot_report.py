#!/usr/bin/env python3
"""Draws every figure of a `meshreuse report` folder into DIR/figures/ (PNG and PDF). What to draw,
from which files, with which script, comes from DIR/manifest.json, which the report writes from
its one table of outputs (reports/report_list.h): this script has no list of its own. Each
figure's script exposes plot(inputs, out, title, variant).

  scripts/plot_report.py DIR
"""
import importlib
import json
import multiprocessing
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import plot_common  # noqa: E402,F401  (re-runs this script under Debian's python3 if needed)


def draw(d, fig):
    """One figure; its exit status (0: drawn; a refused input has said why on stderr)."""
    module = importlib.import_module(fig["script"][:-3])
    inputs = [os.path.join(d, i) for i in fig["inputs"]]
    try:
        plot_common.guarded(
            lambda: module.plot(inputs, os.path.join(d, "figures", fig["name"]),
                                title=fig.get("title", ""), variant=fig.get("variant", "")),
            inputs)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else 1
    return 0


def main(d):
    figs = os.path.join(d, "figures")
    manifest = os.path.join(d, "manifest.json")
    if not os.path.isfile(manifest):
        plot_common.refuse(f"{manifest}: no such file (not a report folder?)")
    os.makedirs(figs, exist_ok=True)
    with open(manifest) as f:
        figures = json.load(f)["figures"]
    # The figures are independent: drawn side by side, a process per core (matplotlib is not
    # thread-safe), in the manifest's order; the first refusal's status is the script's.
    workers = min(len(figures), len(os.sched_getaffinity(0)))
    if workers > 1:
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            codes = pool.starmap(draw, [(d, fig) for fig in figures], chunksize=1)
    else:
        codes = [draw(d, fig) for fig in figures]
    failed = [c for c in codes if c]
    if failed:
        sys.exit(failed[0])
    made = [fig["name"] for fig in figures]
    print(f"plot_report: {len(made)} figures in {figs}: {', '.join(made)}")


if __name__ == "__main__":
    plot_common.wants_help(__doc__)
    if len(sys.argv) != 2:
        plot_common.usage_error(__doc__)
    main(sys.argv[1])
