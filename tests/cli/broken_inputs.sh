#!/usr/bin/env bash
# Every broken input in tests/data/broken/EXPECTED, through the CLI: exit code 2, one error line on
# stderr naming FILE:LINE and the problem, nothing on stdout. Usage: broken_inputs.sh MESHREUSE DATA
set -u
bin=$1 data=$2
fail=0 n=0
# Peak memory of every run, bounded by 100 MB (not under AddressSanitizer, whose shadow memory
# alone is more); /usr/bin/time comes from Debian's `time` package (scripts/setup.sh).
rssfile=$(mktemp)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$rssfile"' EXIT
timer=""
if [[ -x /usr/bin/time ]] && ! ldd "$bin" 2>/dev/null | grep -q libasan; then
  timer="/usr/bin/time -f %M -o $rssfile"
fi
while IFS=$'\t' read -r file line msg kind; do
  [[ -z $file || $file == \#* ]] && continue
  path="$data/broken/$file"
  where="$path:$line: "
  [[ $line == 0 ]] && where="$path: "
  case ${kind:-mesh} in
    mesh) cmds=("mesh info %s" "smooth %s") ;;
    # --threads 3: a chunk per thread, each reading its part (the same message as one reader)
    trace) cmds=("analyze %s" "analyze %s --threads 3" "simulate %s") ;;
    text|u32|u64|lackey|oracle|parda) cmds=("analyze %s --format $kind" "analyze %s --format $kind --threads 3" "simulate %s --format $kind") ;;
    poly) command -v triangle >/dev/null || continue
      cmds=("mesh generate --poly %s --vertices 1000 -o $tmp/generated") ;;
    summary) cmds=("analyze --merge %s") ;;
    perm) cmds=("smooth $data/two_interior.node --ordering file:%s" "reorder $data/two_interior.node -o $tmp/reordered --ordering file:%s") ;;
    visit) cmds=("smooth $data/two_interior.node --visit-order %s") ;;
  esac
  for tmpl in "${cmds[@]}"; do
    # shellcheck disable=SC2059
    cmd=$(printf "$tmpl" "$path")
    n=$((n + 1))
    out=$($timer "$bin" $cmd --quiet 2>/tmp/meshreuse-cli-err.$$)
    rc=$?
    if [[ -n $timer ]]; then
      rss=$(tail -n 1 "$rssfile")
      if ((rss > 102400)); then echo "FAIL $cmd: $rss KB of memory (bound: 100 MB)"; fail=$((fail + 1)); fi
    fi
    err=$(cat /tmp/meshreuse-cli-err.$$)
    if [[ $rc -ne 2 ]]; then echo "FAIL $cmd $file: exit $rc, expected 2 ($err)"; fail=$((fail + 1)); continue; fi
    if [[ $err != "meshreuse: error: $where"*"$msg"* ]]; then
      echo "FAIL $cmd $file: stderr was: $err"; echo "     expected: meshreuse: error: $where...$msg..."; fail=$((fail + 1)); continue
    fi
    if [[ $(printf '%s\n' "$err" | wc -l) -ne 1 ]]; then echo "FAIL $cmd $file: more than one stderr line: $err"; fail=$((fail + 1)); fi
    if [[ $cmd == "mesh info"* && -n $out ]]; then echo "FAIL $cmd $file: wrote to stdout: $out"; fail=$((fail + 1)); fi
  done
done < "$data/broken/EXPECTED"
# Hostile inputs made here: a directory and /dev/zero where files are expected, a sparse trace
# announcing 50,000 sweeps. Each: exit 2, the file named, bounded memory.
tmp=$(mktemp -d)
mkdir "$tmp/d.msh"
ln -s /dev/zero "$tmp/zero.node"
ln -s /dev/zero "$tmp/zero.ele"
/usr/bin/python3 "$data/broken/make_traces.py" "$tmp" --sparse
/usr/bin/python3 "$data/broken/make_meshes.py" "$tmp" 100000
# Issue 38's (round 4): a machine file of 1-byte lines in a GiB level and one whose name holds a
# control byte; a file where a folder must be; a u64 trace in zstd frames whose seek table claims
# 2^32 - 1 content bytes a frame; two u64 traces of one size and the same ends, edited inside.
printf 'name tiny\nsockets 1\ncores 1\nline 1\nmemory 100 100\nprivate L1=1G/1@4\n' >"$tmp/huge.machine"
printf 'name bad\001name\nsockets 1\ncores 1\nline 64\nmemory 100 100\nprivate L1=32K/8@4\n' >"$tmp/ctrl.machine"
touch "$tmp/afile"
printf '# 2 parts\n0\n1\n0\n' >"$tmp/short.part"
{ for i in $(seq 1 8); do echo 0; done; echo 1; } >"$tmp/long.part"
printf '0\n1\n2\n0\n1\n0\n1\n0\n' >"$tmp/range.part"
printf '0\n1\nx\n0\n1\n0\n1\n0\n' >"$tmp/word.part"
/usr/bin/python3 - "$tmp" <<'PY'
import random, struct, sys
d = sys.argv[1]
r = random.Random(1)
v = [r.randrange(3000) for _ in range(30000)]
open(f"{d}/a.u64", "wb").write(b"".join(struct.pack("<Q", x) for x in v))
for i in list(range(8500, 9500)) + list(range(14000, 16000)):
    v[i] = (v[i] + 1) % 3000
open(f"{d}/b.u64", "wb").write(b"".join(struct.pack("<Q", x) for x in v))
PY
"$bin" compress "$tmp/a.u64" -o "$tmp/a.zst" --frame-kib 16 --quiet >/dev/null
/usr/bin/python3 - "$tmp" <<'PY'
import struct, sys
d = sys.argv[1]
b = bytearray(open(f"{d}/a.zst", "rb").read())
n, desc, magic = struct.unpack("<IBI", b[-9:])
assert magic == 0x8F92EAB1
width = 12 if desc & 0x80 else 8
for i in range(n):  # every frame's content size: 2^32 - 1
    struct.pack_into("<I", b, len(b) - 9 - n * width + i * width + 4, 0xFFFFFFFF)
open(f"{d}/lie.zst", "wb").write(b)
PY
for i in 0 1 2; do
  "$bin" analyze "$tmp/a.u64" --format u64 --chunk $i/3 --summary-out "$tmp/sa$i" --quiet
  "$bin" analyze "$tmp/b.u64" --format u64 --chunk $i/3 --summary-out "$tmp/sb$i" --quiet
done
hostile=(
  "2|$tmp/d.msh: is a directory, not a file|mesh info $tmp/d.msh"
  "2|$tmp/zero.node: is a character device, not a file|mesh info $tmp/zero.node"
  "2|/dev/zero: is a character device, not a file|smooth $data/two_interior.node --ordering file:/dev/zero"
  "2|/dev/zero: is a character device, not a file|analyze /dev/zero --format text"
  "2|$data/broken: is a directory, not a file|analyze $data/broken --format u64"
  "2|$data/broken: is a directory, not a file|analyze $data/broken --format text"
  "2|$data/broken: is a directory, not a file|simulate $data/broken --format u32"
  "0||analyze $tmp/sweeps_50000.trace --granularity element --profile-csv $tmp/p.csv"
  # Gigabytes from kilobytes (issue 20): a header announcing 16,352 x 256 empty (sweep, stream)
  # pairs is refused from its fixed 48 bytes; 256 streams of one record each, with 256 sweeps
  # announced, cost what the records need (per-sweep rows only where a stream has accesses);
  # option products that cannot fit are refused before anything is allocated.
  "2|$tmp/announce_16352x256.trace: the header announces 16352 sweeps x 256 streams: at most 65536|simulate $tmp/announce_16352x256.trace --per-sweep"
  "0||simulate $tmp/streams_256.trace --per-sweep --csv"
  "0||analyze $tmp/below_base.trace"
  "0||analyze $tmp/streams_256.trace --profile-csv $tmp/p256.csv"
  "2|usage: --iterations 2000 x --threads 255 = 510000 (sweep, stream) pairs: at most 65536|analyze $data/two_interior.node -k 2000 -t 255"
  "2|usage: --iterations 2000 x --threads 255 = 510000 (sweep, stream) pairs: at most 65536|simulate $data/two_interior.node -k 2000 -t 255 --per-sweep"
  "2|usage: --iterations must be 1..65536|analyze $data/two_interior.node -k 100000"
  "0||simulate $data/two_interior.node -k 256 -t 255 --per-sweep --csv"
  # Valid meshes that took quadratic time (issue 20): one vertex in 100,000 triangles, and
  # 100,000 Gmsh element blocks of one triangle (binary and ASCII). The time ratios against an
  # ordinary mesh are a benchmark (meshreuse_bench --benchmark_filter=Build), not a test.
  "0||mesh info $tmp/fan_100000.node"
  "0||reorder $tmp/fan_100000.node --ordering rdr -o $tmp/fan_rdr"
  "0||smooth $tmp/fan_100000.node --max-iters 3"
  "0||mesh info $tmp/blocks_100000.msh"
  "0||mesh info $tmp/blocks_ascii_100000.msh"
  # Issue 38 (round 4): each refused at once, naming what is wrong.
  "2|usage: --parts must be 1..65536, found 2147483647|mesh partition $data/two_interior.node --parts 2147483647 --split $tmp/P_"
  "2|usage: --vertices must be 100..1073741824, found 100000000000|mesh generate --shape lake --vertices 100000000000 -o $tmp/g"
  "2|usage: -o '$tmp/afile/x': $tmp/afile is not a folder|mesh generate --shape lake -o $tmp/afile/x"
  "2|usage: --seed takes a whole number|mesh refine $data/two_interior.node --seed -1 -o $tmp/r.node"
  "2|usage: --seed takes a whole number|mesh partition $data/two_interior.node --seed -1"
  "2|usage: --merge: --iterations was the chunk runs' to choose|analyze --merge $tmp/sa0 $tmp/sa1 $tmp/sa2 -k 5"
  "2|usage: --merge: --threads was the chunk runs' to choose|analyze --merge $tmp/sa0 $tmp/sa1 $tmp/sa2 --threads 2"
  "2|$tmp/sb1: a summary of another analysis|analyze --merge $tmp/sa0 $tmp/sb1 $tmp/sa2"
  "0||analyze --merge $tmp/sa0 $tmp/sa1 $tmp/sa2"
  "2|$tmp/huge.machine: level L1: 1073741824 lines of 1 B; a level holds at most 67108864 lines|simulate $data/two_interior.node --machine $tmp/huge.machine"
  "2|$tmp/ctrl.machine:1: the name holds a control character|simulate $data/two_interior.node --machine $tmp/ctrl.machine"
  "2|usage: cache level L1: 1073741824 lines of 1 B|simulate $data/two_interior.node --cache L1=1G/1 --line-bytes 1"
  "2|$tmp/lie.zst: the zstd seek table does not match the frames|analyze $tmp/lie.zst --format u64"
  "2|$tmp/lie.zst: the zstd seek table does not match the frames|analyze $tmp/lie.zst --format u64 --threads 3"
  "2|$tmp/lie.zst: the zstd seek table does not match the frames|analyze $tmp/lie.zst --format u64 --chunk 1/3 --summary-out $tmp/lie.sum"
  "2|$tmp/short.part: 3 parts for a mesh of 8 vertices: a line per vertex|smooth-ranks $data/two_interior.node --ranks 2 --partition file:$tmp/short.part"
  "2|$tmp/long.part:9: more lines than the mesh's 8 vertices|smooth-ranks $data/two_interior.node --ranks 2 --partition file:$tmp/long.part"
  "2|$tmp/range.part:3: part 2 of vertex 2 is outside 0..1 (2 ranks)|analyze $data/two_interior.node --ranks 2 --partition file:$tmp/range.part"
  "2|$tmp/word.part:3: |simulate $data/two_interior.node --ranks 2 --partition file:$tmp/word.part"
  "2|usage: -o '$tmp/same.vtk' is the file --pi-out writes too|smooth-ranks $data/two_interior.node --ranks 2 -o $tmp/same.vtk --pi-out $tmp/same.vtk"
  "2|usage: --mrc-csv '$tmp/h.csv' is the file --histogram-csv writes too|analyze $data/two_interior.node --histogram-csv $tmp/h.csv --mrc-csv $tmp/h.csv"
)
for h in "${hostile[@]}"; do
  IFS='|' read -r want msg cmd <<<"$h"
  n=$((n + 1))
  $timer "$bin" $cmd --quiet >/dev/null 2>/tmp/meshreuse-cli-err.$$
  rc=$?
  err=$(cat /tmp/meshreuse-cli-err.$$)
  if [[ $rc -ne $want ]]; then echo "FAIL $cmd: exit $rc, expected $want ($err)"; fail=$((fail + 1)); continue; fi
  if [[ $msg == usage:* ]]; then  # an option's error: "meshreuse COMMAND: MESSAGE (see --help)"
    sub=${cmd%% *}
    [[ $sub == mesh ]] && sub="mesh $(cut -d' ' -f2 <<<"$cmd")"
    if [[ $err != "meshreuse $sub: ${msg#usage: }"* ]]; then echo "FAIL $cmd: stderr was: $err"; fail=$((fail + 1)); continue; fi
  elif [[ -n $msg && $err != "meshreuse: error: $msg"* ]]; then echo "FAIL $cmd: stderr was: $err"; fail=$((fail + 1)); continue; fi
  if [[ -n $timer ]] && (($(tail -n 1 "$rssfile") > 102400)); then echo "FAIL $cmd: $(tail -n 1 "$rssfile") KB"; fail=$((fail + 1)); fi
done
# A summary read from a pipe of zeros is refused at its magic, at once and in bounded memory.
mkfifo "$tmp/zeros"
(timeout 20 cat /dev/zero >"$tmp/zeros" 2>/dev/null &)
n=$((n + 1))
err=$($timer timeout 20 "$bin" analyze --merge "$tmp/sa0" "$tmp/zeros" "$tmp/sa2" --quiet 2>&1 >/dev/null)
rc=$?
(exec 3<>"$tmp/zeros") 2>/dev/null
if [[ $rc -ne 2 || $err != "meshreuse: error: $tmp/zeros: not a chunk summary"* ]]; then
  echo "FAIL a pipe of zeros as a summary: exit $rc: $err"; fail=$((fail + 1))
elif [[ -n $timer ]] && (($(tail -n 1 "$rssfile") > 102400)); then
  echo "FAIL a pipe of zeros as a summary: $(tail -n 1 "$rssfile") KB"; fail=$((fail + 1))
fi
# A Gmsh split set with a part missing names it; a stray part of an older split is left out.
cp "$data/plate_split_1.msh" "$tmp/s_1.msh" && cp "$data/plate_split_3.msh" "$tmp/s_3.msh"
n=$((n + 1))
err=$("$bin" mesh partition "$tmp/s_1.msh" --method gmsh --parts 3 --quiet 2>&1 >/dev/null)
[[ $? -eq 2 && $err == *"$tmp/s_2.msh: cannot open: part 2 of the 3 that $tmp/s_1.msh declares"* ]] ||
  { echo "FAIL split set without part 2: $err"; fail=$((fail + 1)); }
cp "$data/plate_split_2.msh" "$tmp/s_2.msh" && cp "$data/plate_split_3.msh" "$tmp/s_4.msh"
n=$((n + 1))
err=$("$bin" mesh partition "$tmp/s_1.msh" --method gmsh --parts 3 --quiet 2>&1 >/dev/null)
[[ $? -eq 0 && $err == *"$tmp/s_4.msh: left out: $tmp/s_1.msh declares 3 parts"* ]] ||
  { echo "FAIL split set with a stray part 4: $err"; fail=$((fail + 1)); }
# A trace set written again in part (a rank's file of another run) is refused when read together.
"$bin" trace "$data/plate41.msh" --ranks 2 -o "$tmp/set" --quiet >/dev/null 2>&1
"$bin" trace "$data/plate41.msh" --ranks 2 --ordering bfs -o "$tmp/other" --quiet >/dev/null 2>&1
n=$((n + 1))
"$bin" analyze "$tmp/set.rank0" "$tmp/set.rank1" --quiet >/dev/null 2>&1 || { echo "FAIL a trace set"; fail=$((fail + 1)); }
cp "$tmp/other.rank0" "$tmp/set.rank0"
n=$((n + 1))
err=$("$bin" analyze "$tmp/set.rank0" "$tmp/set.rank1" --quiet 2>&1 >/dev/null)
[[ $? -eq 2 && $err == *"$tmp/set.rank1: a rank of another \`trace --ranks\` run than $tmp/set.rank0"* ]] ||
  { echo "FAIL a mixed trace set: $err"; fail=$((fail + 1)); }
# Ranks as threads beyond what the process may create: exit 3 naming --ranks, no temporary left.
n=$((n + 1))
err=$( (ulimit -v 3000000; "$bin" mesh refine "$data/plate41.msh" --levels 1 --layout pieces --ranks 4096 \
  -o "$tmp/r4096.mrm" --quiet) 2>&1 >/dev/null)
rc=$?
if [[ -z $timer ]]; then :  # under AddressSanitizer the address-space limit is meaningless
elif [[ $rc -ne 3 || $err != *"allow fewer (--ranks)"* ]] || ls "$tmp" | grep -q 'r4096.mrm'; then
  echo "FAIL 4096 ranks under 3 GB: exit $rc: $err"; fail=$((fail + 1))
fi
[[ $(wc -l <"$tmp/p.csv") -eq 101 ]] || { echo "FAIL sparse trace: its profile should have 100 steps"; fail=$((fail + 1)); }
# 256 streams, one record each in sweep 1: one profile step each (a sweep of one access).
[[ $(wc -l <"$tmp/p256.csv") -eq 257 ]] || { echo "FAIL streams_256: its profile should have 256 steps, has $(($(wc -l <"$tmp/p256.csv") - 1))"; fail=$((fail + 1)); }
rm -rf "$tmp" "$rssfile"
rm -f /tmp/meshreuse-cli-err.$$
echo "broken inputs: $((n - fail)) passed, $fail failed"
[[ $fail -eq 0 ]]
