#!/usr/bin/env bash
# Chunk summaries and the merge (reports/chunk_summary.h) as a user runs them, against the serial
# analyzer: every output (table, histogram, profile, miss-ratio curve) byte for byte equal for
# P = 1, 2, 3, 4, 7 chunks on a meshreuse trace (2 threads, 3 sweeps, element and line), u64
# scans, uniform and hashed 64-bit ids, u32, oracle, text (BOM, comments, CRLF: cut at line
# boundaries) and lackey, fewer accesses than chunks and sizes not divisible by P (lib.sh's
# traces); SHARDS at a fixed rate (with and without --sample-error) equal to the serial estimate;
# --threads 2 and 3 (the streamed merge) equal too; each bad merge refused by name with
# exit 2: reordered, repeated, missing, truncated, corrupt, foreign and non-summary files; chunks
# of a zstd trace refused before any work; no summary left behind.
# Usage: chunks.sh MESHREUSE DATA
set -u
bin=$1 data=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/lib.sh"
chunked() {  # chunked PREFIX P TRACE ARGS... : P chunk runs then the merge, outputs at PREFIX
  local p=$1 n=$2 tr=$3 r list=()
  shift 3
  for ((r = 0; r < n; r++)); do
    "$bin" analyze "$tr" "$@" --chunk "$r/$n" --summary-out "$tmp/s$r" --quiet || { echo "FAIL chunk $r/$n of $tr"; fail=$((fail + 1)); }
    list+=("$tmp/s$r")
  done
  outputs "$p" "$bin" analyze --merge "${list[@]}"
}

make_traces "$bin" "$data"

for P in 1 2 3 4 7; do
  outputs "$tmp/serial" "$bin" analyze "$tmp/mesh.trace"
  chunked "$tmp/merged" "$P" "$tmp/mesh.trace"
  same "mesh trace P=$P" "$tmp/serial" "$tmp/merged"
  for f in "${trace_specs[@]}"; do
    set -- $f
    outputs "$tmp/serial" "$bin" analyze "$tmp/$1" --format "$2" --granularity "$3"
    chunked "$tmp/merged" "$P" "$tmp/$1" --format "$2" --granularity "$3"
    same "$1 P=$P" "$tmp/serial" "$tmp/merged"
  done
done
# SHARDS at a fixed rate, with and without the exact analysis beside it: the merged estimate is
# the serial sampler's, bit for bit.
for P in 1 3 4; do
  for extra in "--sample-rate 0.1" "--sample-rate 0.05 --sample-error"; do
    outputs "$tmp/serial" "$bin" analyze "$tmp/mesh.trace" $extra
    chunked "$tmp/merged" "$P" "$tmp/mesh.trace" $extra
    same "mesh trace P=$P $extra" "$tmp/serial" "$tmp/merged"
    outputs "$tmp/serial" "$bin" analyze "$tmp/uniform.u64" --format u64 $extra
    chunked "$tmp/merged" "$P" "$tmp/uniform.u64" --format u64 $extra
    same "uniform.u64 P=$P $extra" "$tmp/serial" "$tmp/merged"
  done
done
check "fixed-size chunk" 2 "$bin" analyze "$tmp/uniform.u64" --format u64 --sample-size 100 --chunk 0/2 --summary-out "$tmp/x" --quiet
contains "fixed-size chunk" "samples at a fixed rate"

# The streamed merge on threads: the same outputs.
for th in 2 3; do
  outputs "$tmp/serial" "$bin" analyze "$tmp/uniform.u64" --format u64 --granularity element
  outputs "$tmp/threads" "$bin" analyze "$tmp/uniform.u64" --format u64 --granularity element --threads "$th"
  same "uniform.u64 --threads $th" "$tmp/serial" "$tmp/threads"
  outputs "$tmp/serial" "$bin" analyze "$tmp/mesh.trace"
  outputs "$tmp/threads" "$bin" analyze "$tmp/mesh.trace" --threads "$th"
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
