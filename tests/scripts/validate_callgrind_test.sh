#!/usr/bin/env bash
# scripts/validate_callgrind.sh on a 20,000-vertex mesh (Triangle): the address trace's count per
# sweep within 1% of callgrind's data references for the sweep function, and the simulator's D1
# and LL misses within 3% of callgrind's, for ori and rdr with LL = L2 and LL = L3. Release builds
# only (sanitizers add loads of their own). Exit 77 (skipped) without valgrind.
# Usage: validate_callgrind_test.sh MESHREUSE
set -euo pipefail
bin=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
command -v valgrind >/dev/null || { echo "valgrind not found: skipped"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" mesh generate --shape valve --vertices 20000 -o "$tmp/valve" --quiet >/dev/null
MESHREUSE=$bin OUT=$tmp/v.csv bash "$root/scripts/validate_callgrind.sh" "$tmp/valve.node" ori rdr
/usr/bin/python3 - "$tmp/v.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 4, rows
bad = []
for r in rows:
    for col, limit in (("refs_diff_%", 1.0), ("d1_diff_%", 3.0), ("ll_diff_%", 3.0)):
        if abs(float(r[col])) > limit:
            bad.append(f"{r['ordering']} LL={r['ll']}: {col} {r[col]} beyond {limit}%")
print("\n".join(bad) or "validate_callgrind: all within bounds")
sys.exit(1 if bad else 0)
PY
