#!/usr/bin/env bash
# scripts/scale_threads.sh end to end on small traces (50,000 accesses over 2,000 ids, no mesh
# trace): every trace gets its rows (the script itself fails if a threaded table differs from the
# serial one), its parts are the trace cut where the chunks begin, the table and the model come
# out with finite numbers for 2..64 threads, and bad options exit 2.
# Usage: scale_threads_test.sh MESHREUSE
set -u
bin=$1
here=$(cd "$(dirname "$0")/../.." && pwd)
source "$here/tests/cli/lib.sh"  # pass, fail, scratch
scratch
/usr/bin/python3 -c 'import numpy' 2>/dev/null || { echo "skipped: no numpy for /usr/bin/python3"; exit 77; }
MESHREUSE_BIN=$bin "$here/scripts/scale_threads.sh" --accesses 50000 --ids 2000 --no-mesh --repeat 1 \
  --threads 2,3 --out "$tmp/out" >"$tmp/log" 2>&1 || { echo "FAIL scale_threads.sh exited $?"; cat "$tmp/log"; exit 1; }
for f in threads.csv threads.md model/projection.md model/constants.json; do
  [[ -s $tmp/out/$f ]] || { echo "FAIL no $f"; fail=1; }
done
for t in uniform.u64 scan.u64 scan_heap.u64 random64.u64 uniform.txt uniform.u64.zst; do
  for th in 2 3; do
    grep -q "^$t,$th,1," "$tmp/out/threads.csv" || { echo "FAIL no row for $t at $th threads"; fail=1; }
    grep -q "^| $t | $th |" "$tmp/out/threads.md" || { echo "FAIL no table row for $t at $th threads"; fail=1; }
  done
done
# The parts analysed at once: each trace's T parts are the trace, cut where T chunks begin (records
# of 8 bytes; text at line starts), and every row but the compressed trace's has their time and
# ratio.
/usr/bin/python3 - "$tmp/out" <<'PY' || { echo "FAIL parts"; fail=1; }
import csv, sys
out = sys.argv[1]
for name in ["uniform.u64", "scan.u64", "scan_heap.u64", "random64.u64", "uniform.txt"]:
    data = open(f"{out}/{name}", "rb").read()
    for t in (2, 3):
        p = [open(f"{out}/parts/{name}.{t}.{r}", "rb").read() for r in range(t)]
        assert b"".join(p) == data, (name, t)
        if name.endswith(".txt"):
            assert all(x.endswith(b"\n") for x in p[:-1]), name
            assert all(abs(len(x) - len(data) / t) < 16 for x in p), (name, [len(x) for x in p])
        else:
            assert [len(x) // 8 for x in p] == [len(data) // 8 * (r + 1) // t - len(data) // 8 * r // t for r in range(t)]
for r in csv.DictReader(open(f"{out}/threads.csv")):
    if r["trace"].endswith(".zst"):  # no parts: compressed
        assert r["parts_wall_s"] == "" and float(r["speedup"]) > 0, r
        continue
    assert float(r["parts_wall_s"]) > 0 and float(r["parts_speedup"]) > 0, r
PY
rows=$(sed -n '/^Model for/,$p' "$tmp/out/model/projection.md" | grep -cE '^\| (2|4|8|16|32|64) \|')
[[ $rows -eq 6 ]] || { echo "FAIL projection rows: $rows"; fail=1; }
grep -qiE 'nan|inf' "$tmp/out/model/projection.md" && { echo "FAIL a number is not finite"; fail=1; }
/usr/bin/python3 -c "import json,sys; c=json.load(open(sys.argv[1])); assert c['t_a_ns'] > 0 and c['t_r_ns'] > 0 and c['pairs_per_rank'] > 0, c" \
  "$tmp/out/model/constants.json" || { echo "FAIL constants"; fail=1; }
for bad in "--threads two" "--repeat 0" "--bogus"; do
  MESHREUSE_BIN=$bin "$here/scripts/scale_threads.sh" $bad --out "$tmp/bad" >"$tmp/log" 2>&1
  rc=$?
  [[ $rc -eq 2 ]] || { echo "FAIL '$bad' exited $rc, expected 2"; fail=1; }
done
((fail == 0)) && echo "scale_threads_test: passed"
((fail == 0))
