#!/usr/bin/env bash
# The MPI analysis's scaling constants, measured on this machine, and the model of
# ../shared/scale-out.md section 4 evaluated for a large trace on 64-1024 ranks
# (scripts/project_mpi.py). Runs `meshreuse-mpi analyze` on one trace at -np 1, 2, ... up to
# --max-np (default: the cores here, at least 2), each --repeat times, and records per rank: thread
# CPU seconds analysing (t_a per access, reading included), filtering the streamed stack (t_f per
# id), resolving first touches (t_ft per first touch); wall seconds; peak memory per distinct id;
# bytes sent. Writes OUT/runs.json, OUT/constants.json and OUT/projection.md (markdown table).
#
# Usage: scripts/scale_mpi.sh [--trace FILE --format F] [--accesses N --ids M] [--max-np P]
#          [--repeat R] [--project-accesses N] [--project-ids M] [--alpha S] [--beta B/S]
#          [--out DIR]
#   default trace: N = 20,000,000 accesses uniform over M = 1,048,576 ids (u64, generated)
#   projection defaults: 10^11 accesses over 10^8 ids, alpha 2e-6 s, beta 1e10 bytes/s
set -euo pipefail
caller=$PWD
cd "$(dirname "$0")/.."
trace="" format="" accesses=20000000 ids=1048576 max_np="" repeat=3 out="out/scale_mpi"
pn=100000000000 pm=100000000 alpha=2e-6 beta=1e10
source scripts/lib.sh
usage() { lib_usage 2 16; }
LIB_USAGE=usage
lib_options --trace=trace --format=format --accesses=accesses --ids=ids --max-np=max_np \
  --repeat=repeat --project-accesses=pn --project-ids=pm --alpha=alpha --beta=beta --out=out \
  -- "$@"
[[ $out = /* ]] || out=$caller/$out
[[ -z $trace || $trace = /* ]] || trace=$caller/$trace
for v in "$accesses" "$ids" "$repeat" ${max_np:+"$max_np"}; do
  [[ $v =~ ^[1-9][0-9]{0,11}$ ]] || lib_die "'$v' is not a positive count"
done
mpi=${MESHREUSE_MPI_BIN:-build/release/cli/meshreuse-mpi}
[[ -x $mpi ]] || lib_die "no $mpi: build Release with MPI (scripts/setup.sh installs Open MPI)"
command -v mpirun >/dev/null || lib_die "no mpirun (apt-get install openmpi-bin)"
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)  # nproc obeys OMP_NUM_THREADS
[[ -n $max_np ]] || max_np=$((cores > 2 ? cores : 2))
mkdir -p "$out"
if [[ -z $trace ]]; then
  trace=$out/uniform.u64 format=u64
  if [[ ! -e $trace ]]; then
    echo "scale_mpi.sh: writing $trace ($accesses accesses over $ids ids, seed 1)" >&2
    /usr/bin/python3 - "$trace" "$accesses" "$ids" <<'PY'
import array, random, sys
path, n, m = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
rng = random.Random(1)
with open(path, "wb") as f:
    for at in range(0, n, 1 << 20):
        array.array("Q", (rng.randrange(m) for _ in range(min(1 << 20, n - at)))).tofile(f)
PY
  fi
fi
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
export OMPI_MCA_mpi_yield_when_idle=1
fmt=(); [[ -n $format ]] && fmt=(--format "$format" --granularity element)
runs=()
for ((np = 1; np <= max_np; np *= 2)); do
  for ((k = 1; k <= repeat; k++)); do
    f=$out/np$np-$k.json
    echo "scale_mpi.sh: -np $np, run $k of $repeat" >&2
    t0=$(date +%s%N)
    mpirun --oversubscribe -np "$np" "$mpi" analyze "$trace" "${fmt[@]}" --quiet --rank-stats "$f" >/dev/null
    t1=$(date +%s%N)
    ms=$(((t1 - t0) / 1000000))
    runs+=("$np:$((ms / 1000)).$(printf %03d $((ms % 1000))):$f")
  done
done
/usr/bin/python3 scripts/project_mpi.py --out "$out" --cores "$cores" --project-accesses "$pn" \
  --project-ids "$pm" --alpha "$alpha" --beta "$beta" "${runs[@]}"
echo "scale_mpi.sh: wrote $out/runs.json, $out/constants.json, $out/projection.md" >&2
