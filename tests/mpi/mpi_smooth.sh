#!/usr/bin/env bash
# meshreuse-mpi smooth (reports/distributed_smooth.h) at -np 1..4 against the serial smoother, by
# comparing the written meshes byte for byte:
#   -np 1, ordered, ori       == meshreuse smooth (today's smoother) on a Gmsh file and a refined mesh;
#   -np P, ordered            == meshreuse smooth --visit-order PI, PI written by the run (--pi-out),
#                                Hilbert, METIS, Scotch and PT-Scotch partitions (PT-Scotch's
#                                computed by the job, deterministic), orderings inside the parts;
#   --cut-placement first and interleaved at -np 3 == the serial sweep along their own PI;
#   Gmsh's split set (plate.geo in 3) with --partition gmsh == the unsplit file along PI;
#   -np P, jacobi             == meshreuse smooth --mode jacobi, and the same quality and sweep
#                                count for every P (stopped by --tol);
# and that the comparison can fail (ordered at -np 2 differs from the storage-order sweep).
# The distributed mesh file (FILE.mrm) read in ranges: equal to the whole read and to the serial
# sweep along pi at -np 1..4; -o X.pvtu at -np 3 (a piece per rank, read back by meshio);
# damaged, truncated and foreign files refused on every rank.
# meshreuse-mpi refine at -np 1..4 == one process's file byte for byte, smoothed along pi; refused
# outputs and inputs. A scale smoke test at -np 2 on about 10^6 vertices (refined, no Triangle needed) with its memory
# per rank checked (whole read and ranges); a rank killed mid-run ends the job naming the rank; bad input exits 2 naming
# the file on every rank; never a hang (each run under `timeout`).
# Usage: mpi_smooth.sh MESHREUSE MESHREUSE_MPI MPIEXEC DATA
set -u
bin=$1 mpi=$2 mpiexec=$3 data=$4
source "$(dirname "$0")/../cli/lib.sh"
scratch
mpi_setup "$mpiexec"
equal() {  # equal NAME A B : two written meshes identical, A not empty
  if [[ -s "$2" ]] && cmp -s "$2" "$3"; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "FAIL $1: $2 and $3 differ"; sed 's/^/    /' "$tmp/out" | head -20; fi
}

plate=$data/plate41.msh
# PT-Scotch (--partition ptscotch) where meshreuse-mpi was built with it (libptscotch-dev).
layouts=("--partition hilbert --ordering ori" "--partition metis --ordering bfs"
         "--partition hilbert --ordering grid-wave" "--partition scotch --ordering ori")
ptscotch=1
if run 1 "$mpi" smooth "$plate" --partition ptscotch --max-iters 1 --quiet 2>&1 | grep -q "built with libptscotch-dev"; then
  echo "SKIP --partition ptscotch: meshreuse-mpi was built without PT-Scotch"; ptscotch=0
else
  layouts+=("--partition ptscotch --ordering ori")
fi
check "refine" 0 "$bin" mesh refine "$plate" --levels 2 --jitter 0.3 -o "$tmp/fine" --quiet
fine=$tmp/fine.node  # 15,000 vertices

for mesh in "$plate" "$fine"; do
  n=$(basename "$mesh")
  check "serial $n" 0 "$bin" smooth "$mesh" --max-iters 6 --tol -1 -o "$tmp/serial.vtk" --quiet
  check "np 1 $n" 0 run 1 "$mpi" smooth "$mesh" --max-iters 6 --tol -1 -o "$tmp/np1.vtk" --quiet
  equal "np 1 == serial ($n)" "$tmp/serial.vtk" "$tmp/np1.vtk"
  for np in 2 3 4; do
    for layout in "${layouts[@]}"; do
      check "np $np $layout $n" 0 run $np "$mpi" smooth "$mesh" $layout --max-iters 6 --tol -1 \
        -o "$tmp/np.vtk" --pi-out "$tmp/pi" --quiet
      check "serial along pi" 0 "$bin" smooth "$mesh" --visit-order "$tmp/pi" --max-iters 6 \
        --tol -1 -o "$tmp/along.vtk" --quiet
      equal "np $np $layout == serial along pi ($n)" "$tmp/along.vtk" "$tmp/np.vtk"
    done
  done
  # The reference can tell: the storage-order sweep is another order, other bits.
  if cmp -s "$tmp/serial.vtk" "$tmp/np.vtk"; then fail=$((fail + 1)); echo "FAIL ordered np 4 equals the storage-order sweep"; else pass=$((pass + 1)); fi
done

# PT-Scotch's parts are the job's: deterministic (three runs, the same pi and cut), and refused
# where no MPI job can compute them (ranks as threads).
if ((ptscotch)); then
  for k in 1 2 3; do
    check "ptscotch np 3 run $k" 0 run 3 "$mpi" smooth "$fine" --partition ptscotch --max-iters 2 \
      --tol -1 --pi-out "$tmp/pi$k" --quiet
  done
  cmp -s "$tmp/pi1" "$tmp/pi2" && cmp -s "$tmp/pi1" "$tmp/pi3" && pass=$((pass + 1)) || {
    fail=$((fail + 1)); echo "FAIL ptscotch: three runs, different parts"; }
  contains "ptscotch np 3 run 3" "ptscotch partition"
fi
check "ptscotch as threads" 2 "$bin" smooth-ranks "$fine" --ranks 2 --partition ptscotch --quiet
contains "ptscotch as threads" "computed by the ranks of an MPI job together"

# Gmsh's own partition: the split set Gmsh wrote (plate.geo in 3 parts), read and smoothed on 3
# ranks, equals the unsplit file (plate41.msh, the same Gmsh run without -part) along pi.
check "gmsh split np 3" 0 run 3 "$mpi" smooth "$data/plate_split_1.msh" --partition gmsh --max-iters 5 \
  --tol -1 -o "$tmp/np.vtk" --pi-out "$tmp/pi" --quiet
check "unsplit along pi" 0 "$bin" smooth "$plate" --visit-order "$tmp/pi" --max-iters 5 --tol -1 \
  -o "$tmp/along.vtk" --quiet
equal "gmsh split np 3 == unsplit along pi" "$tmp/along.vtk" "$tmp/np.vtk"
check "gmsh split, wrong rank count" 2 run 2 "$mpi" smooth "$data/plate_split_2.msh" --partition gmsh --quiet
contains "gmsh split, wrong rank count" "belongs to a set of 3 parts"

# The cut-vertex placements over MPI: each equals the serial sweep along its pi.
for placement in first interleaved; do
  check "np 3 cut $placement" 0 run 3 "$mpi" smooth "$fine" --cut-placement $placement --max-iters 5 --tol -1 \
    -o "$tmp/np.vtk" --pi-out "$tmp/pi" --quiet
  check "serial along pi ($placement)" 0 "$bin" smooth "$fine" --visit-order "$tmp/pi" --max-iters 5 \
    --tol -1 -o "$tmp/along.vtk" --quiet
  equal "np 3 cut $placement == serial along pi" "$tmp/along.vtk" "$tmp/np.vtk"
done

# Jacobi: the serial Jacobi for every P, stopped by the tolerance at the same sweep with the same
# exact quality.
check "serial jacobi" 0 "$bin" smooth "$fine" --mode jacobi --max-iters 6 --tol -1 -o "$tmp/serial.vtk" --quiet
for np in 1 2 3 4; do
  check "jacobi np $np" 0 run $np "$mpi" smooth "$fine" --mode jacobi --partition metis --max-iters 6 \
    --tol -1 -o "$tmp/np.vtk" --quiet
  equal "jacobi np $np == serial jacobi" "$tmp/serial.vtk" "$tmp/np.vtk"
  check "jacobi np $np to tol" 0 run $np "$mpi" smooth "$fine" --mode jacobi --tol 2e-4 \
    --out "$tmp/j$np" --quiet
  cut -d, -f1-3 "$tmp/j$np/sweeps.csv" >"$tmp/sweeps.$np"  # sweep, exact quality, improvement
  if [[ $np -gt 1 ]] && ! cmp -s "$tmp/sweeps.1" "$tmp/sweeps.$np"; then
    fail=$((fail + 1)); echo "FAIL jacobi np $np: other sweeps or quality"; diff "$tmp/sweeps.1" "$tmp/sweeps.$np" | head; else pass=$((pass + 1)); fi
done
[[ $(wc -l <"$tmp/sweeps.1") -gt 5 && $(wc -l <"$tmp/sweeps.1") -lt 100 ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL jacobi stopped by tol"; }
check "hybrid" 0 run 2 "$mpi" smooth "$fine" --mode hybrid --max-iters 3 --out "$tmp/hyb" --quiet
[[ -s "$tmp/hyb/ranks.csv" && -s "$tmp/hyb/run.json" ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL --out"; }

# The distributed mesh file: each rank reads its range and gets its ghosts from their owners; the
# run equals the whole read with the Hilbert partition (the file is in Hilbert order) and the
# serial sweep along its pi, at every P, ordering and placement; Jacobi equals serial Jacobi.
check "convert to .mrm" 0 "$bin" mesh convert "$fine" -o "$tmp/fine.mrm" --quiet
check "convert back" 0 "$bin" mesh convert "$tmp/fine.mrm" -o "$tmp/fineh" --quiet
for np in 1 2 3 4; do
  for layout in "--ordering ori" "--ordering grid-wave --cut-placement first"; do
    check "mrm np $np $layout" 0 run $np "$mpi" smooth "$tmp/fine.mrm" $layout --max-iters 5 --tol -1 \
      -o "$tmp/np.vtk" --pi-out "$tmp/pi" --quiet
    check "whole read np $np $layout" 0 run $np "$mpi" smooth "$tmp/fineh.node" --partition hilbert \
      $layout --max-iters 5 --tol -1 -o "$tmp/whole.vtk" --pi-out "$tmp/piw" --quiet
    equal "mrm np $np $layout == whole read" "$tmp/whole.vtk" "$tmp/np.vtk"
    tail -n +2 "$tmp/pi" >"$tmp/pi.body"
    tail -n +2 "$tmp/piw" >"$tmp/piw.body"
    equal "mrm np $np $layout: same pi" "$tmp/piw.body" "$tmp/pi.body"
    check "serial along pi (mrm)" 0 "$bin" smooth "$tmp/fine.mrm" --visit-order "$tmp/pi" --max-iters 5 \
      --tol -1 -o "$tmp/along.vtk" --quiet
    equal "mrm np $np $layout == serial along pi" "$tmp/along.vtk" "$tmp/np.vtk"
  done
done
check "serial jacobi (mrm)" 0 "$bin" smooth "$tmp/fine.mrm" --mode jacobi --max-iters 4 --tol -1 -o "$tmp/serial.vtk" --quiet
check "mrm jacobi np 3" 0 run 3 "$mpi" smooth "$tmp/fine.mrm" --mode jacobi --max-iters 4 --tol -1 -o "$tmp/np.vtk" --quiet
equal "mrm jacobi np 3 == serial jacobi" "$tmp/serial.vtk" "$tmp/np.vtk"
# -o FILE.mrm written by every rank at once: byte for byte the serial smoother's file along pi.
for np in 1 3; do
  check "mrm to mrm np $np" 0 run $np "$mpi" smooth "$tmp/fine.mrm" --max-iters 3 --tol -1 -o "$tmp/out.mrm" \
    --pi-out "$tmp/pi" --quiet
  check "serial to mrm" 0 "$bin" smooth "$tmp/fine.mrm" --visit-order "$tmp/pi" --max-iters 3 --tol -1 \
    -o "$tmp/serial.mrm" --quiet
  equal "mrm written by $np ranks == serial along pi" "$tmp/serial.mrm" "$tmp/out.mrm"
done
check "mrm output reads" 0 "$bin" mesh info "$tmp/out.mrm"
# -o X.pvtu at -np 3 from a mesh file read in ranges: each rank writes its piece; read by meshio
# (tests/scripts/check_vtu.py), the pieces are the serial .vtu, ghost cells marked.
check "serial jacobi .vtu (mrm)" 0 "$bin" smooth "$tmp/fine.mrm" --mode jacobi --max-iters 4 --tol -1 -o "$tmp/serial.vtu" --quiet
check "mrm jacobi np 3 -> pvtu" 0 run 3 "$mpi" smooth "$tmp/fine.mrm" --mode jacobi --max-iters 4 --tol -1 -o "$tmp/np.pvtu" --quiet
check "pvtu np 3 == serial .vtu (meshio)" 0 /usr/bin/python3 "$(dirname "$0")/../scripts/check_vtu.py" pieces "$tmp/serial.vtu" "$tmp/np.pvtu"
# PT-Scotch on the mesh file: each rank hands PT-Scotch its range's rows, learns its part's ids and
# its ghosts' owners from the directory and reads only its part; the same parts (the same rows go
# to PT-Scotch), pi and result as every rank reading the whole mesh (the same ids, as .node), the
# serial sweep along pi, and -o FILE.mrm written by every rank byte for byte the serial file.
if ((ptscotch)); then
  for np in 2 3 4; do
    check "ptscotch mrm np $np" 0 run $np "$mpi" smooth "$tmp/fine.mrm" --partition ptscotch \
      --ordering bfs --max-iters 4 --tol -1 -o "$tmp/np.vtk" --pi-out "$tmp/pi" --quiet
    contains "ptscotch mrm np $np" "ptscotch partition"
    check "ptscotch whole np $np" 0 run $np "$mpi" smooth "$tmp/fineh.node" --partition ptscotch \
      --ordering bfs --max-iters 4 --tol -1 -o "$tmp/whole.vtk" --pi-out "$tmp/piw" --quiet
    tail -n +2 "$tmp/pi" >"$tmp/pi.body"
    tail -n +2 "$tmp/piw" >"$tmp/piw.body"
    equal "ptscotch mrm np $np: the whole read's pi" "$tmp/piw.body" "$tmp/pi.body"
    equal "ptscotch mrm np $np == whole read" "$tmp/whole.vtk" "$tmp/np.vtk"
    check "serial along pi (ptscotch mrm)" 0 "$bin" smooth "$tmp/fine.mrm" --visit-order "$tmp/pi" \
      --max-iters 4 --tol -1 -o "$tmp/along.vtk" --quiet
    equal "ptscotch mrm np $np == serial along pi" "$tmp/along.vtk" "$tmp/np.vtk"
  done
  check "ptscotch mrm to mrm np 3" 0 run 3 "$mpi" smooth "$tmp/fine.mrm" --partition ptscotch \
    --max-iters 3 --tol -1 -o "$tmp/out.mrm" --pi-out "$tmp/pi" --quiet
  check "serial to mrm (ptscotch pi)" 0 "$bin" smooth "$tmp/fine.mrm" --visit-order "$tmp/pi" \
    --max-iters 3 --tol -1 -o "$tmp/serial.mrm" --quiet
  equal "ptscotch mrm written by 3 ranks == serial along pi" "$tmp/serial.mrm" "$tmp/out.mrm"
fi
ls "$tmp"/*.tmp.* &>/dev/null && { fail=$((fail + 1)); echo "FAIL a temporary left behind"; } || pass=$((pass + 1))
# Damaged, truncated and foreign files: exit 2 on every rank, the file and the place named.
size=$(stat -c %s "$tmp/fine.mrm")
head -c $((size - 8)) "$tmp/fine.mrm" >"$tmp/trunc.mrm"
check "truncated mrm" 2 run 3 "$mpi" smooth "$tmp/trunc.mrm" --quiet
contains "truncated mrm" "meshreuse-mpi: rank 0: error: $tmp/trunc.mrm: byte"
contains "truncated mrm" "truncated: "
cp "$tmp/fine.mrm" "$tmp/bad.mrm"
printf '\x55' | dd of="$tmp/bad.mrm" bs=1 seek=$((size * 3 / 4)) conv=notrunc status=none
check "damaged mrm" 2 run 3 "$mpi" smooth "$tmp/bad.mrm" --quiet
contains "damaged mrm" "does not match its hash"
"$bin" mesh convert "$plate" -o "$tmp/other.mrm" --quiet
check "ranks read different files" 2 timeout 120 "$mpiexec" --oversubscribe -np 1 "$mpi" smooth "$tmp/fine.mrm" --quiet : \
  -np 1 "$mpi" smooth "$tmp/other.mrm" --quiet
contains "ranks read different files" "rank 1 read another mesh file than rank 0"

# Scale smoke test: about 10^6 vertices at -np 2; each rank reads the whole mesh, so a rank's
# peak memory is checked against the serial smoother's; then the mesh file, read in ranges.
check "refine 10^6" 0 "$bin" mesh refine "$plate" --levels 5 --jitter 0.3 -o "$tmp/big" --quiet
check "serial 10^6" 0 /usr/bin/time -f "rss %M" "$bin" smooth "$tmp/big.node" --max-iters 3 --quiet
serial_kb=$(awk '/^rss /{print $2}' "$tmp/out")
check "np 2 10^6" 0 run 2 "$mpi" smooth "$tmp/big.node" --max-iters 3 --quiet
contains "np 2 10^6" "946,464 vertices"
# bytes per owned vertex bounded in a Release build only (a sanitizer's shadow memory and red zones
# triple it); the ratio to the serial smoother's peak holds in both.
per_owned=600; "$bin" --version | grep -q Release || per_owned=1000000
whole_mb=$(awk '$1 ~ /^[01]$/ && NF == 18 {if ($17 > m) m = $17} END {print m}' "$tmp/out")
awk -v s="$serial_kb" -v b="$per_owned" '$1 ~ /^[01]$/ && NF == 18 {n++; if ($17 * 1024 > 1.5 * s) bad = 1; if ($18 > b) bad = 1}
  END {exit !(n == 2 && !bad)}' "$tmp/out" && pass=$((pass + 1)) || {
  fail=$((fail + 1)); echo "FAIL np 2 memory: serial ${serial_kb} kB"; cat "$tmp/out"; }
# Read in ranges, a rank holds its neighbourhood and part, not the mesh: each rank's peak below
# 0.8 of a whole-reading rank's (Release: at most 400 bytes per owned vertex), and it read at most
# 56% of the file (its half, the blocks its range straddles, the block table's pages).
check "big.mrm" 0 "$bin" mesh convert "$tmp/big.node" -o "$tmp/big.mrm" --quiet
check "np 2 10^6 mrm" 0 run 2 "$mpi" smooth "$tmp/big.mrm" --max-iters 3 --quiet
mrm_size=$(stat -c %s "$tmp/big.mrm")
per_owned=400; "$bin" --version | grep -q Release || per_owned=1000000
awk -v w="$whole_mb" -v f="$mrm_size" -v b="$per_owned" '$1 ~ /^[01]$/ && NF == 18 {n++; if ($17 > 0.8 * w) bad = 1; if ($18 > b) bad = 1; if ($10 * 1048576 > 0.56 * f) bad = 1}
  END {exit !(n == 2 && !bad)}' "$tmp/out" && pass=$((pass + 1)) || {
  fail=$((fail + 1)); echo "FAIL np 2 mrm memory or reading: a whole-reading rank ${whole_mb} MB, file $mrm_size B"; cat "$tmp/out"; }
# With PT-Scotch's parts: a rank reads its range's rows (the graph PT-Scotch is given: 77% of a
# range's bytes), then only its part, so at most 95% of the file at -np 2 (1.9/P); PT-Scotch's
# structures beside the rows raise the peak to at most 0.85 of a whole-reading rank's.
if ((ptscotch)); then
  check "np 2 10^6 mrm ptscotch" 0 run 2 "$mpi" smooth "$tmp/big.mrm" --partition ptscotch --max-iters 3 --quiet
  awk -v w="$whole_mb" -v f="$mrm_size" -v b="$per_owned" '$1 ~ /^[01]$/ && NF == 18 {n++; if ($17 > 0.85 * w) bad = 1; if ($18 > b) bad = 1; if ($10 * 1048576 > 0.95 * f) bad = 1}
    END {exit !(n == 2 && !bad)}' "$tmp/out" && pass=$((pass + 1)) || {
    fail=$((fail + 1)); echo "FAIL np 2 mrm ptscotch memory or reading: a whole-reading rank ${whole_mb} MB, file $mrm_size B"; cat "$tmp/out"; }
fi

# meshreuse-mpi refine: the mesh file every rank writes a range of is byte for byte one process's
# (`mesh refine --layout pieces`, the whole mesh in memory) at -np 1..4, at a level where some
# blocks hold no vertex (K = 1) and one where all do; it reads in ranges and smooths at -np 3 equal
# to the serial sweep along pi; the 10^6-vertex refinement at -np 2 in at most 200 bytes per fine
# vertex per rank (Release); outputs that cannot be written in ranges, a missing coarse mesh and a
# refinement beyond 32-bit ids exit 2 on every rank with nothing written.
for k in 1 3; do
  check "pieces, one process, K $k" 0 "$bin" mesh refine "$plate" --levels $k --jitter 0.3 \
    --layout pieces -o "$tmp/pieces.mrm" --quiet
  for np in 1 2 3 4; do
    check "refine np $np K $k" 0 run $np "$mpi" refine "$plate" --levels $k --jitter 0.3 \
      -o "$tmp/ranks.mrm" --quiet
    equal "refine np $np == one process (K $k)" "$tmp/pieces.mrm" "$tmp/ranks.mrm"
  done
done
contains "refine np 4" "from 4 ranks"
check "pieces file np 3" 0 run 3 "$mpi" smooth "$tmp/ranks.mrm" --max-iters 5 --tol -1 \
  -o "$tmp/np.vtk" --pi-out "$tmp/pi" --quiet
check "pieces file along pi" 0 "$bin" smooth "$tmp/ranks.mrm" --visit-order "$tmp/pi" \
  --max-iters 5 --tol -1 -o "$tmp/along.vtk" --quiet
equal "pieces file np 3 == serial along pi" "$tmp/along.vtk" "$tmp/np.vtk"
check "refine 10^6 np 2" 0 run 2 "$mpi" refine "$plate" --levels 5 --jitter 0.3 \
  -o "$tmp/p5.mrm" --rank-stats "$tmp/rs.csv" --quiet
contains "refine 10^6 np 2" "946,464 vertices"
per_vertex=200; "$bin" --version | grep -q Release || per_vertex=1000000
awk -F, -v b="$per_vertex" 'NR > 1 {n++; v += $3; if ($8 > b) bad = 1} END {exit !(n == 2 && v == 946464 && !bad)}' \
  "$tmp/rs.csv" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL refine 10^6 memory"; cat "$tmp/rs.csv"; }
check "refine -o not a mesh file" 2 run 2 "$mpi" refine "$plate" -o "$tmp/x.node" --quiet
contains "refine -o not a mesh file" "PATH.mrm"
ln -s /dev/null "$tmp/null.mrm"
check "refine -o a device" 2 run 2 "$mpi" refine "$plate" -o "$tmp/null.mrm" --quiet
contains "refine -o a device" "regular file"
check "refine missing mesh" 2 run 3 "$mpi" refine "$tmp/missing.node" -o "$tmp/x.mrm" --quiet
contains "refine missing mesh" "$tmp/missing.node"
check "refine beyond 32-bit ids" 2 run 2 "$mpi" refine "$plate" --levels 12 -o "$tmp/x.mrm" --quiet
contains "refine beyond 32-bit ids" "32-bit"
if ls "$tmp" | grep -q "^x\.\|\.tmp\."; then fail=$((fail + 1)); echo "FAIL refusals left files"; ls "$tmp"; else pass=$((pass + 1)); fi

# Failures: a killed rank ends the job naming it; bad input exits 2 on every rank, file named.
MESHREUSE_MPI_KILL_RANK=1 run 3 "$mpi" smooth "$fine" --quiet >"$tmp/out" 2>&1
rc=$?
if [[ $rc -ne 0 && $rc -ne 124 ]] && grep -q "rank 1" "$tmp/out"; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL killed rank: exit $rc"; head -20 "$tmp/out"; fi
check "missing mesh" 2 run 2 "$mpi" smooth "$tmp/missing.node" --quiet
contains "missing mesh" "meshreuse-mpi: rank 0: error: $tmp/missing.node"
contains "missing mesh: Open MPI's report announced" "the lines that follow, if any, are Open MPI's own report of the abort"
check "help names the program" 0 run 1 "$mpi" smooth --help
contains "help names the program" "usage: meshreuse-mpi smooth MESH"
check "broken mesh" 2 run 2 "$mpi" smooth "$data/broken/degenerate.node" --quiet
contains "broken mesh" "degenerate.ele:10"
printf '3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n' >"$tmp/tri.node"
printf '1 3 0\n1 1 2 3\n' >"$tmp/tri.ele"
check "more ranks than vertices" 2 run 4 "$mpi" smooth "$tmp/tri.node" --quiet
contains "more ranks than vertices" "4 ranks for a mesh of 3 vertices"
check "one triangle, no interior" 0 run 3 "$mpi" smooth "$tmp/tri.node" --quiet
check "tri.mrm" 0 "$bin" mesh convert "$tmp/tri.node" -o "$tmp/tri.mrm" --quiet
check "mrm more ranks than vertices" 2 run 4 "$mpi" smooth "$tmp/tri.mrm" --quiet
contains "mrm more ranks than vertices" "4 ranks for a mesh of 3 vertices"
check "mrm one triangle, no interior" 0 run 3 "$mpi" smooth "$tmp/tri.mrm" --quiet
check "bad mode" 2 run 2 "$mpi" smooth "$fine" --mode gs --quiet
contains "bad mode" "unknown distributed mode 'gs'"
check "pi needs ordered" 2 run 1 "$mpi" smooth "$fine" --mode jacobi --pi-out "$tmp/pi2" --quiet
check "serial visit order of another mesh" 2 "$bin" smooth "$plate" --visit-order "$tmp/pi" --quiet
contains "serial visit order of another mesh" "$tmp/pi:"

# Partition once, smooth many times (issue 39): a partition file from `mesh partition -o` gives
# byte for byte the run that computed the same partition itself; one for other ranks is refused.
check "partition file" 0 "$bin" mesh partition "$plate" --parts 3 --method metis -o "$tmp/p3.part" --quiet
check "smooth from the file" 0 run 3 "$mpi" smooth "$plate" --partition "file:$tmp/p3.part" -o "$tmp/pf.vtk" --pi-out "$tmp/pf.pi" --quiet
check "smooth computing it" 0 run 3 "$mpi" smooth "$plate" --partition metis -o "$tmp/pm.vtk" --pi-out "$tmp/pm.pi" --quiet
equal "partition file: mesh" "$tmp/pf.vtk" "$tmp/pm.vtk"
equal "partition file: pi" "$tmp/pf.pi" "$tmp/pm.pi"
check "partition file for 3 ranks at 2" 2 run 2 "$mpi" smooth "$plate" --partition "file:$tmp/p3.part" --quiet
contains "partition file for 3 ranks at 2" "$tmp/p3.part:4: part 2 of vertex 2 is outside 0..1 (2 ranks)"

# Cancelled writers leave no temporary (issue 38): SIGTERM and SIGINT to mpirun (what SLURM's
# scancel sends) and SIGKILL to one rank, while every rank writes the refined mesh file (-np 2 and
# 3) or a smoothed one in ranges, at several moments; a temporary a killed run left is named by the
# next run.

# `timeout --foreground`: without it timeout passes the signal to mpirun and to its own process
# group, which holds mpirun too; two SIGINTs are Open MPI's "forcibly terminate" (it SIGKILLs the
# ranks, whose temporaries nothing can then remove: the next run names them, tested below). A CI
# run left a temporary so; one signal is what scancel or a Ctrl-C at a terminal delivers.
# The moments count from the temporary's appearance (the ranks past MPI_Init, writing), not from
# the launch: a signal while mpirun is still launching is Open MPI's to handle, and a CI run on a
# slow fresh machine left a temporary so, signalled 0.3 s after the launch (nothing a rank can do
# about a SIGKILL it never sees). `cancel_at` waits (10 s at most) for the temporary, then the
# delay, then signals. SIGKILL to a rank cuts its write at once; mpirun takes about a second to
# act on SIGTERM or SIGINT (a 2.5 s refinement, --levels 7, signalled mid-write: ended 1.1 s later,
# no temporary, no output), so on a fast host these short jobs often finish their file first and
# those cases check only that a late signal leaves nothing behind.
check "mrm for cancelling" 0 run 2 "$mpi" refine "$plate" --levels 5 -o "$tmp/c5.mrm" --quiet
# A builtin glob, no process: cancel_at polls it every 10 ms while the ranks it waits for start on
# the same cores (with ls and grep, the polling's lines other than its sleeps came to about 40 s
# of a run's wall under ASan, timestamped by xtrace).
left() { compgen -G "$tmp/*.tmp.*" >/dev/null; }
hit=0  # runs signalled while their temporary existed (the cases that test something)
cancel_at() {  # DELAY HOW JOB PATTERN: signal JOB (KILL: the newest process matching PATTERN)
  local i
  for ((i = 0; i < 1000; i++)); do
    left && break
    kill -0 "$3" 2>/dev/null || return 0
    sleep 0.01
  done
  left && hit=$((hit + 1))
  sleep "$1"
  if [[ $2 == KILL ]]; then pkill -KILL -n -f "$4"; else kill -"$2" "$3" 2>/dev/null; fi
}
for np in 2 3; do
  for how in TERM INT KILL; do
    for delay in 0 0.1; do
      timeout --foreground 60 "$mpiexec" --oversubscribe -np $np "$mpi" refine "$plate" --levels 6 \
        -o "$tmp/cancel.mrm" --quiet >/dev/null 2>&1 &
      job=$!
      cancel_at $delay $how $job "meshreuse-mpi refine $plate --levels 6"
      wait $job
      if left; then fail=$((fail + 1)); echo "FAIL refine -np $np, SIG$how after $delay s: $(ls "$tmp" | grep '\.tmp\.')"
        rm -f "$tmp"/*.tmp.*; else pass=$((pass + 1)); fi
      rm -f "$tmp/cancel.mrm"
      timeout --foreground 60 "$mpiexec" --oversubscribe -np $np "$mpi" smooth "$tmp/c5.mrm" --max-iters 5 --tol -1 \
        -o "$tmp/cancel.mrm" --quiet >/dev/null 2>&1 &
      job=$!
      cancel_at $delay $how $job "meshreuse-mpi smooth $tmp/c5.mrm"
      wait $job
      if left; then fail=$((fail + 1)); echo "FAIL smooth -np $np, SIG$how after $delay s: $(ls "$tmp" | grep '\.tmp\.')"
        rm -f "$tmp"/*.tmp.*; else pass=$((pass + 1)); fi
      rm -f "$tmp/cancel.mrm"
    done
  done
done
# Most of the 24 runs must have been signalled mid-write, or the loop tested nothing.
echo "cancels that hit a write: $hit of 24"
if ((hit >= 16)); then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL only $hit of 24 cancels hit a write"; fi
# SIGKILL to rank 0, the process whose pid names the shared temporary, the moment it appears
# (polled by a glob, no process started between the sight and the kill): the other ranks, told
# its name before it was made, remove it when mpirun ends them. Made first and announced after
# (the form before), it was left behind in 19 runs of these 40 (refine -np 3: 9 of 10), the
# other ranks not yet told (the likely cause, not verified, of the one temporary a CI run's KILL
# above, to "the newest rank", left behind).
shopt -s nullglob
killed=0  # runs whose rank 0 was killed (the cases that test something)
for np in 2 3; do
  for what in refine smooth; do
    if [[ $what == refine ]]; then args=(refine "$plate" --levels 6); else
      args=(smooth "$tmp/c5.mrm" --max-iters 5 --tol -1); fi
    for rep in 1 2; do
      timeout --foreground 60 "$mpiexec" --oversubscribe -np $np "$mpi" "${args[@]}" \
        -o "$tmp/cancel.mrm" --quiet >/dev/null 2>&1 &
      job=$!
      SECONDS=0
      while ((SECONDS < 10)); do
        t=("$tmp"/cancel.mrm.tmp.*)
        if ((${#t[@]})); then kill -KILL "${t[0]##*.tmp.}" 2>/dev/null && killed=$((killed + 1)); break; fi
        kill -0 $job 2>/dev/null || break
      done
      wait $job
      t=("$tmp"/*.tmp.*)
      if ((${#t[@]})); then fail=$((fail + 1)); echo "FAIL $what -np $np, rank 0 killed as its temporary appeared: ${t[*]}"
        rm -f "$tmp"/*.tmp.*; else pass=$((pass + 1)); fi
      rm -f "$tmp/cancel.mrm"
    done
  done
done
shopt -u nullglob
echo "rank 0 killed as its temporary appeared: $killed of 8"
if ((killed >= 6)); then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL rank 0 killed in only $killed of 8 runs"; fi
touch "$tmp/cancel.mrm.tmp.999999999"  # no such process
check "stale temporary named" 0 run 2 "$mpi" refine "$plate" --levels 1 -o "$tmp/cancel.mrm"
contains "stale temporary named" "$tmp/cancel.mrm.tmp.999999999: a temporary an earlier run left"
rm -f "$tmp"/cancel.mrm*

echo "mpi_smooth: $pass passed, $fail failed"
((fail == 0))
