#!/usr/bin/env bash
# Option values and output paths, fuzzed: seeded random commands on the tiny mesh, each with one
# to three options set to hostile values (negative, zero, huge, 1e400, nan, empty, lists with
# holes, junk) and outputs pointed at hostile paths (empty, too long, a folder, a missing folder,
# a FIFO, a symbolic link to the input, a link loop, two outputs on one path). Every run must end with exit 0, 2 or 3 (never
# 1, a bug, nor a signal), within 60 s, in bounded memory, with one error line for exit 2, and
# never change the input. Usage: fuzz_options.sh MESHREUSE DATA [CASES] [SEED]
# (scripts/fuzz.sh runs it for as long as the harnesses; ctest runs 300 cases, seed 1).
set -u
bin=$(realpath "$1") data=$(realpath "$2") cases=${3:-300} seed=${4:-1}  # absolute: cases run elsewhere
RANDOM=$seed
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$data/two_interior.node" "$data/two_interior.ele" "$tmp/"
mesh=$tmp/two_interior.node
before=$(cat "$tmp/two_interior.node" "$tmp/two_interior.ele" | md5sum)
timer=""
if [[ -x /usr/bin/time ]] && ! ldd "$bin" 2>/dev/null | grep -q libasan; then
  timer="/usr/bin/time -f %M -o $tmp/rss"
fi
mkfifo "$tmp/fifo"
ln -s two_interior.node "$tmp/link_to_input.node"
ln -s loop_b "$tmp/loop_a" && ln -s loop_a "$tmp/loop_b"
mkdir "$tmp/dir" "$tmp/cwd"

values=(-1 0 1 2 3 7 65536 65537 100001 1e400 -1e400 nan inf -inf 1.5 0x10 " 7" "7 " ""
  18446744073709551616 9223372036854775807 -9223372036854775808 x auto auto:0 auto:2 auto:x
  "1,,2" "," "1,2" "0,1" "256" "257" "1024" "é" "$(printf '9%.0s' {1..400})")
# Sweep and round counts: hostile to the parser, not long valid runs (100,000 sweeps on 256
# oversubscribed threads are legitimate work, and slow).
counts=(-1 0 1 2 3 7 1e400 nan inf -inf 1.5 0x10 " 7" "" 18446744073709551616 x auto auto:0 auto:x
  "1,2" "é" "$(printf '9%.0s' {1..400})")
caches=(westmere-ex "L1=1K/2" "L1=0/1" "L1=64G/1" "L1=999999999999G/8" "L1=1K/3" "I1=1K/2" "L1=1K/2,I1=1K/2,I1=2K/2"
  "L1=1K/2/fifo" "L1=1K/2/lru@4,mem@100" "=" "L1=" "L1=1K/2,,L2=4K/4" "L1=-1K/2")
orderings=(ori bfs rdr random hilbert morton rcm nd "metis:1" "metis:0" "metis:-1" "metis:x" "file:$tmp/missing.perm"
  "file:$tmp/dir" "file:/dev/null" "x=ori" "=ori" "ori,ori" "frob" "rdr-wave")
paths=("$tmp/out.x" "" "$tmp/dir" "$tmp/none/x" "$tmp/$(printf 'n%.0s' {1..300})" "$tmp/fifo"
  "$tmp/link_to_input.node" "$tmp/loop_a" "$tmp/sub.out")

pick() { local -n a=$1; printf '%s' "${a[RANDOM % ${#a[@]}]}"; }

fail=0
for ((i = 0; i < cases; i++)); do
  case $((RANDOM % 13)) in
    0) cmd=(analyze "$mesh" -k "$(pick values)" -t "$(pick values)" --line-bytes "$(pick values)") ;;
    1) cmd=(analyze "$mesh" --quantiles "$(pick values)" --sample-rate "$(pick values)" --seed "$(pick values)" --orderings "$(pick orderings)") ;;
    2) cmd=(simulate "$mesh" --cache "$(pick caches)" -k "$(pick values)" --orderings "$(pick orderings)") ;;
    3) cmd=(smooth "$mesh" --max-iters "$(pick counts)" --tol "$(pick values)" --threads "$(pick values)" -o "$(pick paths)") ;;
    4) cmd=(compare "$mesh" --repeat "$(pick counts)" --threads "$(pick values)" --max-iters "$(pick counts)" --orderings "$(pick orderings)") ;;
    5) cmd=(trace "$mesh" -k "$(pick values)" -t "$(pick values)" -o "$(pick paths)") ;;
    6) cmd=(reorder "$mesh" --ordering "$(pick orderings)" -o "$(pick paths)") ;;
    7) cmd=(analyze "$mesh" --element-bytes "$(pick values)" --cache "$(pick caches)" --out "$(pick paths)") ;;
    8) cmd=(mesh convert "$mesh" -o "$(pick paths)") ;;
    9) cmd=(compress "$mesh" --level "$(pick counts)" --frame-kib "$(pick counts)" -o "$(pick paths)") ;;
    # Unsigned options given negative and huge values, and two outputs on one path (issue 38).
    10) cmd=(mesh refine "$mesh" --seed "$(pick values)" --levels "$(pick counts)" -o "$(pick paths)") ;;
    11) cmd=(mesh partition "$mesh" --parts "$(pick values)" --seed "$(pick values)" -o "$(pick paths)" --split "$(pick paths)") ;;
    12) o=$(pick paths)
        case $((RANDOM % 3)) in
          0) cmd=(smooth-ranks "$mesh" --ranks "$(pick values)" -o "$o" --pi-out "$o") ;;
          1) cmd=(analyze "$mesh" --histogram-csv "$o" --mrc-csv "$(pick paths)" --profile-csv "$o") ;;
          2) cmd=(smooth "$mesh" --max-iters 2 -o "$o" --out "$(pick paths)") ;;
        esac ;;
  esac
  # A FIFO output needs a reader, or the writer waits for one.
  (timeout 70 cat "$tmp/fifo" >/dev/null 2>&1 &)
  rm -rf "$tmp/out.x" "$tmp/sub.out" "$tmp/out.x".* "$tmp/sub.out".*
  (cd "$tmp/cwd" && timeout 60 $timer "$bin" "${cmd[@]}" --quiet >"$tmp/stdout" 2>"$tmp/stderr")
  rc=$?
  # Unblock a reader left waiting on the FIFO.
  (exec 3<>"$tmp/fifo") 2>/dev/null
  what="meshreuse ${cmd[*]}"
  if [[ $rc != 0 && $rc != 2 && $rc != 3 ]]; then
    echo "FAIL exit $rc: $what"; sed 's/^/    /' "$tmp/stderr" | head -5; fail=$((fail + 1)); continue
  fi
  if [[ $rc == 2 && $(grep -c . "$tmp/stderr") -lt 1 ]]; then
    echo "FAIL exit 2 without a message: $what"; fail=$((fail + 1))
  fi
  if [[ $rc == 2 ]] && (($(grep -vc '^meshreuse: \(warning\|note\):' "$tmp/stderr") > 1)); then
    echo "FAIL more than one error line: $what"; sed 's/^/    /' "$tmp/stderr" | head -5; fail=$((fail + 1))
  fi
  if [[ -n $timer && -s $tmp/rss ]] && (($(tail -n 1 "$tmp/rss") > 204800)); then
    echo "FAIL $(tail -n 1 "$tmp/rss") KB (bound 200 MB): $what"; fail=$((fail + 1))
  fi
  if [[ $(cat "$tmp/two_interior.node" "$tmp/two_interior.ele" | md5sum) != "$before" ]]; then
    echo "FAIL the input changed: $what"; fail=$((fail + 1))
    cp "$data/two_interior.node" "$data/two_interior.ele" "$tmp/"
  fi
  # Nothing lands where the command ran unless asked (an empty prefix once wrote ".node" there).
  if [[ -n $(ls -A "$tmp/cwd") ]]; then
    echo "FAIL wrote into its working folder ($(ls -A "$tmp/cwd" | tr '\n' ' ')): $what"
    fail=$((fail + 1)); rm -rf "$tmp/cwd" && mkdir "$tmp/cwd"
  fi
  if ls "$tmp" | grep -q '\.tmp\.'; then
    echo "FAIL a temporary was left: $what"; fail=$((fail + 1)); rm -f "$tmp"/*.tmp.*
  fi
done
echo "option fuzz: $cases cases (seed $seed), $fail failed"
[[ $fail -eq 0 ]]
