#!/usr/bin/env bash
# The README's main job: every table and figure of the paper, ours beside the paper's, from one
# command. Installs what is missing, builds Release, meshes the nine shipped shapes with Triangle
# to the paper's vertex counts (cached under out/meshes/), runs `meshreuse report` (Table 1, 2, 3,
# misses and their reductions, execution times, speedups, Speedup(p)/Gain(p), reordering cost; on
# 1..nproc threads; and the many-core part: the paper's 4 x 8-core Westmere-EX simulated at 1-32
# threads, compact and scatter, Figure 11 and Speedup(p) predicted), which draws every figure
# (PNG and PDF, scripts/plot_report.py), then prints the results README's path: results/<date>/README.md
# (ours | paper | difference, every figure).
#
# Usage: scripts/reproduce.sh [--quick | --scale] [--orderings ori,bfs,rdr,file:my.perm,...]
#          [--threads 1,2] [--repeat 3|auto] [--vertices N] [--shapes a,b,...] [--kernels LIST]
#          [--out DIR] [--quiet]
#   --quick   the same pipeline on 20,000-vertex meshes, three rounds, the machine simulated at
#             1, 4 and 32 threads (a minute; CI runs it): too small for the paper's columns,
#             which the default run on the paper's sizes fills
#   --scale   one shape (ocean) at 10^4, 10^5, 10^6 and 10^7 vertices, one thread (~15 min): time
#             per vertex per sweep and simulated misses per access against size (figure
#             "scale"); no many-core part
#   --orderings  registered names (meshreuse orderings) or file:PATH (a permutation file, one
#             old vertex id per line in new order; {mesh} in PATH stands for each mesh's name,
#             e.g. file:perms/{mesh}.perm; LABEL=file:PATH names its rows); ori is always run
#             (the speedups need it). Relative paths (here and --out) are from where you run it.
#   --kernels the other-kernels part (the paper's conjecture, reports/docs/kernels.md): which
#             kernels of `meshreuse kernels` race ORI, BFS, RDR, grid-wave, RCM and Hilbert on every
#             mesh; none: no such part. Default: laplacian, smart-laplacian, untangle, edge-swap,
#             assembly and spmv with --quick; smart-laplacian, untangle and edge-swap (the three
#             the paper names) on the paper's sizes, to keep the full run's time; none with
#             --scale.
set -euo pipefail
caller=$PWD
cd "$(dirname "$0")/.."

mode=full vertices="" quiet="" orderings="ori,bfs,rdr" threads="" repeat=3 out="" kernels=""
shapes="carabiner,crake,dialog,lake,riverflow,ocean,stress,valve,wrench"
source scripts/lib.sh
usage() { lib_usage 2 28; }
LIB_USAGE=usage
quick=0 scale=0 q=0
lib_options --quick=quick! --scale=scale! --vertices=vertices --orderings=orderings \
  --threads=threads --repeat=repeat --shapes=shapes --kernels=kernels --out=out --quiet=q! -- "$@"
((q)) && quiet=--quiet
((quick)) && mode=quick
((scale)) && mode=scale
[[ -z $vertices || $vertices =~ ^[0-9]+$ ]] || lib_die "--vertices takes a number, found '$vertices'"
[[ $repeat =~ ^(auto(:[0-9]+)?|[0-9]+)$ ]] || lib_die "--repeat takes a number >= 3 or auto, found '$repeat'"
[[ $repeat == auto* || $repeat -ge 3 ]] || lib_die "--repeat must be at least 3: a median and its interval need rounds"
[[ -z $kernels || $kernels =~ ^[a-z-]+(,[a-z-]+)*$ ]] || lib_die "--kernels takes names like untangle,spmv or none, found '$kernels'"
[[ -z $threads || $threads =~ ^[0-9]+(,[0-9]+)*$ ]] || lib_die "--threads takes numbers like 1,2, found '$threads'"
[[ ,$orderings, == *,ori,* ]] || orderings="ori,$orderings"
# file:PATH and LABEL=file:PATH resolved from the caller's folder; {mesh} in PATH is each mesh's
# name (checked by meshreuse report before any work).
resolved=()
IFS=, read -r -a specs <<<"$orderings"
for o in "${specs[@]}"; do
  label=""
  [[ $o == *=file:* ]] && label=${o%%=file:*}= && o=${o#*=}
  if [[ $o == file:* ]]; then
    p=${o#file:}
    [[ $p == /* ]] || p=$caller/$p
    [[ $p == *'{mesh}'* || -f $p ]] || lib_die "--orderings: ${o#file:}: no such file"
    o=file:$p
  fi
  resolved+=("$label$o")
done
orderings=$(IFS=,; echo "${resolved[*]}")
[[ -z $out || $out == /* ]] || out=$caller/$out
say() { [[ -n $quiet ]] || echo "reproduce [$(date -u +%H:%M:%S)]: $*" >&2; }
start=$(date +%s)

# The output folder, checked before any work.
stamp=$(date -u +%Y-%m-%d)
if [[ -z $out ]]; then
  out=results/$stamp
  [[ $mode != full ]] && out=$out-$mode
  base=$out n=2
  while [[ -e $out ]]; do out=$base-$n; n=$((n + 1)); done
fi
probe=$out
while [[ ! -e $probe && $probe == */* ]]; do probe=${probe%/*}; done
[[ ! -e $probe || -d $probe ]] || lib_die "cannot write to '$out': '$probe' is not a folder"
[[ ! -e $out ]] || [[ -d $out && -z $(ls -A "$out") ]] || lib_die "'$out' exists and is not empty: give a new --out"

# Where the time goes before the report (which adds its own phases): "NAME WALL CPU" lines for
# its --prior-phases, from bash's `time` (wall, and user + system CPU, the children's included).
mkdir -p build
phases=build/reproduce-phases.txt
: >"$phases"
phase() {  # phase NAME COMMAND...: runs it in this shell, its time appended to $phases
  local name=$1 TIMEFORMAT="%R %U %S"
  shift
  { time "$@" 2>&3; } 3>&2 2>"$phases.time" || return
  awk -v n="$name" 'NF == 3 { printf "%s %s %.3f\n", n, $1, $2 + $3 }' "$phases.time" >>"$phases"
}
build_release() {
  say "building Release in build/release"
  # Ninja for a fresh folder, as scripts/test.sh (a first build 110 s instead of make's 120); a
  # folder configured before keeps its generator.
  # A folder configured for Release already is not configured again (a second a run, --quick's
  # budget): its build re-runs CMake itself where a CMakeLists.txt changed.
  local gen=()
  [[ ! -f build/release/CMakeCache.txt ]] && command -v ninja >/dev/null && gen=(-G Ninja)
  if ! grep -qx 'CMAKE_BUILD_TYPE:STRING=Release' build/release/CMakeCache.txt 2>/dev/null; then
    cmake "${gen[@]}" -S . -B build/release -DCMAKE_BUILD_TYPE=Release >build/release.configure.log 2>&1 ||
      { cat build/release.configure.log; exit 1; }
  fi
  # The program alone (not the tests and benchmarks), its progress shown: a first build takes
  # minutes.
  if [[ -n $quiet ]]; then
    cmake --build build/release --target meshreuse -j"$(nproc 2>/dev/null || echo 2)" \
      >build/release.build.log 2>&1 || { tail -n 40 build/release.build.log; exit 1; }
  else
    if ! cmake --build build/release --target meshreuse -j"$(nproc 2>/dev/null || echo 2)" 2>&1 |
        tee build/release.build.log | { grep --line-buffered -E '^\[ *[0-9]+(%|/[0-9]+)\]' >&2 || true; }; then
      tail -n 40 build/release.build.log
      exit 1
    fi
  fi
}
phase setup bash scripts/setup.sh --report-only --with-plots
phase build build_release
bin=build/release/cli/meshreuse
"$bin" orderings --check "$orderings"  # exit 2 with the reason for an unknown one

files=()
# The meshes (cached under out/meshes/), the missing ones made nproc at a time (Triangle is
# serial: on 2 cores the nine paper-size shapes took 11 s one after another); their paths in
# order into files.
mesh_all() {  # mesh_all DIR SHAPE:VERTICES:NAME... (VERTICES empty: the shape's paper size)
  local dir=$1 todo=() item s v name
  shift
  mkdir -p "$dir"
  for item in "$@"; do
    IFS=: read -r s v name <<<"$item"
    files+=("$dir/$name.node")
    [[ -s $dir/$name.node && -s $dir/$name.ele ]] && continue
    say "meshing $s${v:+ at $v vertices} with Triangle -> $dir/$name"
    todo+=("$s" "${v:-paper}" "$dir/$name")
  done
  ((${#todo[@]})) || return 0
  # One failure fails the phase (xargs exits 123), after its error on stderr.
  printf '%s\n' "${todo[@]}" | BIN=$bin Q=$quiet xargs -d '\n' -n 3 -P "$(nproc 2>/dev/null || echo 2)" \
    sh -c 'if [ -n "$Q" ]; then exec >/dev/null; else exec >&2; fi
           if [ "$1" = paper ]; then set -- "$0" "" "$2"; else set -- "$0" "--vertices=$1" "$2"; fi
           exec "$BIN" mesh generate --shape "$1" $2 -o "$3" --quiet'
}

args=(--orderings "$orderings" --repeat "$repeat" --label "$mode")
[[ -n $threads ]] && args+=(--threads "$threads")
make_meshes() {
  local names items=() s v
  IFS=, read -r -a names <<<"$shapes"
  case $mode in
    full)
      args+=(--kernels "${kernels:-smart-laplacian,untangle,edge-swap}")
      for s in "${names[@]}"; do items+=("$s:$vertices:$s"); done
      mesh_all "out/meshes/${vertices:-paper}" "${items[@]}" ;;
    quick)
      for s in "${names[@]}"; do items+=("$s:${vertices:-20000}:$s"); done
      mesh_all "out/meshes/${vertices:-20000}" "${items[@]}"
      [[ -n $kernels ]] && args+=(--kernels "$kernels")
      args+=(--machine-threads 1,4,32) ;;
    scale)
      for v in 10000 100000 1000000 10000000; do items+=("ocean:$v:ocean-$v"); done
      mesh_all out/meshes/scale "${items[@]}"
      [[ -n $threads ]] || args+=(--threads 1)
      args+=(--figure1-mesh none --profile-mesh none --machine none --kernels "${kernels:-none}") ;;
  esac
}
phase meshing make_meshes

say "running meshreuse report on ${#files[@]} meshes ($mode): orderings $orderings -> $out"
# It draws the figures too, and writes where the time went (these phases and its own) into
# README.md and run.json.
"$bin" report "${files[@]}" "${args[@]}" --prior-phases "$phases" --out "$out" $quiet >/dev/null
elapsed=$(($(date +%s) - start))
say "done in $((elapsed / 60)) min $((elapsed % 60)) s"

echo
sed -n '/^## Table 2/,/^Files/p' "$out/README.md" | awk 'NR <= 20'  # not head: its early exit would SIGPIPE sed under pipefail
echo
[[ $mode == quick ]] && echo "(20,000-vertex meshes: too small for the paper's columns, which stay empty; scripts/reproduce.sh without --quick runs the paper's sizes and fills them)"
echo "Every table and figure: $out/README.md"
