#!/usr/bin/env bash
# Every broken input in tests/data/broken/EXPECTED, through the CLI: exit code 2, one error line on
# stderr naming FILE:LINE and the problem, nothing on stdout. Usage: broken_inputs.sh MESHREUSE DATA
set -u
bin=$1 data=$2
fail=0 n=0
while IFS=$'\t' read -r file line msg; do
  [[ -z $file || $file == \#* ]] && continue
  path="$data/broken/$file"
  where="$path:$line: "
  [[ $line == 0 ]] && where="$path: "
  for cmd in "mesh info" "smooth"; do
    n=$((n + 1))
    out=$("$bin" $cmd "$path" --quiet 2>/tmp/meshreuse-cli-err.$$)
    rc=$?
    err=$(cat /tmp/meshreuse-cli-err.$$)
    if [[ $rc -ne 2 ]]; then echo "FAIL $cmd $file: exit $rc, expected 2 ($err)"; fail=$((fail + 1)); continue; fi
    if [[ $err != "meshreuse: error: $where"*"$msg"* ]]; then
      echo "FAIL $cmd $file: stderr was: $err"; echo "     expected: meshreuse: error: $where...$msg..."; fail=$((fail + 1)); continue
    fi
    if [[ $(printf '%s\n' "$err" | wc -l) -ne 1 ]]; then echo "FAIL $cmd $file: more than one stderr line: $err"; fail=$((fail + 1)); fi
    if [[ $cmd == "mesh info" && -n $out ]]; then echo "FAIL $cmd $file: wrote to stdout: $out"; fail=$((fail + 1)); fi
  done
done < "$data/broken/EXPECTED"
rm -f /tmp/meshreuse-cli-err.$$
echo "broken inputs: $((n - fail)) passed, $fail failed"
[[ $fail -eq 0 ]]
