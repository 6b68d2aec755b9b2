#!/usr/bin/env bash
# The README's main job: installs what is missing, builds Release, meshes the nine shipped shapes
# with Triangle to the paper's vertex counts (Table 4; cached under out/meshes/), then times the
# smoother under the paper's orderings with `meshreuse compare` and prints the per-mesh table and
# the paper's averaged Speedup and Gain. Results: results/reproduce-<UTC time>/ (compare.*,
# summary.*, run.json, compare.log with the progress).
# Usage: scripts/reproduce.sh [--orderings ori,bfs,rdr] [--threads 1,2] [--repeat 3]
#                             [--vertices N] [--shapes a,b,...] [--quiet]
set -euo pipefail
cd "$(dirname "$0")/.."

vertices="" quiet="" orderings="ori,bfs,rdr" threads="1,2" repeat=3
shapes="carabiner,crake,dialog,lake,riverflow,ocean,stress,valve,wrench"
while (($#)); do
  case $1 in
    --vertices) vertices=$2; shift 2 ;;
    --orderings) orderings=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --shapes) shapes=$2; shift 2 ;;
    --quiet) quiet=--quiet; shift ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "reproduce.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
say() { [[ -n $quiet ]] || echo "reproduce: $*" >&2; }

bash scripts/setup.sh
say "building Release in build/release"
mkdir -p build results
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >build/release.configure.log 2>&1 ||
  { cat build/release.configure.log; exit 1; }
cmake --build build/release -j"$(nproc 2>/dev/null || echo 2)" >/dev/null
bin=build/release/cli/meshreuse

meshdir=out/meshes/${vertices:-paper}
mkdir -p "$meshdir"
IFS=, read -r -a names <<<"$shapes"
files=()
i=0
for s in "${names[@]}"; do
  i=$((i + 1))
  if [[ -s $meshdir/$s.node && -s $meshdir/$s.ele ]]; then
    say "[$i/${#names[@]}] $s: using $meshdir/$s.node"
  else
    say "[$i/${#names[@]}] $s: meshing with Triangle"
    "$bin" mesh generate --shape "$s" ${vertices:+--vertices "$vertices"} -o "$meshdir/$s" $quiet >&2
  fi
  files+=("$meshdir/$s.node")
done

out=results/reproduce-$(date -u +%Y%m%dT%H%M%SZ)
mkdir -p "$out"
say "timing the smoother on ${#files[@]} meshes: orderings $orderings, threads $threads, $repeat rounds; results in $out"
"$bin" compare "${files[@]}" --orderings "$orderings" --threads "$threads" --repeat "$repeat" \
  --out "$out" $quiet >"$out/compare.txt" 2> >(tee "$out/compare.log" >&2)
echo
echo "Laplacian smoothing to convergence (tol 5e-6) under each ordering; results in $out"
cat "$out/compare.txt"
