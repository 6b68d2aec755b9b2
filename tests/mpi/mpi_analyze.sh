#!/usr/bin/env bash
# meshreuse-mpi (cli/mpi_main.cc) at -np 1, 2, 3, 4 against the serial analyzer: every output
# (table, histogram, profile, miss-ratio curve) byte for byte equal on a meshreuse trace (2 threads,
# 3 sweeps, element and line) and on scan, uniform, hashed 64-bit, u32, oracle, text, lackey and
# 3-access traces (tests/cli/lib.sh; fewer accesses than ranks, sizes not divisible by P), and
# SHARDS at a fixed rate, and the scaling script end to end. A rank killed mid-run ends the job
# non-zero with the rank named, never a hang; bad input exits 2 naming the rank and the problem.
# Usage: mpi_analyze.sh MESHREUSE MESHREUSE_MPI MPIEXEC DATA
set -u
bin=$1 mpi=$2 mpiexec=$3 data=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
export OMPI_MCA_mpi_yield_when_idle=1 OMPI_MCA_rmaps_base_oversubscribe=1
export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0  # Open MPI's own allocations
run() { timeout 120 "$mpiexec" --oversubscribe -np "$@"; }
source "$(dirname "$0")/../cli/lib.sh"

make_traces "$bin" "$data"

outputs "$tmp/serial-mesh" "$bin" analyze "$tmp/mesh.trace"
for np in 1 2 3 4; do
  outputs "$tmp/mpi" run "$np" "$mpi" analyze "$tmp/mesh.trace"
  same "mesh trace -np $np" "$tmp/serial-mesh" "$tmp/mpi"
  for f in "${trace_specs[@]}"; do
    set -- $f
    outputs "$tmp/serial" "$bin" analyze "$tmp/$1" --format "$2" --granularity "$3"
    outputs "$tmp/mpi" run "$np" "$mpi" analyze "$tmp/$1" --format "$2" --granularity "$3"
    same "$1 -np $np" "$tmp/serial" "$tmp/mpi"
  done
done

# SHARDS at a fixed rate: the serial estimate, bit for bit.
for np in 2 3; do
  for extra in "--sample-rate 0.1" "--sample-rate 0.05 --sample-error"; do
    outputs "$tmp/serial" "$bin" analyze "$tmp/mesh.trace" $extra
    outputs "$tmp/mpi" run "$np" "$mpi" analyze "$tmp/mesh.trace" $extra
    same "mesh trace -np $np $extra" "$tmp/serial" "$tmp/mpi"
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
