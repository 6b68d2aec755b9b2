#!/usr/bin/env bash
# How transpose.lackey.zst and transpose.cachegrind were made (valgrind 3.19, gcc 12, Debian 12),
# for tests/analysis/cache_sim_test.cc (CacheSim.LackeyTraceMissesEqualCachegrinds): one static
# program traced by lackey and simulated by cachegrind with the same caches. Static, so that the
# dynamic loader's work does not swell the trace; valgrind lays the client out the same way under
# both tools, so the addresses are the ones cachegrind simulated (their counts check it: D refs
# 35,868 = lackey's L+S+M lines). Re-running on another system gives other numbers, in both files.
set -euo pipefail
cd "$(dirname "$0")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
gcc -O1 -static -o "$tmp/transpose" transpose.c
valgrind --tool=lackey --trace-mem=yes --log-file="$tmp/t.lackey" "$tmp/transpose" || true
zstd -19 -q -f "$tmp/t.lackey" -o transpose.lackey.zst
valgrind --tool=cachegrind --cache-sim=yes --I1=4096,2,64 --D1=4096,2,64 --LL=65536,4,64 \
  --cachegrind-out-file="$tmp/cg.out" "$tmp/transpose" || true
grep '^desc\|^cmd\|^events\|^summary' "$tmp/cg.out" >transpose.cachegrind
