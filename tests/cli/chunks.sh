#!/usr/bin/env bash
# Chunk summaries and the merge (reports/chunk_summary.h) as a user runs them, against the serial
# analyzer: every output (table, histogram, profile, miss-ratio curve) byte for byte equal for
# P = 1, 2, 3, 4, 7 chunks on a meshreuse trace (2 threads, 3 sweeps, element and line), u64
# scans, uniform and hashed 64-bit ids, u32, oracle, text (BOM, comments, CRLF: cut at line
# boundaries) and lackey, fewer accesses than chunks and sizes not divisible by P; --threads 2 and 3 (the streamed merge) equal too; and each bad merge refused by
# name with exit 2: reordered, repeated, missing, truncated, corrupt, foreign and non-summary
# files; chunks of a zstd trace refused before any work; no summary left behind.
# Usage: chunks.sh MESHREUSE DATA
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
contains() {
  if grep -qF -- "$2" "$tmp/out"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1: output lacks '$2'"; sed 's/^/    /' "$tmp/out" | head -20; fi
}
outputs() {  # outputs PREFIX ARGS... : the table and the three files of one analysis
  local p=$1
  shift
  "$bin" analyze "$@" --csv --quiet --histogram-csv "$p.h" --profile-csv "$p.p" --mrc-csv "$p.m" >"$p.t" 2>"$p.err"
}
same() {  # same NAME A B : all four outputs identical, and not empty
  local x ok=1
  [[ -s "$2.t" && -s "$2.h" ]] || { ok=0; echo "FAIL $1: no serial output"; cat "$2.err"; }
  for x in t h p m; do
    [[ -e "$2.$x" || -e "$3.$x" ]] || continue
    cmp -s "$2.$x" "$3.$x" || { ok=0; echo "FAIL $1: .$x differs"; diff "$2.$x" "$3.$x" | head -5; }
  done
  if ((ok)); then pass=$((pass + 1)); else fail=$((fail + 1)); fi
}
chunked() {  # chunked PREFIX P TRACE ARGS... : P chunk runs then the merge, outputs at PREFIX
  local p=$1 n=$2 tr=$3 r list=()
  shift 3
  for ((r = 0; r < n; r++)); do
    "$bin" analyze "$tr" "$@" --chunk "$r/$n" --summary-out "$tmp/s$r" --quiet || { echo "FAIL chunk $r/$n of $tr"; fail=$((fail + 1)); }
    list+=("$tmp/s$r")
  done
  outputs "$p" --merge "${list[@]}"
}

# Inputs: a meshreuse trace of a mesh (2 threads, 3 sweeps), and fixed-record traces.
"$bin" trace "$data/plate41.msh" --ordering rdr -k 3 -t 2 -o "$tmp/mesh.trace" --quiet &>/dev/null
"$bin" trace "$data/plate41.msh" -k 2 -o "$tmp/mesh.trace.zst" --compress --quiet &>/dev/null
/usr/bin/env python3 - "$tmp" <<'PY'
import random, struct, sys
d = sys.argv[1]
rng = random.Random(7)
def u64(name, vals):
    with open(f"{d}/{name}", "wb") as f:
        f.write(b"".join(struct.pack("<Q", v) for v in vals))
u64("scan.u64", [64 * (i % 997) for i in range(9973)])
u64("uniform.u64", [rng.randrange(3000) for _ in range(20011)])
u64("hashed.u64", [(rng.randrange(500) * 0x9E3779B97F4A7C15 | 1 << 63) & (2**64 - 1) for _ in range(7001)])
u64("tiny.u64", [5, 9, 5])
with open(f"{d}/ids.u32", "wb") as f:
    f.write(b"".join(struct.pack("<I", rng.randrange(1000) * 4) for _ in range(5003)))
with open(f"{d}/cache.oracle", "wb") as f:  # oracleGeneral: u32 time, u64 id, u32 size, i64 next
    f.write(b"".join(struct.pack("<IQIq", i, rng.randrange(400) << 40, 1, -1) for i in range(3001)))
with open(f"{d}/ids.txt", "wb") as f:  # a BOM, comments, blank lines, CRLF, hex: cut at lines
    lines = ["\ufeff# ids"] + [("0x%x" if i % 5 == 0 else "%d") % rng.randrange(700) +
                                ("  # c" if i % 7 == 0 else "") for i in range(4001)]
    lines[100:100] = ["", "   ", "# comment"]
    f.write(("\r\n".join(lines[:2000]) + "\n" + "\n".join(lines[2000:])).encode())
PY
zstd -q -d -c "$data/lackey/transpose.lackey.zst" >"$tmp/transpose.lackey"

for P in 1 2 3 4 7; do
  outputs "$tmp/serial" "$tmp/mesh.trace"
  chunked "$tmp/merged" "$P" "$tmp/mesh.trace"
  same "mesh trace P=$P" "$tmp/serial" "$tmp/merged"
  for f in "scan.u64 u64 element" "uniform.u64 u64 element" "hashed.u64 u64 element" \
           "tiny.u64 u64 element" "ids.u32 u32 line" "cache.oracle oracle element" \
           "ids.txt text element" "transpose.lackey lackey line"; do
    set -- $f
    outputs "$tmp/serial" "$tmp/$1" --format "$2" --granularity "$3"
    chunked "$tmp/merged" "$P" "$tmp/$1" --format "$2" --granularity "$3"
    same "$1 P=$P" "$tmp/serial" "$tmp/merged"
  done
done
# The streamed merge on threads: the same outputs.
for th in 2 3; do
  outputs "$tmp/serial" "$tmp/uniform.u64" --format u64 --granularity element
  outputs "$tmp/threads" "$tmp/uniform.u64" --format u64 --granularity element --threads "$th"
  same "uniform.u64 --threads $th" "$tmp/serial" "$tmp/threads"
  outputs "$tmp/serial" "$tmp/mesh.trace"
  outputs "$tmp/threads" "$tmp/mesh.trace" --threads "$th"
  same "mesh.trace --threads $th" "$tmp/serial" "$tmp/threads"
done

# Bad merges, each refused by name.
for r in 0 1 2; do "$bin" analyze "$tmp/uniform.u64" --format u64 --chunk $r/3 --summary-out "$tmp/u$r" --quiet; done
"$bin" analyze "$tmp/scan.u64" --format u64 --chunk 1/3 --summary-out "$tmp/other1" --quiet
check "reordered" 2 "$bin" analyze --merge "$tmp/u0" "$tmp/u2" "$tmp/u1" --quiet
contains "reordered" "$tmp/u2: chunk 2/3 where chunk 1/3 was expected"
check "repeated" 2 "$bin" analyze --merge "$tmp/u0" "$tmp/u1" "$tmp/u1" --quiet
contains "repeated" "$tmp/u1: chunk 1/3 where chunk 2/3 was expected"
check "missing" 2 "$bin" analyze --merge "$tmp/u0" "$tmp/u1" --quiet
contains "missing" "a run of 3 chunks, and 2 summaries given"
check "foreign" 2 "$bin" analyze --merge "$tmp/u0" "$tmp/other1" "$tmp/u2" --quiet
contains "foreign" "$tmp/other1: a summary of another analysis"
head -c 100 "$tmp/u2" >"$tmp/cut"
check "truncated" 2 "$bin" analyze --merge "$tmp/u0" "$tmp/u1" "$tmp/cut" --quiet
contains "truncated" "$tmp/cut: truncated or extended summary"
cp "$tmp/u2" "$tmp/flip"
printf '\x01' | dd of="$tmp/flip" bs=1 seek=200 conv=notrunc 2>/dev/null
check "corrupt" 2 "$bin" analyze --merge "$tmp/u0" "$tmp/u1" "$tmp/flip" --quiet
contains "corrupt" "$tmp/flip: corrupt summary: the checksum does not match"
check "not a summary" 2 "$bin" analyze --merge "$tmp/u0" "$tmp/u1" "$tmp/uniform.u64" --quiet
contains "not a summary" "not a chunk summary"
# Chunks that cannot be: refused before any work, nothing written.
check "zstd chunk" 2 "$bin" analyze "$tmp/mesh.trace.zst" --chunk 1/2 --summary-out "$tmp/z" --quiet
contains "zstd chunk" "decompress it first"
[[ ! -e "$tmp/z" ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL zstd chunk left a summary"; }
zstd -q -f "$tmp/ids.txt" -o "$tmp/ids.txt.zst"
check "zstd text chunk" 2 "$bin" analyze "$tmp/ids.txt.zst" --format text --chunk 1/2 --summary-out "$tmp/x" --quiet
contains "zstd text chunk" "decompress it first"
printf '1\n2\nx\n3\n' >"$tmp/bad.txt"
check "bad text chunk" 2 "$bin" analyze "$tmp/bad.txt" --format text --chunk 1/2 --summary-out "$tmp/x" --quiet
contains "bad text chunk" "where this chunk begins"
check "bad chunk spec" 2 "$bin" analyze "$tmp/uniform.u64" --format u64 --chunk 3/3 --summary-out "$tmp/x" --quiet
contains "bad chunk spec" "expected 0 <= r < P"
check "chunk without out" 2 "$bin" analyze "$tmp/uniform.u64" --format u64 --chunk 0/3 --quiet
contains "chunk without out" "--chunk needs --summary-out"
check "chunk of a mesh" 2 "$bin" analyze "$data/plate41.msh" --chunk 0/2 --summary-out "$tmp/x" --quiet
check "chunk onto input" 2 "$bin" analyze "$tmp/uniform.u64" --format u64 --chunk 0/2 --summary-out "$tmp/uniform.u64" --quiet
[[ ! -e "$tmp/x" ]] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL a refused chunk left a summary"; }

echo "chunks: $pass passed, $fail failed"
((fail == 0))
