#!/usr/bin/env bash
# meshreuse smooth-ranks: the distributed smoother's P ranks as threads of one process
# (core/ranks/thread_communicator.h), compared byte for byte with the serial smoother, as tests/mpi/mpi_smooth.sh
# does for MPI ranks (this one runs where MPI is not built):
#   --ranks 1            == meshreuse smooth (ordered Gauss-Seidel and Jacobi);
#   --ranks P, ordered   == meshreuse smooth --visit-order PI (PI from --pi-out), Hilbert and METIS
#                           partitions, METIS inside the parts too (METIS keeps global state: its
#                           calls from rank threads must not interleave), repeated: the same bytes;
#   --ranks P, jacobi    == meshreuse smooth --mode jacobi;
# `analyze MESH --ranks P`, `simulate MESH --ranks P` and `trace MESH --ranks P` (per-rank
# locality: one stream per rank's part; a rank's trace file analyses as its row);
# the cut-vertex placements (first, interleaved) against their own pi;
# -o X.pvtu (a piece per rank, read back by meshio);
# a busy machine warned of (CPU hogs beside the sweeps);
# and refusals: --ranks 0, --ranks without a value, more ranks than vertices, a missing mesh.
# Usage: smooth_ranks.sh MESHREUSE DATA
set -u
bin=$1 data=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib.sh"
equal() {  # equal NAME A B : two written meshes identical, A not empty
  if [[ -s "$2" ]] && cmp -s "$2" "$3"; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL $1: $2 and $3 differ"; sed 's/^/    /' "$tmp/out" | head -20; fi
}

check "refine" 0 "$bin" mesh refine "$data/plate41.msh" --levels 2 --jitter 0.3 -o "$tmp/fine" --quiet
fine=$tmp/fine.node

for mode in ordered jacobi; do
  serial_mode=()
  [[ $mode == jacobi ]] && serial_mode=(--mode jacobi)
  check "serial $mode" 0 "$bin" smooth "$fine" "${serial_mode[@]}" --max-iters 5 --tol -1 -o "$tmp/serial.vtk" --quiet
  check "ranks 1 $mode" 0 "$bin" smooth-ranks "$fine" --ranks 1 --mode $mode --max-iters 5 --tol -1 -o "$tmp/r1.vtk" --quiet
  equal "ranks 1 == serial ($mode)" "$tmp/serial.vtk" "$tmp/r1.vtk"
done
check "jacobi ranks 5" 0 "$bin" smooth-ranks "$fine" --ranks 5 --mode jacobi --partition metis --max-iters 5 --tol -1 -o "$tmp/r5.vtk" --quiet
equal "jacobi ranks 5 == serial jacobi" "$tmp/serial.vtk" "$tmp/r5.vtk"

for ranks in 2 3 6; do
  for layout in "--partition hilbert --ordering ori" "--partition metis --ordering metis" \
                "--partition hilbert --ordering grid-wave"; do
    for k in 1 2; do
      check "ranks $ranks $layout ($k)" 0 "$bin" smooth-ranks "$fine" --ranks $ranks $layout --max-iters 4 --tol -1 \
        -o "$tmp/r$k.vtk" --pi-out "$tmp/pi$k" --out "$tmp/d$k" --quiet
    done
    equal "ranks $ranks $layout: repeatable" "$tmp/r1.vtk" "$tmp/r2.vtk"
    check "serial along pi" 0 "$bin" smooth "$fine" --visit-order "$tmp/pi1" --max-iters 4 --tol -1 -o "$tmp/along.vtk" --quiet
    equal "ranks $ranks $layout == serial along pi" "$tmp/along.vtk" "$tmp/r1.vtk"
    rows=$(($(wc -l <"$tmp/d1/ranks.csv") - 1))
    if [[ $rows -eq $ranks ]]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL ranks.csv has $rows rows for $ranks ranks"; fi
  done
done
# ParaView's partitioned output (issue 39): -o X.pvtu writes one .vtu piece per rank; read by
# meshio, the pieces' owned points and cells are the serial .vtu's, each once, and each piece's ghost
# cells exactly the serial cells it touches and does not own (tests/scripts/check_vtu.py).
check "pvtu ranks 3" 0 "$bin" smooth-ranks "$fine" --ranks 3 --partition hilbert --ordering grid-wave --max-iters 4 --tol -1 -o "$tmp/r3.pvtu" --pi-out "$tmp/pi3" --quiet
check "pvtu: serial along pi" 0 "$bin" smooth "$fine" --visit-order "$tmp/pi3" --max-iters 4 --tol -1 -o "$tmp/along.vtu" --quiet
for r in 0 1 2; do [[ -s $tmp/r3_$r.vtu ]] || { fail=$((fail + 1)); echo "FAIL pvtu: no piece $r"; }; done
check "pvtu ranks 3 == serial (meshio)" 0 /usr/bin/python3 "$here/../scripts/check_vtu.py" pieces "$tmp/along.vtu" "$tmp/r3.pvtu"
check "jacobi serial .vtu" 0 "$bin" smooth "$fine" --mode jacobi --max-iters 3 --tol -1 -o "$tmp/sj.vtu" --quiet
check "pvtu jacobi ranks 4 metis" 0 "$bin" smooth-ranks "$fine" --ranks 4 --partition metis --mode jacobi --max-iters 3 --tol -1 -o "$tmp/j4.pvtu" --quiet
check "pvtu jacobi ranks 4 == serial (meshio)" 0 /usr/bin/python3 "$here/../scripts/check_vtu.py" pieces "$tmp/sj.vtu" "$tmp/j4.pvtu"
check "pvtu refused by the serial smoother" 2 "$bin" smooth "$fine" -o "$tmp/s.pvtu" --quiet
contains "pvtu refused: said" "written by the distributed smoother"
[[ ! -e $tmp/s.pvtu ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL pvtu refused: a file was written"; }

# The cut-vertex placements: each equals the serial sweep along the pi it writes.
for placement in first interleaved; do
  check "ranks 3 cut $placement" 0 "$bin" smooth-ranks "$fine" --ranks 3 --partition metis --cut-placement $placement \
    --max-iters 4 --tol -1 -o "$tmp/r1.vtk" --pi-out "$tmp/pi1" --quiet
  contains "pi names the placement" "cut vertices $placement"
  check "serial along pi ($placement)" 0 "$bin" smooth "$fine" --visit-order "$tmp/pi1" --max-iters 4 --tol -1 -o "$tmp/along.vtk" --quiet
  equal "ranks 3 cut $placement == serial along pi" "$tmp/along.vtk" "$tmp/r1.vtk"
done
check "bad placement" 2 "$bin" smooth-ranks "$fine" --ranks 2 --cut-placement middle
contains "bad placement: said" "--cut-placement"
check "placement without ranks" 2 "$bin" analyze "$fine" --cut-placement first
check "analyze placement" 0 "$bin" analyze "$fine" --ranks 2 --cut-placement interleaved --quiet

# stdout holds the table only, whatever METIS does meanwhile on other ranks' threads
check "stdout" 0 "$bin" smooth-ranks "$fine" --ranks 4 --partition metis --ordering metis --max-iters 2 --quiet
contains "stdout: sweep table" "     2    0."
contains "stdout: rank table" "rss_bytes_per_owned"

# Per-rank locality: `analyze MESH --ranks P` gives one row per rank, ordering and granularity, and
# the moves of the ranks add up to the whole mesh's interior moves.
check "analyze --ranks" 0 "$bin" analyze "$fine" --ranks 3 --orderings ori,random -k 2 --csv --quiet
rows=$(grep -c '\[rank [0-2] of 3\]' "$tmp/out")
if [[ $rows -eq 12 ]]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL analyze --ranks: $rows rows, expected 12"; cat "$tmp/out"; fi
check "analyze --ranks metis" 0 "$bin" analyze "$fine" --ranks 2 --partition metis --csv --quiet
check "analyze --ranks of a trace" 2 "$bin" analyze "$tmp/r1.vtk" --ranks 2
check "analyze --ranks with threads" 2 "$bin" analyze "$fine" --ranks 2 --threads 2
contains "analyze --ranks with threads: said" "--ranks"
check "analyze bad partition" 2 "$bin" analyze "$fine" --ranks 2 --partition chaco
contains "analyze bad partition: said" "--partition must be hilbert, metis, scotch, ranges, gmsh or file:PATH (meshreuse-mpi smooth also ptscotch)"
# A mesh file read in ranges by thread ranks (ghosts through the threads' mailboxes): the serial
# sweep along pi, and -o FILE.mrm written by every rank equal to the serial smoother's file.
check "mrm" 0 "$bin" mesh convert "$fine" -o "$tmp/fine.mrm" --quiet
for r in 1 3; do
  check "mrm as $r threads" 0 "$bin" smooth-ranks "$tmp/fine.mrm" --ranks $r --max-iters 3 --tol -1 \
    -o "$tmp/rt.mrm" --pi-out "$tmp/rtpi" --quiet
  contains "mrm as $r threads: ranges" "ranges partition"
  check "mrm serial along pi" 0 "$bin" smooth "$tmp/fine.mrm" --visit-order "$tmp/rtpi" --max-iters 3 --tol -1 \
    -o "$tmp/rs.mrm" --quiet
  if [[ -s $tmp/rt.mrm ]] && cmp -s "$tmp/rt.mrm" "$tmp/rs.mrm"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL mrm as $r threads != serial along pi"; fi
done
# A repeated corner (tests/data/broken) refused by the ranks that read the triangle, by name.
check "mrm repeated corner as 2 threads" 2 "$bin" smooth-ranks "$data/broken/mrm_repeated_corner.mrm" --ranks 2 --quiet
contains "mrm repeated corner as 2 threads" "triangle 0: degenerate triangle: vertex 0 is used twice"

# A mesh file is a mesh to the analyzer, the simulator and the tracer (found by its name): the same
# tables as the same mesh in text.
check "mrm back to text" 0 "$bin" mesh convert "$tmp/fine.mrm" -o "$tmp/back" --quiet
check "mrm analysed" 0 "$bin" analyze "$tmp/fine.mrm" -k 2 --csv --quiet
cut -d, -f2- "$tmp/out" >"$tmp/a.mrm.csv"
check "text analysed" 0 "$bin" analyze "$tmp/back.node" -k 2 --csv --quiet
cut -d, -f2- "$tmp/out" >"$tmp/a.node.csv"
if [[ $(wc -l <"$tmp/a.mrm.csv") -gt 2 ]] && cmp -s "$tmp/a.mrm.csv" "$tmp/a.node.csv"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL mrm analysed != text analysed"; fi
check "mrm simulated" 0 "$bin" simulate "$tmp/fine.mrm" -k 1 --quiet
check "mrm traced per rank" 0 "$bin" trace "$tmp/fine.mrm" --ranks 2 -k 1 -o "$tmp/mt" --quiet

# Gmsh's split set as ranks: the unsplit file along pi; analysed per rank with Gmsh's parts.
check "gmsh split as threads" 0 "$bin" smooth-ranks "$data/plate_split_3.msh" --ranks 3 --partition gmsh \
  --max-iters 4 --tol -1 -o "$tmp/gs.vtk" --pi-out "$tmp/gspi" --quiet
check "unsplit along pi" 0 "$bin" smooth "$data/plate41.msh" --visit-order "$tmp/gspi" --max-iters 4 --tol -1 \
  -o "$tmp/gsa.vtk" --quiet
if cmp -s "$tmp/gs.vtk" "$tmp/gsa.vtk"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL gmsh split != unsplit along pi"; fi
check "gmsh split analysed per rank" 0 "$bin" analyze "$data/plate_split_1.msh" --ranks 3 --partition gmsh --csv --quiet
[[ $(grep -o "rank [0-2] of 3" "$tmp/out" | sort -u | wc -l) -eq 3 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL gmsh split: 3 rank rows"; head "$tmp/out"; }
check "gmsh split partition stats" 0 "$bin" mesh partition "$data/plate_split_2.msh" --parts 3 --method gmsh --quiet
contains "gmsh split partition stats" "vertices 995, parts 3 (gmsh)"

# ... and simulated: one row per rank and level; the L1 accesses of each rank are its analysed
# line accesses (the same stream into two consumers).
check "simulate --ranks" 0 "$bin" simulate "$fine" --ranks 3 --orderings bfs -k 2 --csv --quiet
rows=$(grep -c '\[rank [0-2] of 3\],bfs,0,all,L' "$tmp/out")
if [[ $rows -eq 9 ]]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL simulate --ranks: $rows rows, expected 9"; cat "$tmp/out"; fi
awk -F, '$5 == "L1" {print $1, $10}' "$tmp/out" | sort >"$tmp/sim.acc"
check "analyze --ranks bfs" 0 "$bin" analyze "$fine" --ranks 3 --orderings bfs -k 2 --csv --quiet
cp "$tmp/out" "$tmp/an.rows"
awk -F, '$4 == "line" {print $1, $5}' "$tmp/out" | sort >"$tmp/an.acc"
if [[ -s $tmp/sim.acc ]] && cmp -s "$tmp/sim.acc" "$tmp/an.acc"; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL simulate --ranks accesses != analyze --ranks line accesses"; paste "$tmp/sim.acc" "$tmp/an.acc"; fi
check "simulate --ranks with a machine" 2 "$bin" simulate "$fine" --ranks 2 --machine westmere-ex

# ... and written: one trace per rank whose analysis is the rank's row of analyze --ranks.
check "trace --ranks" 0 "$bin" trace "$fine" --ranks 3 --ordering bfs -k 2 -o "$tmp/rt" --quiet
for r in 0 1 2; do
  "$bin" analyze "$tmp/rt.rank$r" --csv --quiet | tail -n +2 | cut -d, -f2- >"$tmp/file.rows"
  awk -F, -v r="$r" 'index($1, "[rank " r " of 3]")' "$tmp/an.rows" | cut -d, -f2- >"$tmp/ranks.rows"
  if [[ -s $tmp/file.rows ]] && cmp -s "$tmp/file.rows" "$tmp/ranks.rows"; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL trace --ranks: rank $r's file analyses differently"; diff "$tmp/file.rows" "$tmp/ranks.rows" | head; fi
done
check "trace --ranks --compress" 2 "$bin" trace "$fine" --ranks 2 --compress -o "$tmp/rz"
check "trace --partition without --ranks" 2 "$bin" trace "$fine" --partition metis -o "$tmp/rz"

# A busy machine is said (issue 39 F6): with two CPU hogs per core the one rank's work spans get
# about a third of a core, below the 90% CPU/wall bound, whatever the machine's size.
"$bin" mesh refine "$data/plate41.msh" --levels 4 -o "$tmp/p4" --quiet &>/dev/null
hogs=()
for ((h = 0; h < 2 * $(nproc); h++)); do timeout 60 sh -c 'while :; do :; done' & hogs+=($!); done
check "busy machine" 0 "$bin" smooth-ranks "$tmp/p4.node" --ranks 1 --mode jacobi --max-iters 20 --tol -1 --quiet --out "$tmp/busy"
kill "${hogs[@]}" 2>/dev/null; wait "${hogs[@]}" 2>/dev/null
contains "busy machine: warned" "warning: timings taken on a busy machine"
contains "busy machine: CPU/wall named" "of their wall time on a core"
if grep -q '"busy": true' "$tmp/busy/run.json"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL busy machine: run.json lacks noise.busy"; fi

check "ranks 0" 2 "$bin" smooth-ranks "$fine" --ranks 0
contains "ranks 0 named" "--ranks"
check "ranks without a value" 2 "$bin" smooth-ranks "$fine" --ranks
check "ranks not given" 2 "$bin" smooth-ranks "$fine"
contains "ranks not given: said" "--ranks P is required"
check "more ranks than vertices" 2 "$bin" smooth-ranks "$data/plate41.msh" --ranks 4000 --quiet
contains "more ranks than vertices: said" "at most one rank per vertex"
check "missing mesh" 2 "$bin" smooth-ranks "$tmp/none.node" --ranks 3 --quiet
contains "missing mesh named" "none.node"
check "help" 0 "$bin" smooth-ranks --help
contains "help" "as P threads"

echo "smooth_ranks.sh: $pass passed, $fail failed"
((fail == 0))
