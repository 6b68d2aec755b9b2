#!/usr/bin/env python3
"""Draws every figure of a `meshreuse report` folder from its CSV files into DIR/figures/ (PNG and
PDF): figure1, profile, histograms, miss-rates, time, speedup, speedup-mean, gain, and scale when
run.json's label is "scale". A figure whose data the report does not have is skipped and said so.

  scripts/plot_report.py DIR
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import plot_figure1  # noqa: E402
import plot_histograms  # noqa: E402
import plot_misses  # noqa: E402
import plot_profile  # noqa: E402
import plot_scale  # noqa: E402
import plot_speedup  # noqa: E402
import plot_time  # noqa: E402


def main(d):
    data, tables, figs = (os.path.join(d, x) for x in ("data", "tables", "figures"))
    os.makedirs(figs, exist_ok=True)
    with open(os.path.join(d, "run.json")) as f:
        run = json.load(f)
    cfg = run["configuration"]
    made = []

    def have(*paths):
        return all(os.path.isfile(p) for p in paths)

    if have(os.path.join(data, "figure1.csv")):
        plot_figure1.main(os.path.join(data, "figure1.csv"),
                          os.path.join(data, "figure1_summary.csv"),
                          os.path.join(figs, "figure1"), cfg.get("figure1_mesh", ""))
        made.append("figure1")
    if have(os.path.join(data, "profile.csv")):
        plot_profile.main(os.path.join(data, "profile.csv"), os.path.join(figs, "profile"))
        made.append("profile")
    plot_histograms.main(os.path.join(data, "histogram.csv"), os.path.join(data, "capacities.csv"),
                         os.path.join(figs, "histograms"))
    plot_misses.main(os.path.join(data, "misses.csv"), os.path.join(figs, "miss-rates"))
    made += ["histograms", "miss-rates"]
    if have(os.path.join(tables, "time.csv")):
        plot_time.main(os.path.join(tables, "time.csv"), os.path.join(figs, "time"))
        plot_speedup.main(os.path.join(tables, "scaling.csv"), figs)
        made += ["time", "speedup", "speedup-mean", "gain"]
    if cfg.get("label") == "scale" and have(os.path.join(tables, "time.csv")):
        plot_scale.main(os.path.join(tables, "table1.csv"), os.path.join(tables, "time.csv"),
                        os.path.join(data, "misses.csv"), os.path.join(figs, "scale"))
        made.append("scale")
    print(f"plot_report: {len(made)} figures in {figs}: {', '.join(made)}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    main(sys.argv[1])
