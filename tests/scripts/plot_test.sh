#!/usr/bin/env bash
# The plotting scripts on the fixture CSVs of tests/data/report (a report of two 1,500-vertex
# meshes, its manifest.json naming what to draw): every figure as a valid PNG and PDF, the scale
# figure when the manifest names it, each figure script from the command line, and a clear error
# (not a traceback, not an empty plot) for a missing file or a profile with no rows; --help of
# every script, and one-line refusals (exit 2) of wrong arguments and tables a script does not draw
# (in a report folder too, its other figures drawn).
# Exit 77 (skipped) when Debian's matplotlib is not installed.
# Usage: plot_test.sh FIXTURE_DIR
set -euo pipefail
fixture=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
py=/usr/bin/python3
$py -c 'import matplotlib' 2>/dev/null || { echo "python3-matplotlib not installed: skipped"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp -r "$fixture" "$tmp/r"
$py "$root/scripts/plot_report.py" "$tmp/r"
for f in figure1 profile histograms miss-rates time speedup speedup-mean gain meshes smoothing \
  orderings figure11 machine-misses predicted-speedup kernels; do
  head -c 8 "$tmp/r/figures/$f.png" | od -An -c | grep -q 'P   N   G' || { echo "$f.png: not a PNG"; exit 1; }
  head -c 5 "$tmp/r/figures/$f.pdf" | grep -q '%PDF-' || { echo "$f.pdf: not a PDF"; exit 1; }
done
[[ ! -e $tmp/r/figures/scale.png ]] || { echo "scale figure drawn without --scale"; exit 1; }
# The scale figure: the manifest of a scale run names it.
$py - "$tmp/r/manifest.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["figures"].append({"name": "scale", "paper": "-", "title": "scale", "script": "plot_scale.py",
                     "variant": "", "inputs": ["tables/table1.csv", "tables/time.csv",
                                               "data/misses.csv"]})
json.dump(m, open(sys.argv[1], "w"))
PY
[[ $($py "$root/scripts/plot_report.py" "$tmp/r") == *scale* ]]
head -c 5 "$tmp/r/figures/scale.pdf" | grep -q '%PDF-'
# The one histogram and profile schemas: analyze's own files plot with the same scripts.
$py "$root/scripts/plot_histograms.py" "$fixture/data/histogram.csv" "$tmp/h"
$py "$root/scripts/plot_profile.py" "$fixture/data/profile.csv" "$tmp/p" "a title"
for f in h p; do head -c 5 "$tmp/$f.pdf" | grep -q '%PDF-'; done
# Bad input: one line naming the file, exit non-zero.
if $py "$root/scripts/plot_profile.py" "$tmp/none.csv" "$tmp/x" 2>"$tmp/err"; then exit 1; fi
grep -q "none.csv: no such file" "$tmp/err"
head -n 1 "$fixture/data/profile.csv" >"$tmp/empty.csv"
if $py "$root/scripts/plot_profile.py" "$tmp/empty.csv" "$tmp/x" 2>"$tmp/err"; then exit 1; fi
grep -q "no rows" "$tmp/err"
[[ ! -e $tmp/x.png ]]
# Every script answers --help (exit 0, its usage); wrong arguments and a table it does not draw
# (compare's CSV to the speedup figure) are refused in one line with exit 2, never a traceback.
for s in "$root"/scripts/plot_*.py; do
  [[ $s == */plot_common.py ]] && continue
  $py "$s" --help >"$tmp/help" 2>&1 || { echo "$(basename "$s") --help: exit $?"; exit 1; }
  grep -q "scripts/$(basename "$s")" "$tmp/help" || { echo "$(basename "$s") --help: no usage line"; cat "$tmp/help"; exit 1; }
done
refused() {  # refused WHAT PATTERN COMMAND... : exit 2, PATTERN on stderr, no traceback
  local what=$1 pattern=$2 rc=0
  shift 2
  "$@" >"$tmp/out" 2>"$tmp/err" || rc=$?
  if [[ $rc -ne 2 ]] || ! grep -q -- "$pattern" "$tmp/err" || grep -q Traceback "$tmp/err"; then
    echo "$what: exit $rc, stderr:"; cat "$tmp/err"; exit 1
  fi
}
printf 'mesh,ordering,threads,rounds,sweep_ms\nm,ori,1,3,1.5\n' >"$tmp/compare.csv"
refused "speedup of compare.csv" "no column 'speedup'" $py "$root/scripts/plot_speedup.py" "$tmp/compare.csv" "$tmp/s" t speedup
refused "speedup, wrong arguments" "usage:" $py "$root/scripts/plot_speedup.py" a b
refused "report of a folder that is none" "not a report folder" $py "$root/scripts/plot_report.py" "$tmp/none"
[[ ! -e $tmp/none ]] || { echo "plot_report made the folder it refused"; exit 1; }
# The figures are drawn side by side: one that cannot be drawn still stops the report's script
# with exit 2 and one line naming its input, and the others are drawn.
cp -r "$fixture" "$tmp/b"
printf 'mesh,ordering\nm,ori\n' >"$tmp/b/tables/time.csv"
refused "report with a broken time table" "time.csv: no column" $py "$root/scripts/plot_report.py" "$tmp/b"
[[ $(grep -c . "$tmp/err") == 1 ]] || { echo "more than one line for one broken table:"; cat "$tmp/err"; exit 1; }
head -c 5 "$tmp/b/figures/figure1.pdf" | grep -q '%PDF-' || { echo "figure1 not drawn beside the broken one"; exit 1; }
echo "plot_test: every figure drawn from the fixture CSVs"
