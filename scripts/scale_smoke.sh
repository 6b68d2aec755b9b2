#!/usr/bin/env bash
# The scale smoke test (issue 12), run by scripts/test.sh: a mesh of --vertices N (default 10^6) is
# generated (ocean), read (mesh info), reordered and written (bfs, rdr), smoothed for 3 sweeps and
# analysed for one in each order, written as .vtu and .vtk (the .vtu at most a third of the .vtk),
# and compared (ori, bfs, rdr); every command must succeed and its
# peak resident memory (GNU time's %M) must stay within the memory budget, in bytes per vertex:
#   mesh info 160, reorder 300, smooth 160, analyze 220, mesh convert 160, compare 300
# (the README's "Memory budget"). The process's own baseline (a command that reads no mesh) is
# subtracted first, so the figure is per vertex of the mesh; both are printed. Not a timing test:
# times are printed for information only. --mesh PREFIX uses an existing PREFIX.node/.ele instead
# of generating one (the README's 10^7 and 3*10^7 rows).
# Usage: scripts/scale_smoke.sh [--vertices N | --mesh PREFIX] [--keep DIR] [MESHREUSE]
set -euo pipefail
cd "$(dirname "$0")/.."

vertices=1000000 keep= bin=build/release/cli/meshreuse given=
source scripts/lib.sh
usage() { lib_usage 2 11; }
LIB_USAGE=usage
lib_options --vertices=vertices --keep=keep --mesh=given @=bin -- "$@"
[[ $vertices =~ ^[0-9]+$ ]] || { echo "scale_smoke: --vertices takes a number" >&2; exit 2; }
[[ -x $bin ]] || { echo "scale_smoke: no meshreuse binary at $bin (build first)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "scale_smoke: needs GNU time (/usr/bin/time; scripts/setup.sh)" >&2; exit 2; }

dir=${keep:-$(mktemp -d)}
mkdir -p "$dir"
[[ -n $keep ]] || trap 'rm -rf "$dir"' EXIT
mesh=$dir/ocean
if [[ -n $given ]]; then
  mesh=$given
  [[ -f $mesh.node && -f $mesh.ele ]] || { echo "scale_smoke: no $mesh.node/.ele" >&2; exit 2; }
else
  echo "scale_smoke: generating ocean with about $vertices vertices in $dir" >&2
  "$bin" mesh generate --shape ocean --vertices "$vertices" -o "$mesh" --quiet >/dev/null
fi
nv=$(awk '!/^#/ && NF {print $1; exit}' "$mesh.node")

# Peak RSS in KB of a command, its time in s; stdout to a file.
measure() {  # measure NAME OUT -- command...
  local name=$1 out=$2
  shift 3
  if ! /usr/bin/time -f '%M %e' -o "$dir/time.txt" "$@" >"$out" 2>"$dir/stderr.txt"; then
    echo "scale_smoke: FAILED: $name: $*" >&2
    cat "$dir/stderr.txt" >&2
    exit 1
  fi
  read -r kb secs <"$dir/time.txt"
}

measure baseline /dev/null -- "$bin" orderings
base_kb=$kb
failed=0
printf '%-22s %10s %8s %12s %8s %7s\n' command peak_MB seconds B/vertex budget ok
check() {  # check NAME BUDGET -- command...
  local name=$1 budget=$2
  shift 2
  measure "$name" "$dir/out.txt" "$@"
  local per ok
  per=$(awk -v kb="$kb" -v b="$base_kb" -v n="$nv" 'BEGIN {printf "%.1f", (kb - b) * 1024 / n}')
  ok=$(awk -v p="$per" -v b="$budget" 'BEGIN {print (p <= b) ? "yes" : "NO"}')
  [[ $ok == yes ]] || failed=1
  printf '%-22s %10.1f %8s %12s %8s %7s\n' "$name" "$(awk -v k="$kb" 'BEGIN {print k / 1024}')" \
    "$secs" "$per" "$budget" "$ok"
}

check "mesh info" 160 -- "$bin" mesh info "$mesh.node" --quiet
for ord in bfs rdr; do
  check "reorder $ord" 300 -- "$bin" reorder "$mesh.node" --ordering "$ord" -o "$dir/$ord" --quiet
  check "smooth $ord (3 sweeps)" 160 -- "$bin" smooth "$dir/$ord.node" --max-iters 3 --tol -1 \
    --triangle-order file --quiet
  check "analyze $ord (1 sweep)" 220 -- "$bin" analyze "$dir/$ord.node" --iterations 1 \
    --triangle-order file --quiet
done
# ParaView's format at scale: the compressed .vtu at most a third of the legacy ASCII .vtk
# (issue 39), both written from the same mesh.
check "mesh convert -> .vtu" 160 -- "$bin" mesh convert "$dir/bfs.node" -o "$dir/bfs.vtu" --quiet
check "mesh convert -> .vtk" 160 -- "$bin" mesh convert "$dir/bfs.node" -o "$dir/bfs.vtk" --quiet
vtu_bytes=$(stat -c %s "$dir/bfs.vtu") vtk_bytes=$(stat -c %s "$dir/bfs.vtk")
echo "scale_smoke: .vtu $vtu_bytes bytes, .vtk $vtk_bytes bytes ($(awk -v a="$vtu_bytes" -v b="$vtk_bytes" 'BEGIN {printf "%.3f", a / b}') of it)" >&2
if ((3 * vtu_bytes > vtk_bytes)); then
  echo "scale_smoke: FAILED: the .vtu is more than a third of the .vtk" >&2
  failed=1
fi
rm -f "$dir/bfs.vtu" "$dir/bfs.vtk"
check "compare ori,bfs,rdr" 300 -- "$bin" compare "$mesh.node" --orderings ori,bfs,rdr \
  --max-iters 2 --tol -1 --repeat 3 --quiet
echo "scale_smoke: $nv vertices; baseline $((base_kb / 1024)) MB subtracted" >&2
if ((failed)); then
  echo "scale_smoke: FAILED: a command exceeded its memory budget, or the .vtu its size" >&2
  exit 1
fi
echo "scale_smoke: every command within its memory budget" >&2
