#!/usr/bin/env bash
# scripts/scale_smooth.sh end to end on a small mesh (plate41 refined twice, ranks as threads): it
# writes its four outputs, the strong table has a row per rank count, the weak one its 1-rank row,
# the projection a row for each of 64..1024 ranks with every number finite, and bad options exit 2.
# Usage: scale_smooth_test.sh MESHREUSE
set -u
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
here=$(cd "$(dirname "$0")/../.." && pwd)
fail=0
MESHREUSE_BIN=$bin OMP_NUM_THREADS=1 "$here/scripts/scale_smooth.sh" --levels 2 --max-ranks 2 --repeat 1 \
  --sweeps 3 --weak --out "$tmp/out" >"$tmp/log" 2>&1 || { echo "FAIL scale_smooth.sh exited $?"; cat "$tmp/log"; exit 1; }
for f in runs.json constants.json scaling.md projection.md; do
  [[ -s $tmp/out/$f ]] || { echo "FAIL no $f"; fail=1; }
done
grep -q '^| 1 | 15,044 | 15,044 |' "$tmp/out/scaling.md" || { echo "FAIL strong 1-rank row"; fail=1; }
grep -q '^| 2 | 15,044 | 7,522 |' "$tmp/out/scaling.md" || { echo "FAIL strong 2-rank row"; fail=1; }
grep -q '^\*\*weak\*\*' "$tmp/out/scaling.md" || { echo "FAIL no weak table"; fail=1; }
rows=$(grep -cE '^\| (64|128|256|512|1024) \|' "$tmp/out/projection.md")
[[ $rows -eq 5 ]] || { echo "FAIL projection rows: $rows"; fail=1; }
grep -qiE 'nan|inf' "$tmp/out/projection.md" && { echo "FAIL a number is not finite"; fail=1; }
MESHREUSE_BIN=$bin "$here/scripts/scale_smooth.sh" --bogus >/dev/null 2>&1
[[ $? -eq 2 ]] || { echo "FAIL a bad option does not exit 2"; fail=1; }
MESHREUSE_BIN=$bin "$here/scripts/scale_smooth.sh" --transport pigeon >/dev/null 2>&1
[[ $? -eq 2 ]] || { echo "FAIL a bad transport does not exit 2"; fail=1; }
((fail == 0)) && echo "scale_smooth_test: passed"
exit $fail
