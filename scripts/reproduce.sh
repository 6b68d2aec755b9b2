#!/usr/bin/env bash
# The README's main job: installs what is missing, builds Release, meshes the nine shipped shapes
# with Triangle to the paper's vertex counts (Table 4), smooths each in ORI order (Triangle's own
# numbering) and prints the table. Meshes are cached under out/meshes/; results go to
# results/reproduce-<UTC time>/ (summary.csv, summary.md, sweeps.csv, run.json).
# Usage: scripts/reproduce.sh [--vertices N] [--threads P] [--shapes a,b,...] [--quiet]
set -euo pipefail
cd "$(dirname "$0")/.."

vertices="" threads=1 quiet="" shapes="carabiner,crake,dialog,lake,riverflow,ocean,stress,valve,wrench"
while (($#)); do
  case $1 in
    --vertices) vertices=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --shapes) shapes=$2; shift 2 ;;
    --quiet) quiet=--quiet; shift ;;
    -h|--help) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
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
say "smoothing ${#files[@]} meshes in ORI order with $threads thread(s); results in $out"
"$bin" smooth "${files[@]}" --threads "$threads" --out "$out" $quiet >"$out.log" || { cat "$out.log"; exit 1; }
mv "$out.log" "$out/smooth.log"
echo
echo "Laplacian smoothing in ORI order ($threads thread(s)); per-sweep log: $out/smooth.log"
column -s, -t <"$out/summary.csv" 2>/dev/null || cat "$out/summary.csv"
