#!/usr/bin/env bash
# The CLI as a user meets it: help, exit codes, outputs of each subcommand on the tiny mesh.
# Usage: commands.sh MESHREUSE DATA
set -u
bin=$1 data=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib.sh"

check "no arguments" 2 "$bin"
contains "no arguments" "usage: meshreuse <command>"
check "--help" 0 "$bin" --help
check "unknown command" 2 "$bin" frobnicate
contains "unknown command" "unknown command 'frobnicate'"
for c in "mesh info" "mesh generate" "mesh convert" "mesh refine" "mesh partition" "smooth" "orderings" "kernels" "reorder" "compare" "trace" "analyze" "simulate" "validate"; do
  check "$c --help" 0 "$bin" $c --help
  contains "$c --help" "usage: meshreuse $c"
done
check "unknown option" 2 "$bin" smooth "$data/two_interior.node" --frobnicate
contains "unknown option" "unrecognised option '--frobnicate'"
check "bad threads" 2 "$bin" smooth "$data/two_interior.node" --threads 0
check "bad mode" 2 "$bin" smooth "$data/two_interior.node" --mode sor
contains "bad mode" "unknown update mode 'sor'"

# The scripts' own options: usage at once, an unknown option refused (exit 2), nothing started.
root=$(cd "$(dirname "$0")/../.." && pwd)
for sc in test.sh reproduce.sh; do
  check "$sc --help" 0 timeout 5 bash "$root/scripts/$sc" --help
  contains "$sc --help" "Usage: scripts/$sc"
  check "$sc bad option" 2 timeout 5 bash "$root/scripts/$sc" --frobnicate
  contains "$sc bad option" "unknown argument '--frobnicate'"
done
check "mesh help" 0 "$bin" mesh --help
contains "mesh help" "mesh info"
check "mesh alone" 2 "$bin" mesh
# Exit codes (core/error.h): 2 bad input or options, 3 the environment (an unwritable folder).
mkdir -p "$tmp/ro" && chmod 555 "$tmp/ro"
if [[ $(id -u) -ne 0 ]]; then
  check "read-only output" 3 "$bin" mesh convert "$data/two_interior.node" -o "$tmp/ro/m.vtk" --quiet
  contains "read-only output" "cannot write"
fi

check "mesh info" 0 "$bin" mesh info "$data/two_interior.node" --quiet
contains "mesh info" "vertices           8"
contains "mesh info" "boundary vertices  6"
check "mesh info json" 0 "$bin" mesh info "$data/two_interior22.msh" --json --quiet
contains "mesh info json" '"vertices":8,"triangles":8,"boundary_vertices":6'
contains "mesh info json" "dropped 1 vertices"  # the warning, on stderr
# --kernels: the working set of one sweep per kernel (exact values: tests/reports/working_set_test.cc).
check "mesh info kernels" 0 "$bin" mesh info "$data/two_interior.node" --kernels spmv,laplacian --quiet
contains "mesh info kernels" "working set of one sweep"
contains "mesh info kernels" "spmv                        155           13"
contains "mesh info kernels" "A.off 2, A.col 3, A.val 5, x 1, y 1"
check "mesh info kernels json" 0 "$bin" mesh info "$data/two_interior.node" --kernels all --json --quiet
contains "mesh info kernels json" '"kernel":"spmv","accesses":155,"lines":13,"bytes":832'
contains "mesh info kernels json" '"kernel":"edge-swap"'
check "mesh info unknown kernel" 2 "$bin" mesh info "$data/two_interior.node" --kernels laplacian,nope --quiet
contains "mesh info unknown kernel" "--kernels: unknown kernel 'nope' (known: laplacian,"

check "convert vtk" 0 "$bin" mesh convert "$data/two_interior41.msh" -o "$tmp/m.vtk" --quiet
[[ -s $tmp/m.vtk ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL convert: no m.vtk"; }
check "convert node" 0 "$bin" mesh convert "$data/two_interior41.msh" -o "$tmp/conv" --quiet
check "read converted" 0 "$bin" mesh info "$tmp/conv" --quiet
contains "read converted" "triangles          8"

check "refine" 0 "$bin" mesh refine "$data/two_interior.node" --levels 2 --jitter 0.3 -o "$tmp/ref" --quiet
contains "refine" "refined    77 vertices, 128 triangles"
grep '^hash' "$tmp/out" >"$tmp/refine.hash"
check "refine again" 0 "$bin" mesh refine "$data/two_interior.node" --levels 2 --jitter 0.3 -o "$tmp/ref2" --quiet
contains "refine again" "$(cat "$tmp/refine.hash")"  # the same mesh, bit for bit
check "read refined" 0 "$bin" mesh info "$tmp/ref" --quiet
contains "read refined" "triangles          128"
check "refine bad levels" 2 "$bin" mesh refine "$data/two_interior.node" --levels 16 -o "$tmp/ref3" --quiet
check "refine too large" 2 "$bin" mesh refine "$data/two_interior.node" --levels 15 -o "$tmp/ref3" --quiet
contains "refine too large" "more than 32-bit ids hold"
check "refine bad jitter" 2 "$bin" mesh refine "$data/two_interior.node" --jitter 0.9 -o "$tmp/ref3" --quiet
# The pieces layout: written by 1..4 ranks as threads, byte for byte the in-memory file.
check "refine pieces" 0 "$bin" mesh refine "$data/plate41.msh" --levels 2 --jitter 0.3 --layout pieces -o "$tmp/pieces.mrm" --quiet
contains "refine pieces" "content id"
for p in 1 3 4; do
  check "refine pieces --ranks $p" 0 "$bin" mesh refine "$data/plate41.msh" --levels 2 --jitter 0.3 --layout pieces --ranks $p -o "$tmp/ranks.mrm" --quiet
  cmp -s "$tmp/pieces.mrm" "$tmp/ranks.mrm" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL refine pieces --ranks $p differs"; }
done
contains "refine pieces --ranks 4" "Euler characteristic 0 (coarse 0)"
check "refine pieces reads" 0 "$bin" mesh info "$tmp/ranks.mrm" --quiet
contains "refine pieces reads" "triangles          29,504"
check "refine pieces vtk" 0 "$bin" mesh refine "$data/two_interior.node" --levels 2 --layout pieces -o "$tmp/pieces.vtk" --quiet
check "refine bad layout" 2 "$bin" mesh refine "$data/two_interior.node" --layout morton -o "$tmp/ref3" --quiet
contains "refine bad layout" "--layout must be refinement, hilbert or pieces"
check "refine ranks without pieces" 2 "$bin" mesh refine "$data/two_interior.node" --ranks 2 -o "$tmp/ref3.mrm" --quiet
contains "refine ranks without pieces" "--ranks needs --layout pieces and -o PATH.mrm"
check "refine ranks zero" 2 "$bin" mesh refine "$data/two_interior.node" --layout pieces --ranks 0 -o "$tmp/ref3.mrm" --quiet
[[ ! -e $tmp/ref3.mrm ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL refused refinements wrote ref3.mrm"; }

check "partition" 0 "$bin" mesh partition "$data/two_interior.node" --parts 2 -o "$tmp/p.txt" --quiet
contains "partition" "parts 2 (hilbert)"
[[ $(grep -vc '^#' "$tmp/p.txt") == 8 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL partition: not 8 parts in p.txt"; }
check "partition inherited" 0 "$bin" mesh partition "$data/two_interior.node" --parts 3 --method metis --levels 2 --quiet
contains "partition inherited" "vertices 77, parts 3 (metis, inherited through 2 levels)"
check "partition bad method" 2 "$bin" mesh partition "$data/two_interior.node" --method chaco --quiet
contains "partition bad method" "--method must be hilbert, metis, scotch, ranges or gmsh, not 'chaco'"
check "partition scotch" 0 "$bin" mesh partition "$data/two_interior.node" --parts 2 --method scotch --quiet
contains "partition scotch" "vertices 8, parts 2 (scotch)"
check "partition too many" 2 "$bin" mesh partition "$data/two_interior.node" --parts 9 --quiet
# A Gmsh split set written and read back; Gmsh itself reads it as partitioned where installed.
check "partition --split" 0 "$bin" mesh partition "$data/plate41.msh" --parts 3 --method metis --split "$tmp/sp_" --quiet
contains "partition --split" "wrote $tmp/sp_3.msh"
check "split read back" 0 "$bin" mesh partition "$tmp/sp_2.msh" --parts 3 --method gmsh --quiet
contains "split read back" "vertices 995, parts 3 (gmsh)"
check "split onto its input" 2 "$bin" mesh partition "$tmp/sp_1.msh" --parts 3 --method gmsh --split "$tmp/sp_" --quiet
contains "split onto its input" "is the input"
check "split prefix a folder" 2 "$bin" mesh partition "$data/plate41.msh" --parts 2 --split "$tmp/" --quiet
if command -v gmsh >/dev/null; then
  check "gmsh reads the split set" 0 gmsh "$tmp/sp_1.msh" -0 -o "$tmp/gmsh_check.msh"
  contains "gmsh reads the split set" "3 partitions"
else
  echo "commands: skipped Gmsh reading a written split set (no gmsh here; apt-get install gmsh)"
fi

check "smooth" 0 "$bin" smooth "$data/two_interior.node" --max-iters 3 --tol -1 -o "$tmp/s.vtk" --out "$tmp/res" --quiet
contains "smooth" "sweeps 3 (max-iters reached)"
for f in s.vtk res/summary.csv res/summary.md res/sweeps.csv res/run.json; do
  [[ -s $tmp/$f ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL smooth: no $f"; }
done
grep -q '"git_revision"' "$tmp/res/run.json" && grep -q '"machine"' "$tmp/res/run.json" &&
  /usr/bin/python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$tmp/res/run.json" &&
  pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL run.json is not valid JSON with git_revision and machine"; }
[[ $(ls "$tmp/res" | grep -c tmp) -eq 0 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL temporary files left in results"; }
# The same smoothed mesh in every format -o writes (issue 39): .vtu (VTK XML, compressed) and .msh
# (Gmsh 4.1) read by meshio equal to the legacy .vtk; the .msh read back here equal to .node/.ele;
# analyze --vtk X.vtu keeps its fields.
fine41=$data/plate41.msh
for f in s41.vtk s41.vtu s41.msh s41; do
  check "smooth -o $f" 0 "$bin" smooth "$fine41" --max-iters 3 --tol -1 -o "$tmp/$f" --quiet
done
check "vtu == vtk (meshio)" 0 /usr/bin/python3 "$here/../scripts/check_vtu.py" grid "$tmp/s41.vtu" "$tmp/s41.vtk"
contains "vtu == vtk: fields compared" "boundary, vertex_quality, triangle_quality"
check "msh == vtk (meshio)" 0 /usr/bin/python3 "$here/../scripts/check_vtu.py" grid "$tmp/s41.msh" "$tmp/s41.vtk"
check "msh read back" 0 "$bin" mesh convert "$tmp/s41.msh" -o "$tmp/back" --quiet
if cmp -s "$tmp/back.node" "$tmp/s41.node" && cmp -s "$tmp/back.ele" "$tmp/s41.ele"; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL .msh read back differs from .node/.ele"; fi
check "mesh convert -> vtu" 0 "$bin" mesh convert "$tmp/s41.msh" -o "$tmp/c41.vtu" --quiet
check "converted vtu == smoothed vtu" 0 /usr/bin/python3 "$here/../scripts/check_vtu.py" grid "$tmp/c41.vtu" "$tmp/s41.vtu"
check "analyze --vtk .vtu" 0 "$bin" analyze "$fine41" --orderings bfs --vtk "$tmp/a.vtu" --quiet
check "analyze --vtk .vtk" 0 "$bin" analyze "$fine41" --orderings bfs --vtk "$tmp/a.vtk" --quiet
if /usr/bin/python3 - "$tmp/a.vtu" "$tmp/a.vtk" <<'PY'; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL analyze --vtk .vtu fields"; fi
import sys, meshio, numpy as np
u, k = meshio.read(sys.argv[1]), meshio.read(sys.argv[2])
assert set(k.point_data) <= set(u.point_data), (set(k.point_data), set(u.point_data))
for name in ("rank", "original_id", "reuse_distance_max"):
    a, b = np.ravel(u.point_data[name]), np.ravel(k.point_data[name])
    assert np.array_equal(a.astype(np.float64), b.astype(np.float64)), name
assert u.point_data["rank"].dtype == np.int32
PY
check "pvtu refused by mesh convert" 2 "$bin" mesh convert "$fine41" -o "$tmp/x.pvtu"
contains "pvtu refused by mesh convert: said" "a .pvtu (one .vtu piece per rank) is written by the distributed smoother"

check "smooth two meshes" 0 "$bin" smooth "$data/two_interior.node" "$data/two_interior41.msh" --quiet
contains "smooth two meshes" "median_ms_per_sweep"
check "smooth -o two meshes" 2 "$bin" smooth "$data/two_interior.node" "$data/two_interior41.msh" -o "$tmp/x"
check "unwritable output" 2 "$bin" smooth "$data/two_interior.node" -o /nonexistent-dir/x.vtk --quiet
contains "unwritable output" "-o '/nonexistent-dir/x.vtk': cannot write: its folder /nonexistent-dir does not exist"

check "generate unknown shape" 2 "$bin" mesh generate --shape nope -o "$tmp/g"
contains "generate unknown shape" "unknown shape 'nope'"
check "generate both" 2 "$bin" mesh generate --shape lake --poly x.poly
if command -v triangle >/dev/null; then
  check "generate" 0 "$bin" mesh generate --shape stress --vertices 3000 -o "$tmp/gen/stress" --quiet
  contains "generate" "target 3,000"
  check "generated mesh reads" 0 "$bin" mesh info "$tmp/gen/stress.node" --quiet
  # A count the outline cannot reach is the user's to change (exit 2, naming --vertices), not a bug.
  check "generate too few vertices" 2 "$bin" mesh generate --shape ocean --vertices 100 -o "$tmp/gen/few" --quiet
  contains "generate too few vertices" "--vertices 100: could not mesh"
else
  echo "note: 'triangle' not installed; skipped the generate checks"
fi
PATH=/nonexistent check "generate without triangle" 3 "$bin" mesh generate --shape lake -o "$tmp/g2" --quiet
contains "generate without triangle" "triangle-bin"

# Orderings: list, reorder (mesh + permutation), read the permutation back, smooth and compare.
check "orderings" 0 "$bin" orderings
contains "orderings" "rdr"
contains "orderings" "Aupy, Park, Raghavan, Algorithm 2"
for o in rdr-frontier rdr-wave morton "metis[:ARG]" nd "wave-blocks[:ARG]" "metis-wave[:ARG]" "grid-wave[:ARG]"; do contains "orderings" "$o"; done
check "smooth lean" 0 "$bin" smooth "$data/two_interior.node" --quality per-sweep --max-iters 2 --tol -1 --out "$tmp/lean" --quiet
contains "smooth lean" "sweeps 2"
grep -q '"quality": "per-sweep"' "$tmp/lean/run.json" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL smooth lean: run.json lacks the quality mode"; }
check "smooth bad quality" 2 "$bin" smooth "$data/two_interior.node" --quality sometimes
contains "smooth bad quality" "unknown quality mode 'sometimes'"
check "metis bytes" 0 "$bin" smooth "$data/two_interior.node" --ordering metis:1K --max-iters 1 --quiet
check "metis bad bytes" 2 "$bin" smooth "$data/two_interior.node" --ordering metis:lots
contains "metis bad bytes" "metis:BYTES needs a positive size"
check "reorder" 0 "$bin" reorder "$data/two_interior.node" --ordering rdr -o "$tmp/r" --quiet
for f in r.node r.ele r.perm; do
  [[ -s $tmp/$f ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL reorder: no $f"; }
done
check "reorder from file" 0 "$bin" reorder "$data/two_interior.node" --ordering "file:$tmp/r.perm" -o "$tmp/r2" --quiet
cmp -s "$tmp/r.node" "$tmp/r2.node" && cmp -s "$tmp/r.ele" "$tmp/r2.ele" && pass=$((pass + 1)) ||
  { fail=$((fail + 1)); echo "FAIL reorder via file: does not reproduce the rdr mesh"; }
check "reordered smooths" 0 "$bin" smooth "$tmp/r.node" --quiet
check "smooth --ordering" 0 "$bin" smooth "$data/two_interior.node" --ordering random --seed 7 --quiet
contains "smooth --ordering" "ordering random (seed 7)"
contains "smooth --ordering" "reordering (ordering + apply):"
check "smooth unknown ordering" 2 "$bin" smooth "$data/two_interior.node" --ordering nope
contains "smooth unknown ordering" "unknown ordering 'nope'"
printf '0\n1\n2\n2\n' >"$tmp/bad.perm"
check "bad permutation file" 2 "$bin" reorder "$data/two_interior.node" --ordering "file:$tmp/bad.perm" -o "$tmp/x" --quiet
contains "bad permutation file" "meshreuse: error: $tmp/bad.perm:4: vertex id 2 is repeated (first on line 3)"
[[ ! -e $tmp/x.node ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL bad permutation: wrote output"; }
check "compare" 0 "$bin" compare "$data/two_interior.node" "$data/two_interior41.msh" --orderings ori,bfs,rdr,random --threads 1,2 --repeat 3 --out "$tmp/cmp" --quiet
contains "compare" "speedup vs ori1 [95%]"
contains "compare" "(seed 1; medians over the rounds after a warm-up, [95% interval of the median]"
check "compare one round" 2 "$bin" compare "$data/two_interior.node" --repeat 1 --quiet
contains "compare one round" "--repeat must be at least 3"
check "compare no warm-up" 2 "$bin" compare "$data/two_interior.node" --warm-up-sweeps 0 --quiet
contains "compare no warm-up" "--warm-up-sweeps must be 1..1000"
check "compare warns even when quiet" 0 "$bin" compare "$data/two_interior22.msh" --orderings ori --repeat 3 --quiet
contains "compare warns even when quiet" "meshreuse: warning: $data/two_interior22.msh: dropped 1 vertices"
for f in compare.csv compare.md compare.json run.json; do
  [[ -s $tmp/cmp/$f ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL compare: no $f"; }
done
[[ $(wc -l <"$tmp/cmp/compare.csv") -eq 17 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL compare.csv should have 2 meshes x 4 orderings x 2 threads rows"; }
/usr/bin/python3 - "$tmp/cmp" <<'PY' && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL compare JSON"; }
import json, sys
run = json.load(open(sys.argv[1] + "/run.json"))
rows = json.load(open(sys.argv[1] + "/compare.json"))["rows"]
assert run["configuration"]["seed"] == 1 and run["configuration"]["repeat"] == 3, run["configuration"]
assert run["configuration"]["warmup_sweeps"] == 2, run["configuration"]
assert "noise" in run and "busy" in run["noise"], run.keys()
for r in rows:
    if r["ordering"] == "ori" and r["threads"] == 1:
        assert r["speedup_vs_ori1"]["median"] == 1.0 and r["speedup_vs_ori1_verdict"] == "reference", r
    if r["ordering"] == "bfs":
        assert r["gain_vs_bfs"]["median"] is None, r  # no gain over itself
    s = r["seconds_per_sweep"]
    assert s["min"] <= s["ci95_low"] <= s["median"] <= s["ci95_high"] <= s["max"], s
    assert len(r["rounds_measured"]) == 3 and r["vertices"] == 8, r
    assert all(x["total_cpu"] > 0 for x in r["rounds_measured"]), r
PY
check "compare cpu clock" 0 "$bin" compare "$data/two_interior.node" --orderings ori,bfs --repeat 3 --clock cpu --out "$tmp/cmpcpu" --quiet
contains "compare cpu clock" "per-sweep medians (cpu clock)"
grep -q '"clock": "cpu"' "$tmp/cmpcpu/run.json" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL compare cpu clock: run.json"; }
contains "compare cpu clock: the interval is the cpu one" "cpu ms/sweep [95%]"
contains "compare cpu clock: wall beside it" "wall ms/sweep"
# --repeat auto:CAP ends settled (every speedup within +-2%) or at its cap, and says which: at the
# cap a warning naming the widest interval left, kept in run.json either way (issue 39).
check "compare auto cap" 0 "$bin" compare "$data/plate41.msh" --orderings ori,bfs,random --repeat auto:3 --max-iters 2 --tol -1 --out "$tmp/cmpauto" --quiet
cp "$tmp/out" "$tmp/cmpauto.out"
if /usr/bin/python3 - "$tmp/cmpauto/run.json" "$tmp/cmpauto.out" <<'PY'; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL compare auto cap"; cat "$tmp/cmpauto.out"; fi
import json, sys
run = json.load(open(sys.argv[1]))
ends = run["repeat_auto"]
out = open(sys.argv[2]).read()
assert len(ends) == 1, ends
e = ends[0]
assert e["settled"] == (e["widest_relative_half_width"] <= 0.02), e
said = "--repeat auto stopped at its cap of 3 rounds" in out
assert said == (not e["settled"]), (said, e)
if said:
    assert f"the widest, {e['widest']}'s, is +-{100 * e['widest_relative_half_width']:.1f}%" in out, out
    assert e["rounds"] == 3
PY
check "compare bad clock" 2 "$bin" compare "$data/two_interior.node" --clock cycles
contains "compare bad clock" "--clock: 'cycles' is not a clock (wall or cpu)"
check "compare bad threads" 2 "$bin" compare "$data/two_interior.node" --threads 1,x
check "compare unknown ordering" 2 "$bin" compare "$data/two_interior.node" --orderings ori,zzz

# Traces and reuse distances: a trace file and the streamed mesh give the same numbers.
check "trace" 0 "$bin" trace "$data/two_interior.node" --ordering rdr --iterations 3 --threads 2 -o "$tmp/t.trace" --quiet
contains "trace" "498 accesses (20.75 per vertex per sweep), 132 element touches (5.50), 3 sweep(s), 2 stream(s)"
check "analyze trace" 0 "$bin" analyze "$tmp/t.trace" --csv --quiet
cp "$tmp/out" "$tmp/from_file.csv"
check "analyze mesh" 0 "$bin" analyze "$data/two_interior.node" --orderings rdr --iterations 3 --threads 2 --csv --quiet
if diff <(cut -d, -f2- "$tmp/from_file.csv") <(cut -d, -f2- "$tmp/out") >/dev/null; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL analyze: the trace file and the streamed mesh disagree"; diff "$tmp/from_file.csv" "$tmp/out" | head; fi
check "analyze json" 0 "$bin" analyze "$data/two_interior.node" --iterations 2 --json --quiet --histogram-csv "$tmp/h.csv" --profile-csv "$tmp/p.csv" --measured-misses L1=5
/usr/bin/python3 - "$tmp/out" <<'PY' && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL analyze --json"; }
import json, sys
rows = json.load(open(sys.argv[1]))
e = [r for r in rows if r["granularity"] == "element"][0]
assert e["accesses"] == 88 and e["cold"] == 8 and e["distinct"] == 8, e
assert e["q100"] >= e["q90"] >= e["q75"] >= e["q50"], e
assert e["L1_misses"] == 8 and "cost_cycles_at_low_latency" in e and "L1_capacity_for_5" in e, e
PY
[[ $(wc -l <"$tmp/p.csv") -eq 289 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL profile csv: want 2 sweeps x (44 element + 100 line steps) + header"; }
grep -q '^input,ordering,thread,granularity,lo,hi,count' "$tmp/h.csv" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL histogram csv"; }
# One schema per analysis: analyze's histogram and profile files have the report's columns
# (tests/data/report is a report folder), and one script plots each.
for f in h:histogram p:profile; do
  [[ $(head -n 1 "$tmp/${f%%:*}.csv") == $(head -n 1 "$data/report/data/${f#*:}.csv") ]] && pass=$((pass + 1)) ||
    { fail=$((fail + 1)); echo "FAIL ${f#*:} csv: analyze's columns differ from the report's"; }
done
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  scripts=$(dirname "$0")/../../scripts
  check "plot analyze histogram" 0 /usr/bin/python3 "$scripts/plot_histograms.py" "$tmp/h.csv" "$tmp/hplot"
  check "plot analyze profile" 0 /usr/bin/python3 "$scripts/plot_profile.py" "$tmp/p.csv" "$tmp/pplot"
  "$bin" analyze "$data/two_interior.node" --mrc-csv "$tmp/m.csv" --quiet >/dev/null
  check "plot analyze mrc" 0 /usr/bin/python3 "$scripts/plot_mrc.py" "$tmp/m.csv" "$tmp/mplot"
  "$bin" simulate "$data/two_interior.node" --orderings ori,bfs --cache L1=256/2,L2=1K/4 --csv --quiet >"$tmp/sim.csv"
  check "plot simulate" 0 /usr/bin/python3 "$scripts/plot_simulation.py" "$tmp/sim.csv" "$tmp/splot"
  for f in hplot pplot mplot splot; do
    [[ -s $tmp/$f.png && -s $tmp/$f.pdf ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL plot $f"; }
  done
fi
printf '1\n2\n0x1\n# c\n3\n2\n' >"$tmp/ext.txt"
check "analyze text" 0 "$bin" analyze "$tmp/ext.txt" --format text --granularity element --csv --quiet
contains "analyze text" "$tmp/ext.txt,,0,element,5,,3,3,3,1.5,1,2,2,2"  # ids 1 2 1 3 2: distances 1, 2
check "analyze stdin" 0 bash -c "printf '5\n5\n' | '$bin' analyze - --format text --granularity element --csv --quiet"
contains "analyze stdin" "-,,0,element,2,,1,1,0,0,0,0,0,0"  # missing values: empty
/usr/bin/python3 -c 'import struct,sys; open(sys.argv[1],"wb").write(struct.pack("<4Q",7,8,7,8))' "$tmp/ext.u64"
check "analyze u64" 0 "$bin" analyze "$tmp/ext.u64" --format u64 --granularity element --csv --quiet
contains "analyze u64" ",element,4,,2,2,2,1,1,1,1,1"
printf 'MRTRACEX' >"$tmp/bad.trace"
check "analyze bad trace" 2 "$bin" analyze "$tmp/bad.trace" --quiet
contains "analyze bad trace" "meshreuse: error: $tmp/bad.trace: not a meshreuse trace (wrong magic"
head -c 100 "$tmp/t.trace" >"$tmp/cut.trace"
check "analyze truncated trace" 2 "$bin" analyze "$tmp/cut.trace" --quiet
contains "analyze truncated trace" "truncated trace"
printf '1\nx2\n' >"$tmp/bad.txt"
check "analyze bad text" 2 "$bin" analyze "$tmp/bad.txt" --format text --quiet
contains "analyze bad text" "$tmp/bad.txt:2: expected a decimal or 0x-hex id, found 'x2'"
check "analyze bad cache" 2 "$bin" analyze "$data/two_interior.node" --cache L1=lots
check "analyze bad granularity" 2 "$bin" analyze "$data/two_interior.node" --granularity page
check "trace unwritable" 2 "$bin" trace "$data/two_interior.node" -o /nonexistent-dir/t.trace --quiet

# Issue 9: compressed traces, analyzer threads, the ecosystem's formats, sampling, exact outputs.
check "trace --compress" 0 "$bin" trace "$data/two_interior.node" --ordering rdr --iterations 3 --threads 2 -o "$tmp/t.trace.zst" --compress --quiet
contains "trace --compress" "MB compressed"
"$bin" analyze "$tmp/t.trace" --csv --quiet | cut -d, -f2- >"$tmp/plain.csv"
for args in "$tmp/t.trace.zst" "$tmp/t.trace --threads 2" "$tmp/t.trace.zst --threads 3"; do
  # shellcheck disable=SC2086
  if diff <("$bin" analyze $args --csv --quiet | cut -d, -f2-) "$tmp/plain.csv" >/dev/null; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL analyze $args: differs from the plain serial analysis"; fi
done
/usr/bin/python3 -c 'import struct,sys; open(sys.argv[1],"wb").write(b"".join(struct.pack("<Q", i % 5000) for i in range(60000)))' "$tmp/scan.u64"
"$bin" analyze "$tmp/scan.u64" --format u64 --granularity element --csv --quiet >"$tmp/scan1.csv"
check "analyze u64 threads" 0 "$bin" analyze "$tmp/scan.u64" --format u64 --granularity element --csv --quiet --threads 2
if diff "$tmp/out" "$tmp/scan1.csv" >/dev/null; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL analyze u64 --threads 2 differs"; fi
contains "analyze u64 threads" ",element,60000,,5000,5000,274945000,4999,4999,4999,4999,4999,"  # a scan: every warm distance 4999
printf '==1== Lackey\nI  0040,2\n L 1000,8\n S 1000,8\n M 103e,4\n' >"$tmp/t.lackey"
check "analyze lackey" 0 "$bin" analyze "$tmp/t.lackey" --format lackey --granularity both --csv --quiet
contains "analyze lackey" ",element,4,,2,2,0,0,"  # addresses 1000 1000 103e 103e: distances 0, 0
contains "analyze lackey" ",line,6,,2,2,2,0.5,"  # lines 40 40 (40 41) (40 41): the modify straddles
# An address trace defaults to lines and says so under the table.
check "analyze lackey default" 0 "$bin" analyze "$tmp/t.lackey" --format lackey --quiet
contains "analyze lackey default" "granularity line for --format lackey (values are addresses"
if grep -q "  element  " "$tmp/out"; then fail=$((fail + 1)); echo "FAIL analyze lackey default: element rows"; else pass=$((pass + 1)); fi
check "analyze lackey instructions" 0 "$bin" analyze "$tmp/t.lackey" --format lackey --instructions --granularity element --csv --quiet
contains "analyze lackey instructions" ",element,5,,3,3,"
check "instructions without lackey" 2 "$bin" analyze "$tmp/scan.u64" --format u64 --instructions
# simulate: an I1 takes the fetch (line 1 of the I1), the data take D1; LL sees both levels' misses.
check "simulate lackey I1" 0 "$bin" simulate "$tmp/t.lackey" --format lackey --instructions --cache I1=1K/2,D1=1K/2,LL=4K/4 --csv --quiet
contains "simulate lackey I1" ",I1,1024,2,8,lru,1,0,1,1,0,1,0,0,1"
contains "simulate lackey I1" ",D1,1024,2,8,lru,4,2,2,2,0,0.5,2,0,0"  # L miss; S hit; M: L miss (straddles), S hit
contains "simulate lackey I1" ",LL,4096,4,16,lru,3,0,3,3,0,1,2,0,1"
# On a machine: another tool's trace has no sweeps, so its run is the whole trace (it stopped at
# an internal error once). L1: L miss (cold), S hit, M's read misses line 0x41 (cold), its write
# hits; cycles 4 x 4 + 2 x 10 (L2) + 2 x 38 (L3) + 2 x 175 (local memory) at the low end.
check "simulate lackey machine" 0 "$bin" simulate "$tmp/t.lackey" --format lackey --machine westmere-ex --csv --quiet
contains "simulate lackey machine" ",westmere-ex,compact,1,0,0,0,all,L1,4,2,2,2,0,0,0,0,2,0,,"
contains "simulate lackey machine" ",all,total,4,,,,,,,,,,462,"
check "analyze refuses I1" 2 "$bin" analyze "$tmp/t.lackey" --format lackey --cache I1=1K,L2=4K
contains "analyze refuses I1" "I1 is simulate's instruction cache"
check "analyze oracle" 2 "$bin" analyze "$data/broken/oracle_reserved.oracle" --format oracle --quiet
contains "analyze oracle" "record 1 (byte offset 24): the value 2^64-1 is reserved"
check "sample" 0 "$bin" analyze "$tmp/scan.u64" --format u64 --granularity element --sample-rate 0.5 --seed 7 --sample-error --json --quiet
contains "sample" '"sampling":"fixed-rate","rate":0.5'
contains "sample" '"seed":7,"accesses":60000'
# At rate 1 the sample is the trace: the miss ratio error at every level's capacity is 0.
check "sample rate 1" 0 "$bin" analyze "$tmp/scan.u64" --format u64 --granularity element --sample-rate 1 --sample-error --cache L1=64K,L2=512K --csv --quiet
contains "sample rate 1" ",mrc_mae,L1_miss_ratio_error,L2_miss_ratio_error"
contains "sample rate 1" ",0,0,0"
# Sampling is exact below the first cache level's capacity by default (512 lines or elements for
# westmere-ex; issue 39): on a 15,000-vertex mesh at rate 0.01 the median and the L1 misses equal
# the exact analysis's, bounded by 0; the levels beyond carry a 95% bound; a sample of fewer than
# 1,000 ids is said to be too small. --sample-exact-below 0 turns the exact part off.
"$bin" mesh refine "$data/plate41.msh" --levels 2 -o "$tmp/p2" --quiet &>/dev/null
check "exact analysis" 0 "$bin" analyze "$tmp/p2.node" --orderings bfs -k 2 --granularity element --csv --quiet
cp "$tmp/out" "$tmp/exact.csv"
check "sampled, default" 0 "$bin" analyze "$tmp/p2.node" --orderings bfs -k 2 --granularity element --sample-rate 0.01 --csv --out "$tmp/sampled"
cp "$tmp/out" "$tmp/sampled.out"
contains "sampled, default: a small sample said" "ids (fewer than 1000): its estimates at distances of 512 and beyond are not to be trusted"
if /usr/bin/python3 - "$tmp/exact.csv" "$tmp/sampled/analyze.csv" "$tmp/sampled/run.json" <<'PY'; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL sampled, default"; cat "$tmp/sampled.out"; fi
import csv, json, sys
ex = next(csv.DictReader(open(sys.argv[1])))
sa = next(csv.DictReader(open(sys.argv[2])))
cfg = json.load(open(sys.argv[3]))["configuration"]
assert cfg["sample_exact_below"] == 512, cfg["sample_exact_below"]
assert sa["q50_est"] == ex["q50"], (sa["q50_est"], ex["q50"])
assert round(float(sa["L1_misses_est"])) == int(ex["L1_misses"]), (sa["L1_misses_est"], ex["L1_misses"])
assert float(sa["L1_misses_ci95"]) == 0
for l in ("L2", "L3"):
    assert float(sa[l + "_misses_ci95"]) > 0, l
PY
check "sampled, exact part off" 0 "$bin" analyze "$tmp/p2.node" --orderings bfs -k 2 --granularity element --sample-rate 0.01 --sample-exact-below 0 --out "$tmp/sampled0" --quiet
contains "sampled, exact part off: said" "no distance counted exactly"
grep -q '"sample_exact_below": 0' "$tmp/sampled0/run.json" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL --sample-exact-below 0: run.json"; }
check "sample size" 0 "$bin" analyze "$tmp/scan.u64" --format u64 --granularity element --sample-size 100 --csv --quiet
contains "sample size" ",fixed-size,"
# Small distances counted exactly: at 1% on a mesh the L1 and L2 capacities (8 and 64 lines here)
# fall below K = 64 + 1, so their miss-ratio errors are exactly 0 where plain SHARDS' are not.
check "sample exact below" 0 "$bin" analyze "$data/plate41.msh" -k 3 --granularity line --sample-rate 0.01 \
  --sample-exact-below 65 --sample-error --cache L1=512/8,L2=4K/8 --csv --quiet
levels_exact() {  # the last two columns (L1 and L2 miss-ratio errors) of the last row within 1e-12
  tail -n 1 "$tmp/out" | awk -F, '{e1 = $(NF-1); e2 = $NF; exit !((e1 < 1e-12 && e1 > -1e-12) && (e2 < 1e-12 && e2 > -1e-12))}'
}
if levels_exact; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL sample exact below: L1/L2 errors not 0"; cat "$tmp/out"; fi
check "sample exact below: plain" 0 "$bin" analyze "$data/plate41.msh" -k 3 --granularity line --sample-rate 0.01 \
  --sample-error --cache L1=512/8,L2=4K/8 --csv --quiet
if levels_exact; then fail=$((fail + 1)); echo "FAIL plain SHARDS exact at L1 and L2 already: the test shows nothing"; else pass=$((pass + 1)); fi
check "sample exact below without sampling" 2 "$bin" analyze "$data/plate41.msh" --sample-exact-below 64
check "sample exact below in chunks" 2 "$bin" analyze "$data/plate41.msh" --sample-rate 0.1 --sample-exact-below 64 --chunk 0/2 --summary-out "$tmp/s0"
check "sample both" 2 "$bin" analyze "$tmp/scan.u64" --format u64 --sample-size 100 --sample-rate 0.1
check "sample rate range" 2 "$bin" analyze "$tmp/scan.u64" --format u64 --sample-rate 1.5
check "mrc csv" 0 "$bin" analyze "$tmp/scan.u64" --format u64 --granularity element --mrc-csv "$tmp/mrc.csv" --quiet
if [[ $(sed -n 2p "$tmp/mrc.csv") == *",element,0,60000,60000,1,0" && $(sed -n 3p "$tmp/mrc.csv") == *",element,5000,5000,60000,0.083333333333333329,0" ]]; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL mrc csv:"; head -3 "$tmp/mrc.csv"; fi
check "mrc csv unwritable" 2 "$bin" analyze "$tmp/scan.u64" --format u64 --mrc-csv /nonexistent-dir/m.csv --quiet
contains "mrc csv unwritable" "--mrc-csv '/nonexistent-dir/m.csv': cannot write: its folder /nonexistent-dir does not exist"

# The simulator: a mesh streamed and its trace file give the same rows; a fully associative level
# (ways = lines) gives the line model's misses.
check "simulate mesh" 0 "$bin" simulate "$data/two_interior.node" --orderings rdr --iterations 3 --threads 2 --cache L1=256/2,L2=1K/4 --csv --quiet
cut -d, -f2- "$tmp/out" >"$tmp/sim_mesh.csv"
contains "simulate mesh" ",0,all,L1,256,2,2,lru,249,"  # 3 sweeps x 83 loads and stores per thread
check "simulate trace" 0 "$bin" simulate "$tmp/t.trace" --cache L1=256/2,L2=1K/4 --csv --quiet
if diff <(cut -d, -f2- "$tmp/out") "$tmp/sim_mesh.csv" >/dev/null; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL simulate: the trace file and the streamed mesh disagree"; diff <(cut -d, -f2- "$tmp/out") "$tmp/sim_mesh.csv" | head; fi
check "simulate per sweep" 0 "$bin" simulate "$data/two_interior.node" --iterations 2 --per-sweep --cache L1=1K/16 --json --quiet
/usr/bin/python3 - "$tmp/out" <<'PY' && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL simulate --per-sweep"; }
import json, sys
rows = json.load(open(sys.argv[1]))
allrow = [r for r in rows if r["sweep"] == "all"][0]
sweeps = [r for r in rows if r["sweep"] != "all"]
assert len(sweeps) == 2 and sum(r["misses"] for r in sweeps) == allrow["misses"], rows
assert sweeps[1]["cold"] == 0 and allrow["accesses"] == 2 * 165, rows
PY
# Misses per array: every array of the sweep named, a rank's message buffers among them; the per
# array counts add up to the level's (checked in the core test); not with the many-core simulator.
check "simulate by array" 0 "$bin" simulate "$data/two_interior.node" --by-array --cache L1=256/2,L2=1K/4 --csv --quiet
contains "simulate by array" "input,ordering,thread,array,level,accesses,misses,miss_share"
contains "simulate by array" ",0,xy,L1,"
contains "simulate by array" ",0,v2t.idx,L2,"
check "simulate ranks by array" 0 "$bin" simulate "$data/plate41.msh" --ranks 3 --by-array --out "$tmp/sba" --csv --quiet
contains "simulate ranks by array" ",send.buf,L1,"
contains "simulate ranks by array" ",recv.idx,L3,"
if [[ -s $tmp/sba/simulate-arrays.csv && -s $tmp/sba/simulate.csv ]] && grep -q '"by_array": true' "$tmp/sba/run.json"; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL simulate --by-array --out: files"; ls "$tmp/sba"; fi
check "simulate by array on a machine" 2 "$bin" simulate "$data/two_interior.node" --by-array --machine westmere-ex
contains "simulate by array on a machine" "not with --machine"
check "simulate needs ways" 2 "$bin" simulate "$data/two_interior.node" --cache L1=32K
contains "simulate needs ways" "needs its associativity for simulation, e.g. L1=32K/8"
check "simulate bad geometry" 2 "$bin" simulate "$data/two_interior.node" --cache L1=1000/3
check "simulate json+csv" 2 "$bin" simulate "$data/two_interior.node" --json --csv
printf '0
64
128
0
' >"$tmp/addr.txt"
check "simulate text" 0 "$bin" simulate "$tmp/addr.txt" --format text --cache L1=128/1 --csv --quiet
contains "simulate text" ",,0,all,L1,128,1,2,lru,4,0,4,3,1,"  # 0 and 128 share set 0 of a direct-mapped 2-set cache

# Validation: every number labelled simulated here (no hardware counters), the tables written.
check "validate" 0 "$bin" validate "$data/two_interior.node" --orderings ori,bfs --iterations 2 --cache L1=256/2,L2=1K/4,L3=4K/8 --out "$tmp/val" --quiet
contains "validate" "simulated"
for f in validate.csv validate.md validate.json cost.csv table3.csv table3.md sweeps.csv run.json; do
  [[ -s $tmp/val/$f ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL validate --out: no $f"; }
done
/usr/bin/python3 - "$tmp/val/validate.json" "$tmp/val/run.json" <<'PY' && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL validate json"; }
import json, sys
rows = json.load(open(sys.argv[1]))
assert len(rows) == 6 and {r["level"] for r in rows} == {"L1", "L2", "L3"}, rows
for r in rows:
    assert r["simulated_excess"] == r["simulated_misses"] - r["simulated_cold"], r
json.load(open(sys.argv[2]))
PY
check "validate markdown" 0 "$bin" validate "$data/two_interior.node" --orderings ori --iterations 1 --markdown --counters none --quiet
contains "validate markdown" "| mesh | ordering | level |"
check "validate one format" 2 "$bin" validate "$data/two_interior.node" --json --markdown

# Counters: a software event counts through PAPI where it is built in; a missing event is said once.
check "smooth counters" 0 "$bin" smooth "$data/two_interior.node" --max-iters 2 --tol -1 --counters NO_SUCH_EVENT --quiet
contains "smooth counters" "meshreuse: note: counters:"
if "$bin" smooth "$data/two_interior.node" --max-iters 2 --counters perf::TASK-CLOCK --quiet >"$tmp/out" 2>&1 && grep -q "counter perf::TASK-CLOCK" "$tmp/out"; then
  pass=$((pass + 1))
elif grep -q "built without PAPI\|perf_event component disabled" "$tmp/out"; then
  pass=$((pass + 1))
else
  fail=$((fail + 1)); echo "FAIL smooth --counters perf::TASK-CLOCK"; sed 's/^/    /' "$tmp/out" | head
fi

# One triangle policy: with the file's order ori is the file as is; sorted is the default.
check "triangle order" 0 "$bin" smooth "$data/two_interior.node" --triangle-order file --max-iters 1 --quiet
check "triangle order bad" 2 "$bin" smooth "$data/two_interior.node" --triangle-order shuffled
contains "triangle order bad" "unknown triangle order 'shuffled' (sorted or file)"

# Outputs a program can read: --version, --json on every table, --json with --csv refused, missing
# values null/empty, output folders checked before any work.
check "version" 0 "$bin" --version
contains "version" "meshreuse 0.1.0 (git "
json_ok() {  # json_ok NAME : the last output parses as JSON (stderr's lines, warnings, apart)
  if /usr/bin/python3 -c 'import json,sys; json.loads("".join(l for l in open(sys.argv[1]) if not l.startswith("meshreuse: ")))' "$tmp/out" 2>/dev/null; then
    pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1: not JSON"; sed 's/^/    /' "$tmp/out" | head; fi
}
check "compare json" 0 "$bin" compare "$data/two_interior.node" --orderings ori,bfs --repeat 3 --json --quiet
json_ok "compare json"
check "compare json csv" 2 "$bin" compare "$data/two_interior.node" --json --csv
contains "compare json csv" "--json and --csv exclude each other"
check "smooth json" 0 "$bin" smooth "$data/two_interior.node" --json --quiet
json_ok "smooth json"
check "orderings json" 0 "$bin" orderings --json
json_ok "orderings json"
check "orderings file last" 0 "$bin" orderings
if tail -n 1 "$tmp/out" | grep -q "^file:PATH"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL orderings: file:PATH is not last"; fi
check "orderings check" 2 "$bin" orderings --check ori,frob
contains "orderings check" "frob"
check "analyze json null" 0 bash -c "printf '5\n5\n' | '$bin' analyze - --format text --json --quiet"
json_ok "analyze json null"
contains "analyze json null" '"per_vertex_sweep":null'
touch "$tmp/afile"
check "compare out under a file" 2 "$bin" compare "$data/two_interior.node" --out "$tmp/afile/sub" --repeat 3 --quiet
contains "compare out under a file" "is not a folder"
check "validate out under a file" 2 "$bin" validate "$data/two_interior.node" --out "$tmp/afile/sub" --quiet
check "analyze out under a file" 2 "$bin" analyze "$data/two_interior.node" --out "$tmp/afile/sub" --quiet
mkdir -p "$tmp/full" && touch "$tmp/full/x"
check "report out not empty" 2 "$bin" report "$data/two_interior.node" --out "$tmp/full" --quiet
contains "report out not empty" "is not empty"
check "report bad ordering" 2 "$bin" report "$data/two_interior.node" --out "$tmp/rep" --orderings ori,frob --quiet
[[ ! -e $tmp/rep/run.json ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL report bad ordering wrote files"; }
# The many-core simulator and the report's many-core options (issue 21).
check "simulate machine" 0 "$bin" simulate "$data/two_interior.node" --machine westmere-ex --threads 4 --placement scatter --warm --csv --quiet
contains "simulate machine" "memory_remote"
check "simulate machine cores" 2 "$bin" simulate "$data/two_interior.node" --machine westmere-ex --threads 33 --quiet
contains "simulate machine cores" "has 32 cores"
check "simulate machine unknown" 2 "$bin" simulate "$data/two_interior.node" --machine nosuch --quiet
contains "simulate machine unknown" "neither westmere-ex (alias westmere) nor a machine file"
check "analyze without input" 2 "$bin" analyze
contains "analyze without input: named as the usage shows it" "no INPUT given: meshreuse analyze INPUT..."
"$bin" trace "$data/plate41.msh" --ordering bfs -k 2 -t 2 -o "$tmp/t2.trace" --quiet &>/dev/null
check "simulate trace interleave" 2 "$bin" simulate "$tmp/t2.trace" --machine westmere-ex --threads 2 --interleave access --quiet
contains "simulate trace interleave: refused by name" "t2.trace is a trace file, whose streams follow one another"
check "simulate trace serial" 0 "$bin" simulate "$tmp/t2.trace" --machine westmere-ex --threads 2 --quiet
contains "simulate trace serial: said" "interleave serial"
check "simulate machine prefix" 2 "$bin" simulate "$data/two_interior.node" --machine wes --quiet
contains "simulate machine prefix: refused, the alias listed" "'wes' is neither westmere-ex (alias westmere)"
check "simulate machine alias" 0 "$bin" simulate "$data/two_interior.node" --machine westmere --threads 2 --out "$tmp/alias" --quiet
grep -q '"machine": "westmere-ex"' "$tmp/alias/run.json" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL the alias westmere not recorded as westmere-ex"; grep machine "$tmp/alias/run.json"; }
check "simulate help lists the alias" 0 "$bin" simulate --help
contains "simulate help lists the alias" "westmere-ex (alias westmere)"
printf 'name x\nsockets 2\ncores 2\nline 64\nmemory 1 2\nprivate L1=32K/8@4\nfrob 3\n' >"$tmp/bad.machine"
check "simulate machine file" 2 "$bin" simulate "$data/two_interior.node" --machine "$tmp/bad.machine" --quiet
contains "simulate machine file" "bad.machine:7: unknown key 'frob'"
check "simulate placement alone" 2 "$bin" simulate "$data/two_interior.node" --placement scatter --quiet
contains "simulate placement alone" "--placement needs --machine"
check "simulate machine and cache" 2 "$bin" simulate "$data/two_interior.node" --machine westmere-ex --cache L1=1K/2 --quiet
check "report machine threads" 2 "$bin" report "$data/two_interior.node" --out "$tmp/rep" --machine-threads 1,64 --quiet
contains "report machine threads" "--machine-threads 64: the machine westmere-ex has 32 cores"
check "report prefetch" 2 "$bin" report "$data/two_interior.node" --out "$tmp/rep" --prefetch L9 --quiet
contains "report prefetch" "no level 'L9'"
[[ ! -e $tmp/rep ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL report with a bad machine option made its folder"; }
check "report no machine" 0 "$bin" report "$data/two_interior.node" --out "$tmp/rep-nomachine" --machine none --no-timing --figure1-mesh none --profile-mesh none --quiet
[[ ! -e $tmp/rep-nomachine/tables/machine_misses.csv && ! -e $tmp/rep-nomachine/data/machine.csv ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL report --machine none wrote the many-core part"; }
# After --no-timing the results README says nothing was timed (not "3 rounds after a warm-up"),
# and report draws its figures itself (issue 39), or with --no-figures leaves them to the script.
if grep -q "nothing was timed" "$tmp/rep-nomachine/README.md" && ! grep -q "rounds after a warm-up" "$tmp/rep-nomachine/README.md"; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL report --no-timing README"; grep -n "Made by" "$tmp/rep-nomachine/README.md"; fi
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  [[ -s $tmp/rep-nomachine/figures/meshes.png ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL report drew no figures"; ls "$tmp/rep-nomachine/figures"; }
fi
check "report --no-figures" 0 "$bin" report "$data/two_interior.node" --out "$tmp/rep-nofig" --machine none --no-timing --figure1-mesh none --profile-mesh none --no-figures --quiet
[[ -z $(ls "$tmp/rep-nofig/figures") ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL report --no-figures drew figures"; }
# An output prefix that names no file would write the hidden ".node", ".ele" (and ".perm").
for o in "" "$tmp/dir-prefix/" ".node"; do
  check "reorder prefix '$o'" 2 "$bin" reorder "$data/two_interior.node" --ordering bfs -o "$o" --quiet
  contains "reorder prefix '$o'" "the prefix names no file"
  check "convert prefix '$o'" 2 "$bin" mesh convert "$data/two_interior.node" -o "$o" --quiet
done
check "generate prefix" 2 "$bin" mesh generate --shape lake -o "$tmp/dir-prefix/" --quiet
contains "generate prefix" "the prefix names no file"
[[ ! -e .node && ! -e .ele && ! -e .perm && ! -e $tmp/dir-prefix ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL a prefix naming no file wrote something"; }
# A trace without sweeps has no profile: said, no empty file.
check "profile without sweeps" 0 bash -c "printf '1\n2\n1\n' | '$bin' analyze - --format text --out '$tmp/nosweep' --quiet"
contains "profile without sweeps" "no profile written: the input has no sweeps"
[[ ! -e $tmp/nosweep/profile.csv && -s $tmp/nosweep/analyze.csv ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL profile without sweeps: profile.csv written"; }
# per_vertex_sweep of a thread is per the vertices it moves: two interior vertices, one per thread.
check "per thread" 0 "$bin" analyze "$data/two_interior.node" --threads 2 --granularity element --csv --quiet
/usr/bin/python3 - "$tmp/out" <<'PY' && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL per_vertex_sweep per thread"; }
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, rows
for r in rows:  # each thread moves one vertex in one sweep
    assert float(r["per_vertex_sweep"]) == float(r["accesses"]), r
PY

# Outputs (issue 20): a FIFO written in place and still a FIFO, a symlink's target written and the
# link kept, an empty or over-long name and an output that is an input refused (exit 2).
mkfifo "$tmp/fifo"
(cat "$tmp/fifo" >"$tmp/from_fifo") &
check "trace into a fifo" 0 "$bin" trace "$data/two_interior.node" -o "$tmp/fifo" --quiet
wait
[[ -p $tmp/fifo && -s $tmp/from_fifo ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL trace into a fifo: not a fifo or nothing read"; }
touch "$tmp/target.trace" && ln -s target.trace "$tmp/link.trace"
check "trace into a link" 0 "$bin" trace "$data/two_interior.node" -o "$tmp/link.trace" --quiet
[[ -L $tmp/link.trace && -s $tmp/target.trace ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL trace into a link: link replaced or target empty"; }
check "empty output name" 2 "$bin" trace "$data/two_interior.node" -o ''
contains "empty output name" "empty"
check "long output name" 2 "$bin" trace "$data/two_interior.node" -o "$tmp/$(printf 'n%.0s' {1..300})"
contains "long output name" "too long"
before=$(cat "$data/two_interior.node" "$data/two_interior.ele" | md5sum)
check "output is the input" 2 "$bin" mesh convert "$data/two_interior.node" -o "$data/two_interior"
[[ $(cat "$data/two_interior.node" "$data/two_interior.ele" | md5sum) == "$before" ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL output is the input: the input changed"; }
# Standard input (issue 20): our trace's magic is recognised without --format, pzstd's frames
# read (size unknown: the count is checked as records come), 256 streams under a 4 GB limit.
"$bin" trace "$data/two_interior.node" -o "$tmp/stdin.trace" --quiet
"$bin" analyze "$tmp/stdin.trace" --csv --quiet | cut -d, -f2- >"$tmp/by_name.csv"
check "trace on stdin" 0 bash -c "cat '$tmp/stdin.trace' | '$bin' analyze - --csv --quiet"
cut -d, -f2- "$tmp/out" | diff -q - "$tmp/by_name.csv" >/dev/null && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL trace on stdin: not the file's numbers"; }
if command -v pzstd >/dev/null; then
  pzstd -q -f "$tmp/stdin.trace" -o "$tmp/p.trace.zst"
  check "pzstd trace" 0 "$bin" analyze "$tmp/p.trace.zst" --csv --quiet
  cut -d, -f2- "$tmp/out" | diff -q - "$tmp/by_name.csv" >/dev/null && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL pzstd trace: not the file's numbers"; }
fi
check "trace on stdin, extra bytes" 2 bash -c "(cat '$tmp/stdin.trace'; echo x) | '$bin' analyze - --quiet"
contains "trace on stdin, extra bytes" "more bytes after the 165 records"
"$bin" trace "$data/two_interior.node" -t 256 -o "$tmp/t256.trace" --quiet
# (not under AddressSanitizer, whose shadow memory alone needs terabytes of address space)
ldd "$bin" 2>/dev/null | grep -q libasan || check "256 streams in 4 GB" 0 bash -c "ulimit -v 4000000; '$bin' analyze '$tmp/t256.trace' -t 16 --quiet && '$bin' simulate '$tmp/t256.trace' --quiet && '$bin' smooth '$data/two_interior.node' -t 256 --max-iters 2 --quiet"

# simulate --machine answers the question (issue 39): with thread and placement lists its summary
# holds Speedup(p) and Gain(p) per ordering and placement, equal to the report's predicted_speedup
# for the same runs (one mesh, two sweeps, the last counted), and a sentence per ordering.
check "simulate machine summary" 0 "$bin" simulate "$data/plate41.msh" --machine westmere-ex \
  --orderings ori,bfs,rdr --threads 1,4 --placement compact,scatter -k 2 --out "$tmp/msum" --quiet
contains "simulate machine summary" "rdr at 4 thread(s), scatter"
contains "simulate machine summary" "speedup_at_low_latency"
check "report predicted" 0 "$bin" report "$data/plate41.msh" --no-timing --machine-threads 1,4 \
  --orderings ori,bfs,rdr --out "$tmp/mrep" --quiet
check "summary equals the report" 0 /usr/bin/python3 - "$tmp/mrep/tables/predicted_speedup.csv" "$tmp/msum/summary.csv" <<'PY'
import csv, sys
rep = list(csv.DictReader(open(sys.argv[1])))
sim = {(r["ordering"], r["placement"], r["threads"]): r for r in csv.DictReader(open(sys.argv[2]))}
cols = [f"{q}_at_{e}_latency" for q in ("speedup", "self_speedup", "gain_vs_ori_pct", "gain_vs_bfs_pct")
        for e in ("low", "high")]
n = 0
for r in rep:
    k = (r["ordering"], r["placement"], r["threads"])
    if k not in sim:
        assert r["threads"] == "1", k  # one thread: the first placement only
        continue
    for c in cols:
        assert r[c] == sim[k][c], (k, c, r[c], sim[k][c])
    n += 1
assert n == 9, n  # 3 orderings x (1 thread + 2 placements at 4)
PY
# Speedups measured elsewhere (report --measured compare.csv): a thread count the prediction lacks
# gets a row of its own; each cell is the mean over the file's meshes of its speedup_vs_ori1.
check "compare elsewhere" 0 "$bin" compare "$data/plate41.msh" "$data/two_interior.node" --orderings ori,bfs,rdr --threads 1,2 --repeat 3 --out "$tmp/elsewhere" --quiet
check "report --measured" 0 "$bin" report "$data/plate41.msh" --no-timing --machine-threads 1,4 \
  --orderings ori,bfs,rdr --measured "$tmp/elsewhere/compare.csv" --figure1-mesh none --profile-mesh none --out "$tmp/mrep2" --quiet
check "measured elsewhere in the table" 0 /usr/bin/python3 - "$tmp/elsewhere/compare.csv" "$tmp/mrep2/tables/predicted_speedup.csv" "$tmp/mrep2/README.md" <<'PY'
import csv, sys
from collections import defaultdict
got = defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    if r["speedup_vs_ori1"]:
        got[(r["ordering"], r["threads"])].append(float(r["speedup_vs_ori1"]))
rows = {(r["ordering"], r["placement"], r["threads"]): r for r in csv.DictReader(open(sys.argv[2]))}
for (o, p), v in got.items():
    r = rows[(o, "compact", p)]
    assert abs(float(r["measured_elsewhere"]) - sum(v) / len(v)) <= 0.006, (o, p, r["measured_elsewhere"], v)
    assert rows.get((o, "scatter", p), {}).get("measured_elsewhere", "") == ""
assert rows[("rdr", "compact", "2")]["speedup_at_low_latency"] == ""  # not simulated at 2
assert "measured_elsewhere: Speedup(p) timed on" in open(sys.argv[3]).read()
PY
printf 'mesh,ordering\nm,ori\n' >"$tmp/notcompare.csv"
check "report --measured, not a compare.csv" 2 "$bin" report "$data/plate41.msh" --no-timing --measured "$tmp/notcompare.csv" --out "$tmp/mrep3" --quiet
contains "report --measured, not a compare.csv: named" "notcompare.csv:1: no column threads"
[[ ! -e $tmp/mrep3 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL report --measured: refused after making its folder"; }
check "one thread count without a machine" 2 "$bin" simulate "$data/plate41.msh" --threads 1,4 --quiet
contains "one thread count without a machine" "--threads and --placement take one value without --machine"

# --kernel (core/kernels/): every command that sweeps takes it; what a kernel cannot do is refused
# by name before any work.
check "kernels" 0 "$bin" kernels
contains "kernels" "smart-laplacian"
check "unknown kernel" 2 "$bin" smooth "$data/plate41.msh" --kernel lapalcian
contains "unknown kernel" "unknown kernel 'lapalcian' (known: laplacian, smart-laplacian"
check "kernel without jacobi" 2 "$bin" analyze "$data/plate41.msh" --kernel untangle --mode jacobi --quiet
contains "kernel without jacobi" "--kernel untangle has no Jacobi form"
check "kernel without threads" 2 "$bin" compare "$data/plate41.msh" --kernel assembly --threads 1,2 --quiet
contains "kernel without threads" "--kernel assembly runs on one thread only"
check "kernel without ranks" 2 "$bin" simulate "$data/plate41.msh" --kernel spmv --ranks 2 --quiet
contains "kernel without ranks" "no --kernel spmv with it"
check "kernel moving nothing" 2 "$bin" smooth "$data/plate41.msh" --kernel spmv -o "$tmp/k.vtu" --quiet
[[ ! -e $tmp/k.vtu ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL kernel moving nothing: wrote"; }
for k in smart-laplacian local-opt untangle edge-swap assembly spmv; do
  check "smooth --kernel $k" 0 "$bin" smooth "$data/plate41.msh" --kernel "$k" --max-iters 3 --quiet
  check "compare --kernel $k" 0 "$bin" compare "$data/plate41.msh" --kernel "$k" --orderings ori,bfs,rdr,grid-wave --repeat 3 --max-iters 3 --csv --quiet
  check "analyze --kernel $k" 0 "$bin" analyze "$data/plate41.msh" --kernel "$k" --orderings ori,rdr -k 2 --csv --quiet
  check "simulate --kernel $k" 0 "$bin" simulate "$data/plate41.msh" --kernel "$k" --orderings rdr -k 2 --cache L1=256/2,L2=1K/4 --csv --quiet
done
check "kernel chunk of a mesh" 2 "$bin" analyze "$data/plate41.msh" --kernel spmv --chunk 0/2 --summary-out "$tmp/kchunk" --quiet
contains "kernel chunk of a mesh" "for --kernel spmv, write its trace"
# A kernel's trace holds what analyze streams: the same numbers from the file as from the mesh.
check "trace --kernel" 0 "$bin" trace "$data/plate41.msh" --kernel assembly --ordering rdr -k 2 -o "$tmp/asm.trace" --quiet
"$bin" analyze "$tmp/asm.trace" --csv --quiet | cut -d, -f2- >"$tmp/asm_file.csv"
"$bin" analyze "$data/plate41.msh" --kernel assembly --orderings rdr -k 2 --csv --quiet | cut -d, -f2- >"$tmp/asm_mesh.csv"
cmp -s "$tmp/asm_file.csv" "$tmp/asm_mesh.csv" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL trace --kernel: the file's analysis differs from the mesh's"; diff "$tmp/asm_file.csv" "$tmp/asm_mesh.csv" | head -5; }

echo "cli commands: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
