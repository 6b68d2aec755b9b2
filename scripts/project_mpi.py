#!/usr/bin/python3
"""The MPI analysis's model (../shared/scale-out.md section 4) from measured constants.

Input: runs as NP:WALL_SECONDS:RANK_STATS_JSON (scripts/scale_mpi.sh). Constants, from the
medians over runs: t_a = analyse CPU seconds per access (reading included), t_f = stream CPU
seconds per stack id received, t_ft = resolve CPU seconds per first touch, memory = peak bytes per
distinct id of a rank's chunk. Model for N accesses over M ids on P ranks (blocks of B = 65,536
ids of s = 8 bytes; latency alpha, bandwidth beta):
  T(P) = t_a N / P + (M / B + P) (B (t_f + s / beta) + alpha) + t_ft min(M, N / P)
         + the reduction + min(M, P H) t_r,   H = min(M, N / P, h M / m)
the chunk, the stack's pipelined pass through every rank, the rank's first touches, the resolved
histograms added up, and rank 0 adding the merged lists into its histograms. Below
--scatter-from ranks (the analyzer's default, 16) the reduction is a binary tree of ranks:
  sum over its log2(P) levels k of H_k (t_r + 16 / beta) + alpha,   H_k = min(M, 2^k H);
from there on it is by distance (a reduce-scatter: each rank adds one slice of distances from
every rank, rank 0 gathers the slices):
  H (2 t_r + 16 / beta) + min(M, P H) (t_r + 16 / beta) + 2 (P - 1) alpha,
each rank sending and adding about H pairs (the slices' adds, into pages, counted at 2 t_r: 17 ns
a pair measured at 2 threads against the tree's 10.5) and rank 0 receiving at most M. t_r = CPU
seconds per (distance, count) pair received and added into a sorted list (merge_cpu: neither
waiting nor decoding, which the 16 / beta stands for). A chunk's
(distance, count) pairs H, its distinct distances, scale with the ids from those measured: h
pairs per chunk of m distinct ids (uniform ids: h = m, so H = M, the worst case; a mesh trace's
first touches spread too: h = 0.54 m for the RDR plate measured); the pairs of 2^k chunks at most
add up.
Writes OUT/runs.json, OUT/constants.json, OUT/projection.md."""
import argparse
import json
import math
import statistics
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--out", required=True)
    ap.add_argument("--cores", type=int, default=0)
    ap.add_argument("--project-accesses", type=float, default=1e11)
    ap.add_argument("--project-ids", type=float, default=1e8)
    ap.add_argument("--alpha", type=float, default=2e-6)
    ap.add_argument("--beta", type=float, default=1e10)
    ap.add_argument("--ranks", default="64,128,256,512,1024")
    ap.add_argument("--scatter-from", type=int, default=16)
    # Ranks as threads of one process (scripts/scale_threads.sh): each reports the process's peak,
    # so a rank's share is that over the ranks.
    ap.add_argument("--threads-of-one-process", action="store_true")
    a = ap.parse_args()
    runs = []
    for r in a.runs:
        np_, wall, path = r.split(":", 2)
        with open(path) as f:
            runs.append({"np": int(np_), "wall_s": float(wall), "ranks": json.load(f)})
    by_np = {}
    for r in runs:
        by_np.setdefault(r["np"], []).append(r)
    ta, tf, tft, mem, tr, pairs, dist = [], [], [], [], [], [], []
    for r in runs:
        for k in r["ranks"]:
            if k["accesses"]:
                ta.append(k["analyse_cpu_s"] / k["accesses"])
            if k["stack_ids_in"]:
                tf.append(k["stream_cpu_s"] / k["stack_ids_in"])
            if k["distinct"]:
                tft.append(k["resolve_cpu_s"] / k["distinct"])
                share = len(r["ranks"]) if a.threads_of_one_process else 1
                mem.append(k["peak_rss_bytes"] / share / k["distinct"])
            if k.get("pairs_added"):
                tr.append(k["merge_cpu_s"] / k["pairs_added"])
            if k.get("pairs") is not None and k["distinct"]:
                pairs.append(k["pairs"])
                dist.append(k["distinct"])
    med = lambda v: statistics.median(v) if v else float("nan")
    c = {"t_a_ns": 1e9 * med(ta), "t_f_ns": 1e9 * med(tf), "t_ft_ns": 1e9 * med(tft),
         "bytes_per_distinct_id": med(mem), "t_r_ns": 1e9 * med(tr),
         "pairs_per_rank": med(pairs), "distinct_per_rank": med(dist), "cores": a.cores}
    scaling = []
    base = med([r["wall_s"] for r in by_np.get(1, [])])
    for np_ in sorted(by_np):
        w = [r["wall_s"] for r in by_np[np_]]
        rank_wall = [max(k["wall_s"] for k in r["ranks"]) for r in by_np[np_]]
        cpu = [sum(k["analyse_cpu_s"] + k["stream_cpu_s"] + k["resolve_cpu_s"] + k["reduce_cpu_s"]
                   for k in r["ranks"]) for r in by_np[np_]]
        sent = [max(k["bytes_sent"] for k in r["ranks"]) for r in by_np[np_]]
        scaling.append({"np": np_, "wall_s_median": med(w), "wall_s_min": min(w),
                        "wall_s_max": max(w), "rank_wall_s_median": med(rank_wall),
                        "cpu_s_all_ranks_median": med(cpu), "max_bytes_sent_per_rank": med(sent),
                        "speedup_wall": base / med(w) if base == base else None,
                        "oversubscribed": bool(a.cores and np_ > a.cores)})
    c["scaling"] = scaling
    N, M, B, s = a.project_accesses, a.project_ids, 65536, 8
    tb = B * (c["t_f_ns"] * 1e-9 + s / a.beta) + a.alpha
    serial = c["t_a_ns"] * 1e-9 * N
    rows = []
    t_r = c["t_r_ns"] * 1e-9 if c["t_r_ns"] == c["t_r_ns"] else 0.0
    for P in (int(x) for x in a.ranks.split(",")):
        analyse = c["t_a_ns"] * 1e-9 * N / P
        stream = (M / B + P) * tb
        first = c["t_ft_ns"] * 1e-9 * min(M, N / P)
        levels = math.ceil(math.log2(P)) if P > 1 else 0
        h = c["pairs_per_rank"] * M / c["distinct_per_rank"] if c["distinct_per_rank"] else M
        H = min(M, N / P, h)
        if P >= max(a.scatter_from, 2):
            reduce = (H * (2 * t_r + 16 / a.beta) + min(M, P * H) * (t_r + 16 / a.beta)
                      + 2 * (P - 1) * a.alpha)
        else:
            reduce = sum(min(M, 2 ** k * H) * (t_r + 16 / a.beta) + a.alpha
                         for k in range(levels))
        reduce += min(M, P * H) * t_r  # rank 0 adds the merged lists into its histograms
        total = analyse + stream + first + reduce
        rows.append((P, analyse, stream, first, reduce, total, serial / total,
                     serial / total / P, c["bytes_per_distinct_id"] * min(M, N / P) / 1e9,
                     M * s / 1e9))
    with open(f"{a.out}/runs.json", "w") as f:
        json.dump(runs, f, indent=1)
    with open(f"{a.out}/constants.json", "w") as f:
        json.dump(c, f, indent=1)
    md = [f"Measured here: t_a = {c['t_a_ns']:.1f} ns per access (reading included), "
          f"t_f = {c['t_f_ns']:.2f} ns per streamed id, t_ft = {c['t_ft_ns']:.1f} ns per first "
          f"touch, t_r = {c['t_r_ns']:.1f} ns per histogram pair merged in the reduction "
          f"({c['pairs_per_rank']:.0f} pairs per rank's chunk of {c['distinct_per_rank']:.0f} "
          f"distinct ids here), "
          f"{c['bytes_per_distinct_id']:.0f} bytes of peak memory per distinct id of a "
          f"chunk.", "",
          "| np | wall s (median, min-max) | slowest rank's wall s | CPU s, all ranks | "
          "bytes sent, busiest rank | speed-up (wall) |", "|---|---|---|---|---|---|"]
    for r in scaling:
        md.append(f"| {r['np']}{' (oversubscribed)' if r['oversubscribed'] else ''} | "
                  f"{r['wall_s_median']:.2f} ({r['wall_s_min']:.2f}-{r['wall_s_max']:.2f}) | "
                  f"{r['rank_wall_s_median']:.2f} | {r['cpu_s_all_ranks_median']:.2f} | "
                  f"{r['max_bytes_sent_per_rank']:.3g} | " +
                  (f"{r['speedup_wall']:.2f}x |" if r['speedup_wall'] else "- |"))
    md += ["", f"Model for N = {N:.3g} accesses over M = {M:.3g} ids (serial: {serial:.0f} s), "
           f"alpha = {a.alpha:g} s, beta = {a.beta:.3g} bytes/s (stated, not measured):", "",
           f"| P | analyse s | stream s | first touches s | adding up s (a tree below {a.scatter_from} "
           "ranks, by distance from there) | total s | "
           "speed-up | efficiency | memory per rank GB | bytes sent per rank GB |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for P, an, st, ft, rd, tot, sp, eff, memg, sentg in rows:
        md.append(f"| {P} | {an:.2f} | {st:.2f} | {ft:.2f} | {rd:.2f} | {tot:.2f} | {sp:.1f}x | "
                  f"{100 * eff:.0f}% | {memg:.2f} | {sentg:.2f} |")
    with open(f"{a.out}/projection.md", "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    sys.exit(main())
