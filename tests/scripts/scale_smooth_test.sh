#!/usr/bin/env bash
# scripts/scale_smooth.sh end to end on a small mesh (plate41 refined twice, ranks as threads): it
# writes its four outputs, the strong table has a row per rank count, the weak one its 1-rank row,
# the projection a row for each of 64..1024 ranks with every number finite, with --mesh-file the
# ranks read their ranges and the memory per rank shrinks with P, and bad options exit 2.
# Usage: scale_smooth_test.sh MESHREUSE
set -u
bin=$1
here=$(cd "$(dirname "$0")/../.." && pwd)
source "$here/tests/cli/lib.sh"  # pass, fail, scratch
scratch
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
# --mesh-file: the ranks read their ranges of the mesh file; the memory column is then per rank
# (the projection's figure shrinks with P).
MESHREUSE_BIN=$bin OMP_NUM_THREADS=1 "$here/scripts/scale_smooth.sh" --levels 2 --max-ranks 2 --repeat 1 \
  --sweeps 3 --mesh-file --out "$tmp/mf" >"$tmp/log" 2>&1 || { echo "FAIL --mesh-file exited $?"; cat "$tmp/log"; exit 1; }
[[ -s $tmp/mf/plate41-L2.mrm ]] || { echo "FAIL no mesh file"; fail=1; }
grep -q '^| 2 | 15,044 | 7,522 |' "$tmp/mf/scaling.md" || { echo "FAIL --mesh-file strong 2-rank row"; fail=1; }
grep -q 'each rank reads its range' "$tmp/mf/projection.md" || { echo "FAIL --mesh-file projection"; fail=1; }
/usr/bin/python3 - "$tmp/mf/projection.md" <<'PY' || { echo "FAIL memory per rank does not shrink with P"; fail=1; }
import re, sys
gb = [float(m.group(1)) for m in re.finditer(r"\| ([0-9.]+) GB \|", open(sys.argv[1]).read())]
sys.exit(0 if len(gb) == 5 and all(a > b for a, b in zip(gb, gb[1:])) else 1)
PY
MESHREUSE_BIN=$bin "$here/scripts/scale_smooth.sh" --bogus >/dev/null 2>&1
[[ $? -eq 2 ]] || { echo "FAIL a bad option does not exit 2"; fail=1; }
MESHREUSE_BIN=$bin "$here/scripts/scale_smooth.sh" --transport pigeon >/dev/null 2>&1
[[ $? -eq 2 ]] || { echo "FAIL a bad transport does not exit 2"; fail=1; }
((fail == 0)) && echo "scale_smooth_test: passed"
exit $fail
