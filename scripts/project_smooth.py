#!/usr/bin/python3
"""The distributed smoother's scaling table and model (../shared/scale-out.md section 4).

Input: runs as KIND:P:DIR (scripts/scale_smooth.sh), DIR holding sweeps.csv and ranks.csv of
`meshreuse smooth-ranks` / `meshreuse-mpi smooth` (KIND strong or weak) or sweeps.csv of the serial
`meshreuse smooth --quality per-sweep` (KIND strong-serial or weak-serial). Per run: the median
wall ms per sweep over its sweeps (the first, which warms the caches, left out) and the spread.
Constants from the strong runs: t_v = each rank's thread CPU seconds per moved vertex per sweep
(median over ranks and runs at the largest P, and at P = 1), c_g = ghosts per rank / sqrt(V/P)
(the boundary of a compact part grows as its side), m = messages per rank per sweep, and the
peak memory per vertex of the mesh (every rank reads the whole mesh today). Model for V vertices
on P ranks, per sweep:
  T(P) = t_v V / P + m alpha + c_g sqrt(V/P) * 16 / beta + 2 log2(P) alpha
(the part's moves, its messages, its ghost coordinates, the exact quality's all-reduce).
Writes OUT/runs.json, OUT/constants.json, OUT/scaling.md, OUT/projection.md."""
import argparse
import csv
import json
import math
import os
import statistics


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def mesh_size(d):
    with open(os.path.join(d, "run.json")) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--out", required=True)
    ap.add_argument("--cores", type=int, default=0)
    ap.add_argument("--transport", default="threads")
    ap.add_argument("--sweeps", type=int, default=10)
    ap.add_argument("--project-vertices", type=float, default=1e9)
    ap.add_argument("--alpha", type=float, default=2e-6)
    ap.add_argument("--beta", type=float, default=1e10)
    a = ap.parse_args()
    runs = []
    for r in a.runs:
        kind, p, d = r.split(":", 2)
        sw = read_csv(os.path.join(d, "sweeps.csv"))
        ms = [float(s["ms"]) for s in sw][1:] or [float(sw[0]["ms"])]
        run = {"kind": kind, "ranks": int(p), "dir": d, "sweeps": len(sw),
               "ms_per_sweep": statistics.median(ms), "ms_min": min(ms), "ms_max": max(ms)}
        ranks_csv = os.path.join(d, "ranks.csv")
        if os.path.exists(ranks_csv):
            rk = read_csv(ranks_csv)
            owned = sum(int(x["owned"]) for x in rk)
            run.update({
                "vertices": owned,
                "moved": [int(x["noncut"]) + int(x["cut"]) for x in rk],
                "ghosts": [int(x["ghosts"]) for x in rk],
                "cpu_s": [float(x["cpu_s"]) for x in rk],
                "wait_s": [float(x["wait_s"]) for x in rk],
                "setup_s": [float(x["setup_s"]) for x in rk],
                "messages": [int(x["messages"]) for x in rk],
                "bytes_sent": [int(x["bytes_sent"]) for x in rk],
                "peak_rss_mb": max(float(x["peak_rss_mb"]) for x in rk),
                # a distributed read (mesh file, ranges): each rank holds its part only
                "ranges": all(x.get("read_mb", "-") != "-" for x in rk),
                "rss_bytes_per_owned": max(float(x["rss_bytes_per_owned"]) for x in rk
                                           if x["rss_bytes_per_owned"] != "-"),
            })
        else:
            summ = read_csv(os.path.join(d, "summary.csv"))[0]
            run["vertices"] = int(summ["vertices"])
        runs.append(run)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "runs.json"), "w") as f:
        json.dump(runs, f, indent=1)

    def group(kind, p):
        return [r for r in runs if r["kind"] == kind and r["ranks"] == p]

    lines = [f"Transport: {a.transport}; {a.sweeps} ordered Gauss-Seidel sweeps a run; median wall "
             "ms per sweep over the runs' sweeps after the first (min-max of the run medians); "
             "speed-up against the same kind at 1 rank.", ""]
    for kind in ("strong", "weak"):
        ps = sorted({r["ranks"] for r in runs if r["kind"] == kind})
        if not ps:
            continue
        base = statistics.median(r["ms_per_sweep"] for r in group(kind, 1)) if group(kind, 1) else None
        ser = [r["ms_per_sweep"] for r in runs if r["kind"] == kind + "-serial"]
        lines += [f"**{kind}**" + (f" (serial `smooth --quality per-sweep` at the 1-rank mesh: "
                                     f"{statistics.median(ser):.1f} ms/sweep)" if ser else ""), "",
                  "| ranks | vertices | per rank | ms/sweep (spread) | speed-up | efficiency | "
                  "cpu ms/sweep, slowest rank | wait ms/sweep, most | ghosts/rank | peak RSS MB |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for p in ps:
            g = group(kind, p)
            med = statistics.median(r["ms_per_sweep"] for r in g)
            lo, hi = min(r["ms_per_sweep"] for r in g), max(r["ms_per_sweep"] for r in g)
            v = g[0]["vertices"]
            sw = g[0]["sweeps"]
            cpu = statistics.median(max(r["cpu_s"]) for r in g) * 1e3 / sw
            wait = statistics.median(max(r["wait_s"]) for r in g) * 1e3 / sw
            gh = statistics.median(g[0]["ghosts"])
            if kind == "strong":
                sp = base / med if base else float("nan")
                eff = sp / p
            else:  # weak: the same work per rank, so efficiency is T(1)/T(P)
                sp = base / med * p * (v / group(kind, 1)[0]["vertices"]) / p if base else float("nan")
                eff = base / med if base else float("nan")
            lines.append(f"| {p} | {v:,} | {v // p:,} | {med:.1f} ({lo:.1f}-{hi:.1f}) | "
                         f"{sp:.2f}x | {100 * eff:.0f}% | {cpu:.1f} | {wait:.1f} | {gh:,.0f} | "
                         f"{g[0]['peak_rss_mb']:,.0f} |")
        lines.append("")
    with open(os.path.join(a.out, "scaling.md"), "w") as f:
        f.write("\n".join(lines) + "\n")

    strong = [r for r in runs if r["kind"] == "strong"]
    pmax = max(r["ranks"] for r in strong)

    def tv(p):
        vals = [c / (m * r["sweeps"]) for r in strong if r["ranks"] == p
                for c, m in zip(r["cpu_s"], r["moved"]) if m > 0]
        return statistics.median(vals)
    tv1, tvp = tv(1), tv(pmax)
    cg = statistics.median(statistics.median(r["ghosts"]) / math.sqrt(r["vertices"] / r["ranks"])
                           for r in strong if r["ranks"] > 1) if pmax > 1 else 5.5
    msgs = statistics.median(max(r["messages"]) / r["sweeps"] for r in strong if r["ranks"] == pmax)
    rss = statistics.median(r["peak_rss_mb"] * 2**20 / r["vertices"] for r in strong if r["ranks"] == 1)
    ranges = all(r.get("ranges") for r in strong)
    # Read in ranges, a rank's peak is its part's: bytes per owned vertex at the most ranks.
    per_owned = statistics.median(r["rss_bytes_per_owned"] for r in strong if r["ranks"] == pmax)
    const = {"t_v_1_rank_s": tv1, f"t_v_{pmax}_ranks_s": tvp, "ghost_coefficient": cg,
             "messages_per_rank_per_sweep": msgs, "peak_bytes_per_vertex_1_rank": rss,
             "ranges_read": ranges, f"peak_bytes_per_owned_vertex_{pmax}_ranks": per_owned,
             "alpha_s": a.alpha, "beta_bytes_per_s": a.beta, "cores": a.cores,
             "transport": a.transport}
    with open(os.path.join(a.out, "constants.json"), "w") as f:
        json.dump(const, f, indent=1)
    V = a.project_vertices
    out = [f"Model for V = {V:.3g} vertices (constants measured here: t_v = {tvp * 1e9:.1f} ns per "
           f"moved vertex per sweep at {pmax} ranks, {tv1 * 1e9:.1f} ns at 1; ghosts = "
           f"{cg:.2f} sqrt(V/P); {msgs:.1f} messages per rank per sweep; alpha = {a.alpha:g} s, "
           f"beta = {a.beta:g} B/s; " +
           (f"each rank reads its range: {per_owned:.0f} B per owned vertex at {pmax} ranks):"
            if ranges else f"every rank reads the whole mesh: {rss:.0f} B per vertex of it):"), "",
           "| ranks | vertices/rank | compute ms/sweep | messages + ghosts + all-reduce ms | "
           "total ms/sweep | efficiency | memory per rank |",
           "|---|---|---|---|---|---|---|"]
    for p in (64, 128, 256, 512, 1024):
        comp = tvp * V / p
        comm = msgs * a.alpha + cg * math.sqrt(V / p) * 16 / a.beta + 2 * math.log2(p) * a.alpha
        tot = comp + comm
        out.append(f"| {p} | {V / p:.3g} | {comp * 1e3:.1f} | {comm * 1e3:.3f} | {tot * 1e3:.1f} | "
                   f"{100 * comp / tot:.1f}% | "
                   f"{(per_owned * V / p if ranges else rss * V) / 1e9:.1f} GB |")
    with open(os.path.join(a.out, "projection.md"), "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(lines + out))


if __name__ == "__main__":
    main()
