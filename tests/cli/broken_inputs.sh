#!/usr/bin/env bash
# Every broken input in tests/data/broken/EXPECTED, through the CLI: exit code 2, one error line on
# stderr naming FILE:LINE and the problem, nothing on stdout. Usage: broken_inputs.sh MESHREUSE DATA
set -u
bin=$1 data=$2
fail=0 n=0
# Peak memory of every run, bounded by 100 MB (not under AddressSanitizer, whose shadow memory
# alone is more); /usr/bin/time comes from Debian's `time` package (scripts/setup.sh).
rssfile=$(mktemp)
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
    trace) cmds=("analyze %s" "simulate %s") ;;
    text|u32|u64|lackey|oracle|parda) cmds=("analyze %s --format $kind" "simulate %s --format $kind") ;;
    perm) cmds=("smooth $data/two_interior.node --ordering file:%s" "reorder $data/two_interior.node -o /nonexistent/x --ordering file:%s") ;;
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
hostile=(
  "2|$tmp/d.msh: is a directory, not a file|mesh info $tmp/d.msh"
  "2|$tmp/zero.node: is a character device, not a file|mesh info $tmp/zero.node"
  "2|/dev/zero: is a character device, not a file|smooth $data/two_interior.node --ordering file:/dev/zero"
  "2|/dev/zero: is a character device, not a file|analyze /dev/zero --format text"
  "2|$data/broken: is a directory, not a file|analyze $data/broken --format u64"
  "2|$data/broken: is a directory, not a file|analyze $data/broken --format text"
  "2|$data/broken: is a directory, not a file|simulate $data/broken --format u32"
  "0||analyze $tmp/sweeps_50000.trace --granularity element --profile-csv $tmp/p.csv"
)
for h in "${hostile[@]}"; do
  IFS='|' read -r want msg cmd <<<"$h"
  n=$((n + 1))
  $timer "$bin" $cmd --quiet >/dev/null 2>/tmp/meshreuse-cli-err.$$
  rc=$?
  err=$(cat /tmp/meshreuse-cli-err.$$)
  if [[ $rc -ne $want ]]; then echo "FAIL $cmd: exit $rc, expected $want ($err)"; fail=$((fail + 1)); continue; fi
  if [[ -n $msg && $err != "meshreuse: error: $msg"* ]]; then echo "FAIL $cmd: stderr was: $err"; fail=$((fail + 1)); continue; fi
  if [[ -n $timer ]] && (($(tail -n 1 "$rssfile") > 102400)); then echo "FAIL $cmd: $(tail -n 1 "$rssfile") KB"; fail=$((fail + 1)); fi
done
[[ $(wc -l <"$tmp/p.csv") -eq 101 ]] || { echo "FAIL sparse trace: its profile should have 100 steps"; fail=$((fail + 1)); }
rm -rf "$tmp" "$rssfile"
rm -f /tmp/meshreuse-cli-err.$$
echo "broken inputs: $((n - fail)) passed, $fail failed"
[[ $fail -eq 0 ]]
