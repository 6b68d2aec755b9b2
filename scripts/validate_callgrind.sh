#!/usr/bin/env bash
# Checks meshreuse's address trace, simulator and model against valgrind's callgrind cache
# simulator, a tool nobody here wrote. For each ordering it runs the sweeps under callgrind with the
# cache simulator collecting in the sweep function only (its mangled name, --demangle=no), once with
# LL = our L2 and once with LL = our L3 (all of --I1/--D1/--LL given: auto-detection would read the
# host's own caches), each from cold caches (smooth --flush-caches streams 64 MiB through them after
# the setup, as the simulator starts empty). Beside callgrind's data references, D1 and LL misses it
# prints `meshreuse simulate` (same two-level configuration) and the fully associative line model.
# Usage: scripts/validate_callgrind.sh MESH [ORDERING...]     (default orderings: ori bfs rdr)
# Environment: ITERATIONS (2), TRIANGLE_ORDER (sorted), MESHREUSE (build/release/cli/meshreuse),
#              OUT (a CSV file to write as well).
# Exit 77 when valgrind is missing (a test runner's "skipped"), 2 on bad arguments.
set -euo pipefail
cd "$(dirname "$0")/.."

if (($# < 1)); then
  echo "usage: scripts/validate_callgrind.sh MESH [ORDERING...]" >&2
  exit 2
fi
mesh=$1
shift
orderings=("$@")
((${#orderings[@]})) || orderings=(ori bfs rdr)
k=${ITERATIONS:-2}
tri=${TRIANGLE_ORDER:-sorted}
bin=${MESHREUSE:-build/release/cli/meshreuse}
if ! command -v valgrind >/dev/null; then
  echo "validate_callgrind: valgrind not found: skipped" >&2
  exit 77
fi
[[ -x $bin ]] || { echo "validate_callgrind: $bin not built (scripts/test.sh --quick)" >&2; exit 2; }
[[ -e $mesh || -e $mesh.node ]] || { echo "validate_callgrind: $mesh: no such mesh" >&2; exit 2; }

# The sweep: the OpenMP body of ForStatic<..., NullSink, GaussSeidelSweep lambda>.
fn=$(nm "$bin" | awk '$3 ~ /ForStatic.*NullSink.*GaussSeidelSweep.*_omp_fn/ && !f {print $3; f = 1}')
[[ -n $fn ]] || { echo "validate_callgrind: sweep function not found in $bin" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# name  callgrind --LL  our level spec
configs=("L2 262144,8,64 L2=256K/8" "L3 25165824,24,64 L3=24M/24")
csv="ordering,ll,refs_callgrind,refs_meshreuse,refs_diff_%,d1_callgrind,d1_simulated,d1_diff_%,d1_model,ll_callgrind,ll_simulated,ll_diff_%,ll_model"
printf '%-8s %-3s %12s %12s %8s %10s %10s %8s %10s %10s %10s %8s %10s\n' ordering LL \
  refs_cg refs_ours diff% D1_cg D1_sim diff% D1_model LL_cg LL_sim diff% LL_model
for ord in "${orderings[@]}"; do
  for cfg in "${configs[@]}"; do
    read -r name ll spec <<<"$cfg"
    out=$tmp/$ord.$name.out
    echo "validate_callgrind: $ord, LL=$name: callgrind ($k sweeps)..." >&2
    valgrind --tool=callgrind --cache-sim=yes --I1=32768,8,64 --D1=32768,8,64 --LL="$ll" \
      --collect-atstart=no --toggle-collect="$fn" --demangle=no --callgrind-out-file="$out" \
      "$bin" smooth "$mesh" --ordering "$ord" --triangle-order "$tri" --max-iters "$k" --tol -1 \
      --flush-caches --quiet >"$tmp/log" 2>&1 || { cat "$tmp/log" >&2; exit 1; }
    # events: Ir Dr Dw I1mr D1mr D1mw ILmr DLmr DLmw
    read -r refs_cg d1_cg ll_cg < <(awk '/^events:/ {for (i = 2; i <= NF; i++) col[$i] = i}
      /^(totals|summary):/ {print $col["Dr"] + $col["Dw"], $col["D1mr"] + $col["D1mw"], $col["DLmr"] + $col["DLmw"]; exit}' "$out")
    sim=$("$bin" simulate "$mesh" --orderings "$ord" --triangle-order "$tri" --iterations "$k" \
      --cache "L1=32K/8,$spec" --csv --quiet)
    # columns: input,ordering,thread,sweep,level,size,ways,sets,accesses,hits,misses,...
    col() {  # col LEVEL COLUMN: the simulator's CSV cell by header name, sweep "all"
      awk -F, -v l="$1" -v c="$2" 'NR == 1 {for (i = 1; i <= NF; i++) h[$i] = i; next}
        $h["level"] == l && $h["sweep"] == "all" {print $h[c]}' <<<"$sim"
    }
    refs_ours=$(col L1 accesses)
    d1_sim=$(col L1 misses)
    ll_sim=$(col "$name" misses)
    model=$("$bin" analyze "$mesh" --orderings "$ord" --triangle-order "$tri" --iterations "$k" \
      --granularity line --cache "L1=32K,${spec%/*}" --csv --quiet)
    d1_model=$(awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) col[$i] = i} NR == 2 {print $col["L1_misses"]}' <<<"$model")
    ll_model=$(awk -F, -v n="${name}_misses" 'NR == 1 {for (i = 1; i <= NF; i++) col[$i] = i} NR == 2 {print $col[n]}' <<<"$model")
    pct() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%+.3f", b ? 100 * (a - b) / b : 0}'; }
    row=("$ord" "$name" "$refs_cg" "$refs_ours" "$(pct "$refs_ours" "$refs_cg")" "$d1_cg" "$d1_sim"
         "$(pct "$d1_sim" "$d1_cg")" "$d1_model" "$ll_cg" "$ll_sim" "$(pct "$ll_sim" "$ll_cg")" "$ll_model")
    printf '%-8s %-3s %12s %12s %8s %10s %10s %8s %10s %10s %10s %8s %10s\n' "${row[@]}"
    csv+=$'\n'$(IFS=,; echo "${row[*]}")
  done
done
echo "(callgrind: D1 32 KiB 8-way + LL as named, 64 B lines, $k sweep(s) from cold caches, sweep function only; diff% = (meshreuse - callgrind) / callgrind; model = fully associative LRU on the same line stream)"
if [[ -n ${OUT:-} ]]; then
  printf '%s\n' "$csv" >"$OUT.tmp.$$" && mv "$OUT.tmp.$$" "$OUT"
  echo "validate_callgrind: wrote $OUT" >&2
fi
