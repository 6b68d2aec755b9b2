#!/usr/bin/env bash
# The CLI as a user meets it: help, exit codes, outputs of each subcommand on the tiny mesh.
# Usage: commands.sh MESHREUSE DATA
set -u
bin=$1 data=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
check() {  # check NAME EXPECTED_RC COMMAND... ; stdout+stderr in $tmp/out
  local name=$1 want=$2
  shift 2
  "$@" >"$tmp/out" 2>&1
  local rc=$?
  if [[ $rc -eq $want ]]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $name: exit $rc, expected $want"; sed 's/^/    /' "$tmp/out" | head -20; fi
}
contains() {  # contains NAME TEXT : the last output contains TEXT
  if grep -qF -- "$2" "$tmp/out"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1: output lacks '$2'"; sed 's/^/    /' "$tmp/out" | head -20; fi
}

check "no arguments" 2 "$bin"
contains "no arguments" "usage: meshreuse <command>"
check "--help" 0 "$bin" --help
check "unknown command" 2 "$bin" frobnicate
contains "unknown command" "unknown command 'frobnicate'"
for c in "mesh info" "mesh generate" "mesh convert" "smooth"; do
  check "$c --help" 0 "$bin" $c --help
  contains "$c --help" "usage: meshreuse $c"
done
check "unknown option" 2 "$bin" smooth "$data/two_interior.node" --frobnicate
contains "unknown option" "unrecognised option '--frobnicate'"
check "bad threads" 2 "$bin" smooth "$data/two_interior.node" --threads 0
check "bad mode" 2 "$bin" smooth "$data/two_interior.node" --mode sor
contains "bad mode" "unknown update mode 'sor'"

check "mesh info" 0 "$bin" mesh info "$data/two_interior.node" --quiet
contains "mesh info" "vertices           8"
contains "mesh info" "boundary vertices  6"
check "mesh info json" 0 "$bin" mesh info "$data/two_interior22.msh" --json --quiet
contains "mesh info json" '"vertices": 8, "triangles": 8, "boundary_vertices": 6'
contains "mesh info json" "dropped 1 vertices"  # the warning, on stderr

check "convert vtk" 0 "$bin" mesh convert "$data/two_interior41.msh" -o "$tmp/m.vtk" --quiet
[[ -s $tmp/m.vtk ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL convert: no m.vtk"; }
check "convert node" 0 "$bin" mesh convert "$data/two_interior41.msh" -o "$tmp/conv" --quiet
check "read converted" 0 "$bin" mesh info "$tmp/conv" --quiet
contains "read converted" "triangles          8"

check "smooth" 0 "$bin" smooth "$data/two_interior.node" --max-iters 3 --tol -1 -o "$tmp/s.vtk" --out "$tmp/res" --quiet
contains "smooth" "sweeps 3 (max-iters reached)"
for f in s.vtk res/summary.csv res/summary.md res/sweeps.csv res/run.json; do
  [[ -s $tmp/$f ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL smooth: no $f"; }
done
grep -q '"git_revision"' "$tmp/res/run.json" && grep -q '"machine"' "$tmp/res/run.json" &&
  /usr/bin/python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$tmp/res/run.json" &&
  pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL run.json is not valid JSON with git_revision and machine"; }
[[ $(ls "$tmp/res" | grep -c tmp) -eq 0 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL temporary files left in results"; }
check "smooth two meshes" 0 "$bin" smooth "$data/two_interior.node" "$data/two_interior41.msh" --quiet
contains "smooth two meshes" "median_ms_per_sweep"
check "smooth -o two meshes" 2 "$bin" smooth "$data/two_interior.node" "$data/two_interior41.msh" -o "$tmp/x"
check "unwritable output" 2 "$bin" smooth "$data/two_interior.node" -o /nonexistent-dir/x.vtk --quiet
contains "unwritable output" "/nonexistent-dir/x.vtk: cannot write"

check "generate unknown shape" 2 "$bin" mesh generate --shape nope -o "$tmp/g"
contains "generate unknown shape" "unknown shape 'nope'"
check "generate both" 2 "$bin" mesh generate --shape lake --poly x.poly
if command -v triangle >/dev/null; then
  check "generate" 0 "$bin" mesh generate --shape stress --vertices 3000 -o "$tmp/gen/stress" --quiet
  contains "generate" "target 3,000"
  check "generated mesh reads" 0 "$bin" mesh info "$tmp/gen/stress.node" --quiet
else
  echo "note: 'triangle' not installed; skipped the generate checks"
fi
PATH=/nonexistent check "generate without triangle" 1 "$bin" mesh generate --shape lake -o "$tmp/g2" --quiet
contains "generate without triangle" "triangle-bin"

echo "cli commands: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
