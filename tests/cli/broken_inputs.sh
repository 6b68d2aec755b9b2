#!/usr/bin/env bash
# Every broken input in tests/data/broken/EXPECTED, through the CLI: exit code 2, one error line on
# stderr naming FILE:LINE and the problem, nothing on stdout. Usage: broken_inputs.sh MESHREUSE DATA
set -u
bin=$1 data=$2
fail=0 n=0
# Peak memory of every run, bounded by 100 MB (not under AddressSanitizer, whose shadow memory
# alone is more); /usr/bin/time comes from Debian's `time` package (scripts/setup.sh).
rssfile=$(mktemp)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$rssfile"' EXIT
timer=""
if [[ -x /usr/bin/time ]] && ! ldd "$bin" 2>/dev/null | grep -q libasan; then
  timer="/usr/bin/time -f %M -o $rssfile"
fi
while IFS=$'\t' read -r file line msg kind; do
  [[ -z $file || $file == \#* ]] && continue
  path="$data/broken/$file"
  where="$path:$line: "
  [[ $line == 0 ]] && where="$path: "
  case ${kind:-mesh} in
    mesh) cmds=("mesh info %s" "smooth %s") ;;
    # --threads 3: a chunk per thread, each reading its part (the same message as one reader)
    trace) cmds=("analyze %s" "analyze %s --threads 3" "simulate %s") ;;
    text|u32|u64|lackey|oracle|parda) cmds=("analyze %s --format $kind" "analyze %s --format $kind --threads 3" "simulate %s --format $kind") ;;
    poly) command -v triangle >/dev/null || continue
      cmds=("mesh generate --poly %s --vertices 1000 -o $tmp/generated") ;;
    summary) cmds=("analyze --merge %s") ;;
    perm) cmds=("smooth $data/two_interior.node --ordering file:%s" "reorder $data/two_interior.node -o $tmp/reordered --ordering file:%s") ;;
    visit) cmds=("smooth $data/two_interior.node --visit-order %s") ;;
  esac
  for tmpl in "${cmds[@]}"; do
    # shellcheck disable=SC2059
    cmd=$(printf "$tmpl" "$path")
    n=$((n + 1))
    out=$($timer "$bin" $cmd --quiet 2>/tmp/meshreuse-cli-err.$$)
    rc=$?
    if [[ -n $timer ]]; then
      rss=$(tail -n 1 "$rssfile")
      if ((rss > 102400)); then echo "FAIL $cmd: $rss KB of memory (bound: 100 MB)"; fail=$((fail + 1)); fi
    fi
    err=$(cat /tmp/meshreuse-cli-err.$$)
    if [[ $rc -ne 2 ]]; then echo "FAIL $cmd $file: exit $rc, expected 2 ($err)"; fail=$((fail + 1)); continue; fi
    if [[ $err != "meshreuse: error: $where"*"$msg"* ]]; then
      echo "FAIL $cmd $file: stderr was: $err"; echo "     expected: meshreuse: error: $where...$msg..."; fail=$((fail + 1)); continue
    fi
    if [[ $(printf '%s\n' "$err" | wc -l) -ne 1 ]]; then echo "FAIL $cmd $file: more than one stderr line: $err"; fail=$((fail + 1)); fi
    if [[ $cmd == "mesh info"* && -n $out ]]; then echo "FAIL $cmd $file: wrote to stdout: $out"; fail=$((fail + 1)); fi
  done
done < "$data/broken/EXPECTED"
# Hostile inputs made here: a directory and /dev/zero where files are expected, a sparse trace
# announcing 50,000 sweeps. Each: exit 2, the file named, bounded memory.
tmp=$(mktemp -d)
mkdir "$tmp/d.msh"
ln -s /dev/zero "$tmp/zero.node"
ln -s /dev/zero "$tmp/zero.ele"
/usr/bin/python3 "$data/broken/make_traces.py" "$tmp" --sparse
/usr/bin/python3 "$data/broken/make_meshes.py" "$tmp" 100000
hostile=(
  "2|$tmp/d.msh: is a directory, not a file|mesh info $tmp/d.msh"
  "2|$tmp/zero.node: is a character device, not a file|mesh info $tmp/zero.node"
  "2|/dev/zero: is a character device, not a file|smooth $data/two_interior.node --ordering file:/dev/zero"
  "2|/dev/zero: is a character device, not a file|analyze /dev/zero --format text"
  "2|$data/broken: is a directory, not a file|analyze $data/broken --format u64"
  "2|$data/broken: is a directory, not a file|analyze $data/broken --format text"
  "2|$data/broken: is a directory, not a file|simulate $data/broken --format u32"
  "0||analyze $tmp/sweeps_50000.trace --granularity element --profile-csv $tmp/p.csv"
  # Gigabytes from kilobytes (issue 20): a header announcing 16,352 x 256 empty (sweep, stream)
  # pairs is refused from its fixed 48 bytes; 256 streams of one record each, with 256 sweeps
  # announced, cost what the records need (per-sweep rows only where a stream has accesses);
  # option products that cannot fit are refused before anything is allocated.
  "2|$tmp/announce_16352x256.trace: the header announces 16352 sweeps x 256 streams: at most 65536|simulate $tmp/announce_16352x256.trace --per-sweep"
  "0||simulate $tmp/streams_256.trace --per-sweep --csv"
  "0||analyze $tmp/below_base.trace"
  "0||analyze $tmp/streams_256.trace --profile-csv $tmp/p256.csv"
  "2|usage: --iterations 2000 x --threads 255 = 510000 (sweep, stream) pairs: at most 65536|analyze $data/two_interior.node -k 2000 -t 255"
  "2|usage: --iterations 2000 x --threads 255 = 510000 (sweep, stream) pairs: at most 65536|simulate $data/two_interior.node -k 2000 -t 255 --per-sweep"
  "2|usage: --iterations must be 1..65536|analyze $data/two_interior.node -k 100000"
  "0||simulate $data/two_interior.node -k 256 -t 255 --per-sweep --csv"
  # Valid meshes that took quadratic time (issue 20): one vertex in 100,000 triangles, and
  # 100,000 Gmsh element blocks of one triangle (binary and ASCII). The time ratios against an
  # ordinary mesh are a benchmark (meshreuse_bench --benchmark_filter=Build), not a test.
  "0||mesh info $tmp/fan_100000.node"
  "0||reorder $tmp/fan_100000.node --ordering rdr -o $tmp/fan_rdr"
  "0||smooth $tmp/fan_100000.node --max-iters 3"
  "0||mesh info $tmp/blocks_100000.msh"
  "0||mesh info $tmp/blocks_ascii_100000.msh"
)
for h in "${hostile[@]}"; do
  IFS='|' read -r want msg cmd <<<"$h"
  n=$((n + 1))
  $timer "$bin" $cmd --quiet >/dev/null 2>/tmp/meshreuse-cli-err.$$
  rc=$?
  err=$(cat /tmp/meshreuse-cli-err.$$)
  if [[ $rc -ne $want ]]; then echo "FAIL $cmd: exit $rc, expected $want ($err)"; fail=$((fail + 1)); continue; fi
  if [[ $msg == usage:* ]]; then  # an option's error: "meshreuse COMMAND: MESSAGE (see --help)"
    if [[ $err != "meshreuse ${cmd%% *}: ${msg#usage: }"* ]]; then echo "FAIL $cmd: stderr was: $err"; fail=$((fail + 1)); continue; fi
  elif [[ -n $msg && $err != "meshreuse: error: $msg"* ]]; then echo "FAIL $cmd: stderr was: $err"; fail=$((fail + 1)); continue; fi
  if [[ -n $timer ]] && (($(tail -n 1 "$rssfile") > 102400)); then echo "FAIL $cmd: $(tail -n 1 "$rssfile") KB"; fail=$((fail + 1)); fi
done
[[ $(wc -l <"$tmp/p.csv") -eq 101 ]] || { echo "FAIL sparse trace: its profile should have 100 steps"; fail=$((fail + 1)); }
# 256 streams, one record each in sweep 1: one profile step each (a sweep of one access).
[[ $(wc -l <"$tmp/p256.csv") -eq 257 ]] || { echo "FAIL streams_256: its profile should have 256 steps, has $(($(wc -l <"$tmp/p256.csv") - 1))"; fail=$((fail + 1)); }
rm -rf "$tmp" "$rssfile"
rm -f /tmp/meshreuse-cli-err.$$
echo "broken inputs: $((n - fail)) passed, $fail failed"
[[ $fail -eq 0 ]]
