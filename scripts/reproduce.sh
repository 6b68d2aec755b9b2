#!/usr/bin/env bash
# The README's main job: installs what is missing, builds Release, meshes the nine shipped shapes
# with Triangle to the paper's vertex counts (Table 4; cached under out/meshes/), then
#   1. times the smoother under the paper's orderings (`meshreuse compare`): per-mesh table and
#      the paper's averaged Speedup and Gain;
#   2. the paper's Table 2: reuse-distance quantiles and accesses of the first sweep
#      (`meshreuse analyze`), with modelled misses;
#   3. the paper's Table 3 (`meshreuse validate`, 2 sweeps per mesh and ordering): misses per
#      level -- hardware counters where the machine has them, else the set-associative simulator,
#      labelled so -- and the inverse model's capacities, beside the paper's values;
#   4. the paper's reuse-distance profile figure (carabiner, 8 sweeps) and histograms, as PNG+PDF.
# Results: results/reproduce-<UTC time>/ (compare/, table2/, table3/, profile/, each with run.json).
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
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "reproduce.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
say() { [[ -n $quiet ]] || echo "reproduce: $*" >&2; }

bash scripts/setup.sh --with-plots
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
say "1/4 timing the smoother on ${#files[@]} meshes: orderings $orderings, threads $threads, $repeat rounds"
"$bin" compare "${files[@]}" --orderings "$orderings" --threads "$threads" --repeat "$repeat" \
  --out "$out/compare" $quiet >"$out/compare.txt"
say "2/4 Table 2: reuse distances of the first sweep, ${#files[@]} meshes x $orderings"
"$bin" analyze "${files[@]}" --orderings "$orderings" --iterations 1 --granularity element \
  --out "$out/table2" $quiet >"$out/table2.txt"
say "3/4 Table 3: misses per level and the inverse model, ${#files[@]} meshes x $orderings, 2 sweeps"
mkdir -p "$out/table3"
i=0
for f in "${files[@]}"; do
  i=$((i + 1))
  name=$(basename "$f" .node)
  say "  [$i/${#files[@]}] $name"
  "$bin" validate "$f" --orderings "$orderings" --iterations 2 --out "$out/table3/$name" $quiet \
    >"$out/table3/$name.txt"
done
{ head -n 1 "$out/table3/${names[0]}/table3.csv"; for n in "${names[@]}"; do tail -n +2 "$out/table3/$n/table3.csv"; done; } \
  >"$out/table3/table3.csv"
{ head -n 1 "$out/table3/${names[0]}/validate.csv"; for n in "${names[@]}"; do tail -n +2 "$out/table3/$n/validate.csv"; done; } \
  >"$out/table3/validate.csv"
carabiner=""
for f in "${files[@]}"; do [[ $f == */carabiner.node ]] && carabiner=$f; done
if [[ -n $carabiner ]]; then
  say "4/4 reuse-distance profile of carabiner, 8 sweeps x $orderings"
  "$bin" analyze "$carabiner" --orderings "$orderings" --iterations 8 --granularity both \
    --out "$out/profile" $quiet >"$out/profile.txt"
  /usr/bin/python3 scripts/plot_reuse.py profile "$out/profile/profile.csv" "$out/profile/carabiner-profile" >&2
  /usr/bin/python3 scripts/plot_reuse.py histogram "$out/profile/histogram.csv" "$out/profile/carabiner-histogram" >&2
  "$bin" analyze "$carabiner" --orderings "$orderings" --iterations 1 --granularity element \
    --mrc-csv "$out/profile/mrc.csv" $quiet >/dev/null
  # Capacities in elements of 66 B: Westmere-EX's 32 KiB, 256 KiB, 24 MiB.
  /usr/bin/python3 scripts/plot_reuse.py mrc "$out/profile/mrc.csv" "$out/profile/carabiner-mrc" \
    L1=496,L2=3971,L3=381300 >&2
fi

echo
echo "== Laplacian smoothing to convergence (tol 5e-6) under each ordering ($out/compare)"
cat "$out/compare.txt"
echo
echo "== Table 2: reuse distances (distinct vertices) of the first sweep ($out/table2)"
cut -d, -f1,2,5,11-14 "$out/table2/analyze.csv" | sed 's|^[^,]*/||; s|\.node,|,|' | column -s, -t
echo
echo "== Table 3: misses per sweep (x10^3) and inverse-model capacities (x10^3 elements), ours | paper ($out/table3)"
cut -d, -f1-15 "$out/table3/table3.csv" | sed 's|\.node,|,|' | column -s, -t
[[ -n $carabiner ]] && echo && echo "== Profile, histogram and miss-ratio figures: $out/profile/carabiner-{profile,histogram,mrc}.{png,pdf}"
