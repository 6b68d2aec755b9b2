#!/usr/bin/env python3
"""The paper's scalability figures from the report's scaling table:
  speedup       Speedup(p) = T_ori(1) / T_ord(p) against threads, one panel per mesh
  speedup-mean  the mean over meshes, one line per ordering, with the ideal line
  gain          Gain(p) of each ordering against ORI and against BFS, mean over meshes (solid)
                and per mesh (thin)

  scripts/plot_speedup.py SCALING.csv OUTDIR   (writes OUTDIR/{speedup,speedup-mean,gain}.{png,pdf})
"""
import os
import sys

from plot_common import colour, grid, legend_below, num, plt, read_rows, save, unique


def main(data, outdir):
    rows = read_rows(data)
    meshes = unique(rows, "mesh")
    ords = unique(rows, "ordering")
    threads = sorted({int(r["threads"]) for r in rows})

    def series(mesh, o, col):
        xs, ys = [], []
        for p in threads:
            r = next((r for r in rows if r["mesh"] == mesh and r["ordering"] == o
                      and int(r["threads"]) == p), None)
            if r and num(r[col]) is not None:
                xs.append(p)
                ys.append(num(r[col]))
        return xs, ys

    fig, axes = grid(len(meshes), width=3.8, height=2.9)
    for ax, m in zip(axes, meshes):
        for o in ords:
            xs, ys = series(m, o, "speedup")
            ax.plot(xs, ys, marker="o", color=colour(o), label=o)
        ax.plot(threads, threads, color="0.7", ls=":", label="ideal (ori)")
        ax.set_title(m, fontsize=10)
        ax.set_xlabel("threads")
        ax.set_ylabel("speedup vs ORI, 1 thread")
        ax.set_xticks(threads)
    fig.suptitle("Speedup(p) = T_ori(1) / T_ord(p)", fontsize=11)
    legend_below(fig, axes)
    save(fig, os.path.join(outdir, "speedup"))

    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for o in ords:
        ys = []
        for p in threads:
            v = [num(r["speedup"]) for r in rows if r["ordering"] == o and int(r["threads"]) == p
                 and num(r["speedup"]) is not None]
            ys.append(sum(v) / len(v) if v else float("nan"))
        ax.plot(threads, ys, marker="o", color=colour(o), label=o)
    ax.plot(threads, threads, color="0.7", ls=":", label="ideal (ori)")
    ax.set_xlabel("threads")
    ax.set_ylabel("mean speedup vs ORI, 1 thread")
    ax.set_xticks(threads)
    ax.set_title(f"Mean speedup over {len(meshes)} mesh(es)", fontsize=11)
    legend_below(fig, [ax])
    save(fig, os.path.join(outdir, "speedup-mean"))

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), squeeze=False)
    axes = list(axes[0])
    for ax, ref in zip(axes, ("ori", "bfs")):
        col = f"gain_vs_{ref}_pct"
        for o in ords:
            if o == ref:
                continue
            for m in meshes:
                xs, ys = series(m, o, col)
                ax.plot(xs, ys, color=colour(o), lw=0.6, alpha=0.5)
            ys = []
            for p in threads:
                v = [num(r[col]) for r in rows if r["ordering"] == o and int(r["threads"]) == p
                     and num(r[col]) is not None]
                ys.append(sum(v) / len(v) if v else float("nan"))
            ax.plot(threads, ys, marker="o", lw=2, color=colour(o), label=f"{o} (mean)")
        ax.axhline(0, color="0.5", lw=0.6)
        ax.set_xlabel("threads")
        ax.set_ylabel(f"gain vs {ref.upper()} (%)")
        ax.set_xticks(threads)
        ax.set_title(f"(T_{ref}(p) - T_ord(p)) / T_{ref}(p); thin: per mesh", fontsize=10)
    legend_below(fig, axes)
    save(fig, os.path.join(outdir, "gain"))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
