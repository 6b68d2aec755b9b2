#!/usr/bin/env bash
# The distributed smoother's scaling measured on this machine, and the model of
# ../shared/scale-out.md section 4 evaluated for 10^9 vertices on 64-1024 ranks
# (scripts/project_smooth.py). Strong scaling: one mesh (plate41.msh refined --levels K with jitter
# 0.3, or --mesh FILE) at P = 1, 2, 4, ... up to --max-ranks (default: the cores here); weak
# scaling (--weak, the refined mesh only): P = 1, 4, 16, ... with the mesh refined once more for
# each 4x ranks, so every rank owns about the same number of vertices. Ranks are threads of one
# process (`meshreuse smooth-ranks`, the default; messages through memory) or MPI ranks
# (--transport mpi: `mpirun meshreuse-mpi smooth`). Every run does --sweeps ordered Gauss-Seidel
# sweeps (never stopped early), --repeat times, interleaved with the serial smoother
# (`meshreuse smooth --quality per-sweep`, the same global quality per sweep). Records the
# median wall ms per sweep, each rank's CPU and wait seconds, messages, bytes and peak memory.
# --mesh-file: the mesh converted once to the distributed mesh file (FILE.mrm, Hilbert order), each
# rank reading only its range (--partition ranges) and the serial smoother reading the same file,
# so memory per rank is its part's and the projection's memory column is per rank.
# Writes OUT/runs.json, OUT/constants.json, OUT/scaling.md and OUT/projection.md.
#
# Usage: scripts/scale_smooth.sh [--levels K] [--mesh FILE] [--max-ranks P] [--weak]
#          [--transport threads|mpi] [--sweeps S] [--repeat R] [--ordering NAME] [--mesh-file]
#          [--partition hilbert|metis] [--project-vertices V] [--alpha S] [--beta B/S] [--out DIR]
#   defaults: --levels 5 (946,464 vertices), --sweeps 10, --repeat 3, --ordering ori, hilbert,
#   projection of 10^9 vertices, alpha 2e-6 s, beta 1e10 bytes/s, OUT out/scale_smooth
set -euo pipefail
caller=$PWD
cd "$(dirname "$0")/.."
levels=5 mesh="" max_ranks="" weak=0 transport=threads sweeps=10 repeat=3 ordering=ori
partition=hilbert mesh_file=0 pv=1000000000 alpha=2e-6 beta=1e10 out="out/scale_smooth"
source scripts/lib.sh
usage() { lib_usage 2 20; }
LIB_USAGE=usage
lib_options --levels=levels --mesh=mesh --max-ranks=max_ranks --weak=weak! --mesh-file=mesh_file! \
  --transport=transport --sweeps=sweeps --repeat=repeat --ordering=ordering --partition=partition \
  --project-vertices=pv --alpha=alpha --beta=beta --out=out -- "$@"
[[ $out = /* ]] || out=$caller/$out
[[ -z $mesh || $mesh = /* ]] || mesh=$caller/$mesh
for v in "$levels" "$sweeps" "$repeat" ${max_ranks:+"$max_ranks"}; do
  [[ $v =~ ^[0-9]{1,6}$ ]] || lib_die "'$v' is not a count"
done
((levels <= 8)) || lib_die "--levels $levels: at most 8 (plate41 refined 8 times is 6*10^7 vertices)"
[[ $transport == threads || $transport == mpi ]] || lib_die "--transport must be threads or mpi"
((weak == 0)) || [[ -z $mesh ]] || lib_die "--weak refines plate41 itself: leave out --mesh"
bin=${MESHREUSE_BIN:-build/release/cli/meshreuse}
mpi=${MESHREUSE_MPI_BIN:-build/release/cli/meshreuse-mpi}
[[ -x $bin ]] || lib_die "no $bin: build Release first"
if [[ $transport == mpi ]]; then
  [[ -x $mpi ]] || lib_die "no $mpi: build Release with MPI (scripts/setup.sh installs Open MPI)"
  command -v mpirun >/dev/null || lib_die "no mpirun (apt-get install openmpi-bin)"
  if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
fi
py=/usr/bin/python3
[[ -x $py ]] || py=python3
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)  # nproc obeys OMP_NUM_THREADS
[[ -n $max_ranks ]] || max_ranks=$((cores > 2 ? cores : 2))
mkdir -p "$out"
refined() {  # refined K : plate41 refined K times with jitter, written once
  local f=$out/plate41-L$1
  if [[ ! -e $f.node ]]; then
    echo "scale_smooth.sh: refining plate41 --levels $1" >&2
    "$bin" mesh refine tests/data/plate41.msh --levels "$1" --jitter 0.3 --seed 1 -o "$f" --quiet >/dev/null
  fi
  echo "$f.node"
}
as_file() {  # as_file MESH : MESH itself, or (--mesh-file) its mesh file, written once
  local m=$1 f=$out/$(basename "${1%.*}").mrm
  if ((mesh_file == 0)); then echo "$m"; return; fi
  if [[ ! -e $f ]]; then
    echo "scale_smooth.sh: converting $(basename "$m") to $f" >&2
    "$bin" mesh convert "$m" -o "$f" --quiet >/dev/null
  fi
  echo "$f"
}
((mesh_file == 0)) || partition=ranges
runs=()
one() {  # one KIND MESH P REP : a distributed run (P ranks) and, for P = 1, the serial one
  local kind=$1 m=$2 p=$3 k=$4 d=$out/$1-$(basename "${2%.*}")-p$3-$4
  rm -rf "$d"
  echo "scale_smooth.sh: $kind, $(basename "$m"), $p ranks, run $k of $repeat" >&2
  local common=(--ordering "$ordering" --max-iters "$sweeps" --tol -1 --quiet --out "$d")
  if [[ $transport == mpi ]]; then
    mpirun --oversubscribe -np "$p" "$mpi" smooth "$m" --partition "$partition" "${common[@]}" >/dev/null
  else
    "$bin" smooth-ranks "$m" --ranks "$p" --partition "$partition" "${common[@]}" >/dev/null
  fi
  runs+=("$kind:$p:$d")
  if ((p == 1)); then
    "$bin" smooth "$m" --quality per-sweep "${common[@]/$d/$d-serial}" >/dev/null
    runs+=("$kind-serial:1:$d-serial")
  fi
}
strong_mesh=$(as_file "${mesh:-$(refined "$levels")}")
for ((k = 1; k <= repeat; k++)); do
  for ((p = 1; p <= max_ranks; p *= 2)); do one strong "$strong_mesh" $p $k; done
  if ((weak)); then
    for ((p = 1, l = levels; p <= max_ranks && l <= 8; p *= 4, l++)); do
      one weak "$(as_file "$(refined $l)")" $p $k
    done
  fi
done
"$py" scripts/project_smooth.py --out "$out" --cores "$cores" --transport "$transport" \
  --project-vertices "$pv" --alpha "$alpha" --beta "$beta" --sweeps "$sweeps" "${runs[@]}"
echo "scale_smooth.sh: wrote $out/runs.json, $out/constants.json, $out/scaling.md, $out/projection.md" >&2
