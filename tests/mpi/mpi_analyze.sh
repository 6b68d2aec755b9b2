#!/usr/bin/env bash
# meshreuse-mpi (cli/mpi_main.cc) at -np 1, 2, 3, 4 against the serial analyzer: every output
# (table, histogram, profile, miss-ratio curve) byte for byte equal on a meshreuse trace (2 threads,
# 3 sweeps, element and line) and on scan, uniform, hashed 64-bit, u32, oracle, text, lackey and
# 3-access traces
# (fewer accesses than ranks, sizes not divisible by P). A rank killed mid-run ends the job
# non-zero with the rank named, never a hang; bad input exits 2 naming the rank and the problem.
# Usage: mpi_analyze.sh MESHREUSE MESHREUSE_MPI MPIEXEC DATA
set -u
bin=$1 mpi=$2 mpiexec=$3 data=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
export OMPI_MCA_mpi_yield_when_idle=1 OMPI_MCA_rmaps_base_oversubscribe=1
export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0  # Open MPI's own allocations
pass=0 fail=0
run() { timeout 120 "$mpiexec" --oversubscribe -np "$@"; }
outputs() {  # outputs PREFIX COMMAND... : the table and three files
  local p=$1
  shift
  "$@" --csv --quiet --histogram-csv "$p.h" --profile-csv "$p.p" --mrc-csv "$p.m" >"$p.t" 2>"$p.err"
}
same() {
  local x ok=1
  [[ -s "$2.t" && -s "$2.h" ]] || { ok=0; echo "FAIL $1: no serial output"; cat "$2.err"; }
  for x in t h p m; do
    [[ -e "$2.$x" || -e "$3.$x" ]] || continue
    cmp -s "$2.$x" "$3.$x" || { ok=0; echo "FAIL $1: .$x differs"; diff "$2.$x" "$3.$x" | head -5; head -5 "$3.err"; }
  done
  if ((ok)); then pass=$((pass + 1)); else fail=$((fail + 1)); fi
}

"$bin" trace "$data/plate41.msh" --ordering rdr -k 3 -t 2 -o "$tmp/mesh.trace" --quiet &>/dev/null
/usr/bin/env python3 - "$tmp" <<'PY'
import random, struct, sys
d = sys.argv[1]
rng = random.Random(7)
def u64(name, vals):
    with open(f"{d}/{name}", "wb") as f:
        f.write(b"".join(struct.pack("<Q", v) for v in vals))
u64("scan.u64", [64 * (i % 997) for i in range(9973)])
u64("uniform.u64", [rng.randrange(3000) for _ in range(20011)])
u64("hashed.u64", [(rng.randrange(500) * 0x9E3779B97F4A7C15 | 1 << 63) & (2**64 - 1) for _ in range(7001)])
u64("tiny.u64", [5, 9, 5])
with open(f"{d}/ids.u32", "wb") as f:
    f.write(b"".join(struct.pack("<I", rng.randrange(1000) * 4) for _ in range(5003)))
with open(f"{d}/cache.oracle", "wb") as f:
    f.write(b"".join(struct.pack("<IQIq", i, rng.randrange(400) << 40, 1, -1) for i in range(3001)))
with open(f"{d}/ids.txt", "w") as f:
    f.write("\n".join("# c" if i % 9 == 0 else str(rng.randrange(700)) for i in range(4001)) + "\n")
PY
zstd -q -d -c "$data/lackey/transpose.lackey.zst" >"$tmp/transpose.lackey"

outputs "$tmp/serial-mesh" "$bin" analyze "$tmp/mesh.trace"
for np in 1 2 3 4; do
  outputs "$tmp/mpi" run "$np" "$mpi" analyze "$tmp/mesh.trace"
  same "mesh trace -np $np" "$tmp/serial-mesh" "$tmp/mpi"
  for f in "scan.u64 u64 element" "uniform.u64 u64 element" "hashed.u64 u64 element" \
           "tiny.u64 u64 element" "ids.u32 u32 line" "cache.oracle oracle element" \
           "ids.txt text element" "transpose.lackey lackey line"; do
    set -- $f
    outputs "$tmp/serial" "$bin" analyze "$tmp/$1" --format "$2" --granularity "$3"
    outputs "$tmp/mpi" run "$np" "$mpi" analyze "$tmp/$1" --format "$2" --granularity "$3"
    same "$1 -np $np" "$tmp/serial" "$tmp/mpi"
  done
done

# A rank killed after its chunk: the job ends, non-zero, naming the rank.
MESHREUSE_MPI_KILL_RANK=1 run 3 "$mpi" analyze "$tmp/uniform.u64" --format u64 --quiet >"$tmp/out" 2>&1
rc=$?
if [[ $rc -ne 0 && $rc -ne 124 ]] && grep -q "rank 1" "$tmp/out"; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL killed rank: exit $rc"; head -20 "$tmp/out"; fi
# Bad input: exit 2, the rank and the problem named.
run 2 "$mpi" analyze "$tmp/missing.trace" --quiet >"$tmp/out" 2>&1
rc=$?
if [[ $rc -eq 2 ]] && grep -q "meshreuse-mpi: rank [01]: error: $tmp/missing.trace" "$tmp/out"; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL missing input: exit $rc"; head -20 "$tmp/out"; fi
run 2 "$mpi" analyze "$tmp/uniform.u64" --format text --quiet >"$tmp/out" 2>&1
rc=$?
if [[ $rc -eq 2 ]] && grep -q "meshreuse-mpi: rank [01]: error: .*not a text trace" "$tmp/out"; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL binary as text: exit $rc"; head -20 "$tmp/out"; fi

# The scaling script end to end on a small trace: constants and a projection come out.
root=$(cd "$(dirname "$0")/../.." && pwd)
if MESHREUSE_MPI_BIN=$mpi bash "$root/scripts/scale_mpi.sh" --accesses 50000 --ids 2000 --max-np 2 \
    --repeat 1 --out "$tmp/scale" >"$tmp/out" 2>&1 &&
   grep -q '| 1024 |' "$tmp/scale/projection.md" &&
   /usr/bin/python3 -c "import json,sys; c=json.load(open(sys.argv[1])); assert c['t_a_ns'] > 0 and c['t_f_ns'] > 0" "$tmp/scale/constants.json"; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL scale_mpi.sh"; tail -20 "$tmp/out"; fi

echo "mpi_analyze: $pass passed, $fail failed"
((fail == 0))
