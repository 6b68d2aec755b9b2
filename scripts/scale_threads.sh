#!/usr/bin/env bash
# The threaded analyzer's speed-up on this machine, whole process: `meshreuse analyze TRACE
# --threads T` against `--threads 1` on the same trace, the two alternating (T, 1, T, 1, ...) so
# that drift hits both, --repeat times each; wall seconds, user + system CPU seconds and peak
# memory from /usr/bin/time; every run's table checked identical to the serial one. Traces (made
# once in OUT, seed 1, 20 M accesses by default over 2^20 ids): uniform ids, a stride-64 address
# scan from 0 and from a heap-like base (every reuse across the chunks), random 64-bit ids (hashed,
# oracleGeneral-like), uniform ids as a text trace (cut at line boundaries), and a mesh trace
# (plate41 refined 4 times, RDR, 4 sweeps, both granularities; --no-mesh skips it); the uniform
# and mesh traces also compressed in zstd frames (`meshreuse compress`). Then the model of
# scripts/project_mpi.py from the threads' own per-chunk phases (--rank-stats), for 32 and 64
# threads. Beside them, what this machine lets any division of the work gain: the trace cut into T
# part files exactly where the threads cut it (records; whole lines for text), each analysed by a
# serial process of its own, all T at once, nothing merged ("parts at once"; not for the mesh
# trace, whose format has no such parts, nor the compressed ones): first touches repeated in each
# part, shared caches and memory, cores that do not run alike all weigh on it as on the threads,
# the merge does not.
# Writes OUT/threads.csv (every run), OUT/threads.md (the table) and OUT/model/.
#
# Usage: scripts/scale_threads.sh [--threads 2,4,...] [--repeat R] [--accesses N --ids M]
#          [--no-mesh] [--out DIR]
#   default: --threads 2 (and the cores here, when more), --repeat 5, out/scale_threads
set -euo pipefail
caller=$PWD
cd "$(dirname "$0")/.."
threads="" repeat=5 accesses=20000000 ids=1048576 mesh=1 out="out/scale_threads"
source scripts/lib.sh
usage() { lib_usage 2 '/^#   default:/'; }
LIB_USAGE=usage
nomesh=0
lib_options --threads=threads --repeat=repeat --accesses=accesses --ids=ids --no-mesh=nomesh! \
  --out=out -- "$@"
((nomesh)) && mesh=0
[[ $out = /* ]] || out=$caller/$out
for v in "$accesses" "$ids" "$repeat"; do
  [[ $v =~ ^[1-9][0-9]{0,11}$ ]] || lib_die "'$v' is not a positive count"
done
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)
[[ -n $threads ]] || { threads=2; ((cores > 2)) && threads="2,$cores"; }
[[ $threads =~ ^[0-9]+(,[0-9]+)*$ ]] || lib_die "--threads takes counts like 2,4, found '$threads'"
bin=${MESHREUSE_BIN:-build/release/cli/meshreuse}
[[ -x $bin ]] || lib_die "no $bin: build Release first (scripts/test.sh or cmake)"
[[ -x /usr/bin/time ]] || lib_die "no /usr/bin/time (apt-get install time)"
/usr/bin/python3 -c 'import numpy' 2>/dev/null || lib_die "no numpy for /usr/bin/python3 (apt-get install python3-numpy)"
mkdir -p "$out/model"
if [[ ! -e $out/uniform.u64 ]]; then
  echo "scale_threads.sh: writing the traces in $out ($accesses accesses over $ids ids, seed 1)" >&2
  /usr/bin/python3 - "$out" "$accesses" "$ids" <<'PY'
import numpy as np, sys
out, n, m = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
rng = np.random.default_rng(1)
u = rng.integers(0, m, n, dtype=np.uint64)
u.tofile(out + "/uniform.u64")
scan = np.resize(np.arange(m, dtype=np.uint64) * np.uint64(64), n)
scan.tofile(out + "/scan.u64")
(scan + np.uint64(0x7f3a12345000)).tofile(out + "/scan_heap.u64")
ids = rng.integers(1, 2**63, m, dtype=np.uint64)
ids[rng.integers(0, m, n)].tofile(out + "/random64.u64")
with open(out + "/uniform.txt", "w") as f:
    for at in range(0, n, 1 << 20):
        f.write("\n".join(map(str, u[at:at + (1 << 20)].tolist())) + "\n")
PY
fi
traces=("uniform.u64 u64 element" "scan.u64 u64 element" "scan_heap.u64 u64 element"
        "random64.u64 u64 element" "uniform.txt text element")
# Compressed in zstd frames (meshreuse compress) of 4 MiB, or fewer KiB where that would make
# fewer than two frames a thread: each thread decompresses its own chunk.
max_t=$(tr , '\n' <<<"$threads" | sort -n | tail -n 1)
compress() {  # compress NAME
  [[ -e $out/$1.zst ]] && return
  local kib=$(($(stat -c %s "$out/$1") / 1024 / (2 * max_t)))
  ((kib > 4096)) && kib=4096
  ((kib < 1)) && kib=1
  "$bin" compress "$out/$1" -o "$out/$1.zst" --frame-kib "$kib" --quiet >/dev/null
}
compress uniform.u64
traces+=("uniform.u64.zst u64 element")
if ((mesh)); then
  if [[ ! -e $out/mesh.trace ]]; then
    echo "scale_threads.sh: writing the mesh trace (plate41 refined 4 times, RDR, 4 sweeps)" >&2
    "$bin" mesh refine tests/data/plate41.msh --levels 4 --jitter 0.3 -o "$out/plate4" --quiet >/dev/null
    "$bin" trace "$out/plate4.node" --ordering rdr -k 4 -o "$out/mesh.trace" --quiet >/dev/null
  fi
  compress mesh.trace
  traces+=("mesh.trace - -" "mesh.trace.zst - -")
fi
echo "trace,threads,run,wall_s,cpu_s,peak_kb,serial_wall_s,serial_cpu_s,serial_peak_kb,speedup,parts_wall_s,parts_speedup" >"$out/threads.csv"
parts() {  # parts NAME FORMAT T: OUT/parts/NAME.T.r for r < T, cut where T chunks are
  local d=$out/parts
  [[ -e $d/$1.$3.0 ]] && return
  mkdir -p "$d"
  /usr/bin/python3 - "$out/$1" "$2" "$3" "$d/$1.$3" <<'PY'
import sys
src, fmt, t, dst = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
data = open(src, "rb").read()
if fmt == "text":  # the whole lines that begin in bytes [B r/T, B (r+1)/T)
    b = len(data)
    start = lambda r: 0 if r == 0 else (b if r == t else data.find(b"\n", b * r // t - 1) + 1 or b)
else:  # records [N r/T, N (r+1)/T)
    n = len(data) // 8
    start = lambda r: n * r // t * 8
for r in range(t):
    open(f"{dst}.{r}", "wb").write(data[start(r):start(r + 1)])
PY
}
at_once() {  # at_once NAME FORMAT GRANULARITY T: wall seconds of the T parts' runs together
  local t0 t1 r pids=()
  t0=$(date +%s%N)
  for ((r = 0; r < $4; r++)); do
    "$bin" analyze "$out/parts/$1.$4.$r" --format "$2" --granularity "$3" --csv --quiet >/dev/null &
    pids+=($!)
  done
  for r in "${pids[@]}"; do wait "$r" || lib_die "$1: a part's analysis failed"; done
  t1=$(date +%s%N)
  t_parts=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }')
}
timed() {  # timed RESULT_PREFIX ARGS... : wall, cpu, peak KB in $t_wall $t_cpu $t_peak
  local p=$1
  shift
  local t0 t1
  t0=$(date +%s%N)
  /usr/bin/time -f "%U %S %M" -o "$p.time" "$bin" analyze "$@" --csv --quiet >"$p.csv"
  t1=$(date +%s%N)
  read -r u s t_peak <"$p.time"
  t_wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }')
  t_cpu=$(awk -v u="$u" -v s="$s" 'BEGIN { printf "%.2f", u + s }')
}
model_runs=()
for spec in "${traces[@]}"; do
  set -- $spec
  name=$1 args=("$out/$1")
  [[ $2 != - ]] && args+=(--format "$2" --granularity "$3")
  IFS=, read -ra ts <<<"$threads"
  cut=1  # the parts at once: plain foreign traces only
  [[ $2 == - || $name == *.zst ]] && cut=0
  for t in "${ts[@]}"; do
    ((cut)) && parts "$1" "$2" "$t"
    for ((k = 1; k <= repeat; k++)); do
      echo "scale_threads.sh: $name, --threads $t against 1, run $k of $repeat" >&2
      timed "$out/run" "${args[@]}" --threads "$t" --rank-stats "$out/model/$name-t$t-$k.json"
      w=$t_wall c=$t_cpu m=$t_peak
      t_parts="" ps=""
      if ((cut)); then
        at_once "$1" "$2" "$3" "$t"
      fi
      timed "$out/serial" "${args[@]}"
      cmp -s "$out/run.csv" "$out/serial.csv" || lib_die "$name: --threads $t's table differs from the serial one"
      [[ -n $t_parts ]] && ps=$(awk -v a="$t_wall" -v b="$t_parts" 'BEGIN { printf "%.3f", a / b }')
      echo "$name,$t,$k,$w,$c,$m,$t_wall,$t_cpu,$t_peak,$(awk -v a="$t_wall" -v b="$w" 'BEGIN { printf "%.3f", a / b }'),$t_parts,$ps" >>"$out/threads.csv"
      [[ $name = uniform.u64 ]] && model_runs+=("$t:$w:$out/model/$name-t$t-$k.json")
    done
  done
done
/usr/bin/python3 - "$out/threads.csv" "$out/threads.md" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
md = lambda v: statistics.median(v)
out = ["| trace | threads | 1 thread: wall s (min-max) | T threads: wall s (min-max) | speed-up, pair by pair: median (min-max) | T parts at once: speed-up, median (min-max) | threads' speed-up over the parts': median | CPU s, 1 / T | peak MB, 1 / T |",
       "|---|---|---|---|---|---|---|---|---|"]
keys = []
for r in rows:
    if (r["trace"], r["threads"]) not in keys:
        keys.append((r["trace"], r["threads"]))
for tr, t in keys:
    g = [r for r in rows if r["trace"] == tr and r["threads"] == t]
    f = lambda k: [float(r[k]) for r in g]
    out.append(f"| {tr} | {t} | {md(f('serial_wall_s')):.3f} ({min(f('serial_wall_s')):.3f}-{max(f('serial_wall_s')):.3f}) "
               f"| {md(f('wall_s')):.3f} ({min(f('wall_s')):.3f}-{max(f('wall_s')):.3f}) "
               f"| **{md(f('speedup')):.2f}x** ({min(f('speedup')):.2f}-{max(f('speedup')):.2f}) "
               + (f"| {md(f('parts_speedup')):.2f}x ({min(f('parts_speedup')):.2f}-{max(f('parts_speedup')):.2f}) "
                  f"| {md([float(r['parts_wall_s']) / float(r['wall_s']) for r in g]):.2f} "
                  if g[0]["parts_speedup"] else "| - | - ") +
               f"| {md(f('serial_cpu_s')):.2f} / {md(f('cpu_s')):.2f} "
               f"| {md(f('serial_peak_kb')) / 1024:.0f} / {md(f('peak_kb')) / 1024:.0f} |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
PY
# The model from the threads' phases on the uniform trace (thread CPU seconds per chunk), with an
# in-process "network": a block handed over in about 10 us, copied at about 5 GB/s.
/usr/bin/python3 scripts/project_mpi.py --out "$out/model" --cores "$cores" --project-accesses "$accesses" \
  --project-ids "$ids" --ranks 2,4,8,16,32,64 --alpha 1e-5 --beta 5e9 --threads-of-one-process \
  "${model_runs[@]}" >/dev/null
echo "scale_threads.sh: wrote $out/threads.csv, $out/threads.md and $out/model/projection.md" >&2
