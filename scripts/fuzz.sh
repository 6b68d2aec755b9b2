#!/usr/bin/env bash
# Fuzzes every reader with libFuzzer (clang, AddressSanitizer + UndefinedBehaviorSanitizer): the
# Triangle pair, Gmsh, the binary trace, other tools' traces (text, u32, u64, parda, oracle,
# lackey; plain or zstd, one frame or several, pzstd's too), permutation files, .poly outlines,
# chunk summaries, visit orders and distributed mesh files (harnesses in tests/fuzz/, each running
# everything downstream of the reader on what it accepts).
# Seeds come from tests/data; corpora grow in build/fuzz/corpus/ and are kept between runs.
# Limits: 10 s per input, 512 MB of RSS (ASan's quarantine at 32 MB), no single allocation above
# 64 MB (a header's count must never be trusted for memory). Fails (exit 1) on any finding;
# reproducers go to build/fuzz/artifacts/.
# Usage: scripts/fuzz.sh [SECONDS] [--build-only]   (per harness, default 60; two harnesses run at
#   a time. --build-only: install, configure and build build/fuzz, then stop; scripts/test.sh
#   builds so in the background while its tests run)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib.sh
usage() { lib_usage 2 11; }
LIB_USAGE=usage
secs=60 build_only=0
lib_options @=secs --build-only=build_only! -- "$@"
[[ $secs =~ ^[0-9]+$ ]] || lib_die "SECONDS must be a number"
bash scripts/setup.sh --with-fuzz
mkdir -p build  # its logs go there, on a fresh clone too

echo "== configure and build build/fuzz (clang, libFuzzer)" >&2
# Ninja for a fresh folder (see test.sh); -g1: line tables, all a finding's stack needs.
gen=()
[[ ! -f build/fuzz/CMakeCache.txt ]] && command -v ninja >/dev/null && gen=(-G Ninja)
CC=clang CXX=clang++ cmake "${gen[@]}" -S . -B build/fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1" -DMESHREUSE_FUZZ=ON -DMESHREUSE_PAPI=OFF >build/fuzz.configure.log 2>&1 || { cat build/fuzz.configure.log; exit 1; }
cmake --build build/fuzz -j"$(nproc 2>/dev/null || echo 2)" >build/fuzz.build.log 2>&1 ||
  { tail -n 40 build/fuzz.build.log; exit 1; }
((build_only)) && exit 0

harnesses=(triangle gmsh trace external permutation poly summary visit_order mesh_file)
c=build/fuzz/corpus
rm -rf build/fuzz/logs build/fuzz/artifacts
mkdir -p build/fuzz/artifacts build/fuzz/logs
for h in "${harnesses[@]}"; do mkdir -p "$c/$h"; done
# Seeds: every small and broken input we have, in the harness's input format.
for node in tests/data/*.node tests/data/broken/*.node; do
  ele=${node%.node}.ele
  [[ -f $ele ]] && { cat "$node"; printf '@@@\n'; cat "$ele"; } >"$c/triangle/seed-$(basename "${node%.node}")"
done
cp tests/data/*.msh tests/data/broken/*.msh "$c/gmsh/"
cp tests/data/broken/*.trace "$c/trace/"
[[ -x build/release/cli/meshreuse ]] &&
  build/release/cli/meshreuse trace tests/data/two_interior.node --threads 2 -o "$c/trace/seed-two_interior.trace" --quiet >/dev/null
# Format byte (tests/fuzz/fuzz_external.cc): low four bits the format's fixed code in
# tracer/trace_formats.cc (1 text, 2 u32, 3 u64, 4 parda, 5 oracle, 6 lackey), bit 4 (0x10)
# instructions, bit 5 (0x20) two workers, bit 6 (0x40) three chunks by range. Octal escapes
# below: \043 = u64 on two workers.
for f in tests/data/broken/*.txt; do { printf '\1'; cat "$f"; } >"$c/external/seed-$(basename "$f")"; done
printf '\1# ids\n1\n2\n0x10\n1\n' >"$c/external/seed-text"
{ printf '\2'; /usr/bin/python3 -c 'import struct,sys; sys.stdout.buffer.write(struct.pack("<4I",1,2,1,3))'; } >"$c/external/seed-u32"
{ printf '\3'; cat tests/data/broken/reserved.u64; } >"$c/external/seed-u64"
for f in tests/data/broken/*.lackey; do { printf '\6'; cat "$f"; } >"$c/external/seed-$(basename "$f")"; done
{ printf '\026'; printf '==1== Lackey\nI  0040,2\n L 1000,8\n S 1000,8\n M 103e,4\n'; } >"$c/external/seed-lackey"
for f in tests/data/broken/*.oracle; do { printf '\5'; cat "$f"; } >"$c/external/seed-$(basename "$f")"; done
for f in tests/data/broken/*.zst; do { printf '\043'; cat "$f"; } >"$c/external/seed-$(basename "$f")"; done
# Bit 6 (0x40): read again in three chunks by range, which must agree with the whole read.
printf '\101# ids\n1\n2\n0x10\n1\n7\n8\n' >"$c/external/seed-text-chunks"
{ printf '\103'; /usr/bin/python3 -c 'import struct,sys; sys.stdout.buffer.write(struct.pack("<7Q",1,2,1,3,2,9,1) + b"x")'; } >"$c/external/seed-u64-chunks"
{ printf '\126'; printf '==1== Lackey\nI  0040,2\n L 1000,8\n S 1000,8\n M 103e,4\n L 2000,4\n'; } >"$c/external/seed-lackey-chunks"
for f in tests/data/broken/*.oracle; do { printf '\105'; cat "$f"; } >"$c/external/seed-chunks-$(basename "$f")"; done
{ printf '\043'; /usr/bin/python3 -c 'import struct,sys; sys.stdout.buffer.write(b"".join(struct.pack("<Q", i % 37) for i in range(400)))' | zstd -q -c; } >"$c/external/seed-u64-zst"
cp tests/data/broken/truncated_trace.zst "$c/trace/seed-truncated_trace.zst"
cp tests/data/broken/*.perm "$c/permutation/"
cp core/shapes/*.poly tests/data/broken/*.poly "$c/poly/"
# zstd as zstd -d reads it: several frames, and pzstd's skippable ones (\043 = u64, two workers).
u64seed=$(mktemp)
/usr/bin/python3 -c 'import struct,sys; sys.stdout.buffer.write(b"".join(struct.pack("<Q", i % 53) for i in range(3000)))' >"$u64seed"
{ printf '\043'; zstd -q -c "$u64seed"; zstd -q -c "$u64seed"; } >"$c/external/seed-two-frames"
if command -v pzstd >/dev/null; then
  pzstd -q -c -p 2 "$u64seed" >"$u64seed.pz" && { printf '\043'; cat "$u64seed.pz"; } >"$c/external/seed-pzstd"
  [[ -s $c/trace/seed-two_interior.trace ]] && pzstd -q -c "$c/trace/seed-two_interior.trace" >"$c/trace/seed-pzstd.trace.zst"
fi
# Bit 6 on zstd in frames, cut inside records and lines: chunks enter at frame starts (\103 = u64
# in three chunks, \101 = text in three chunks).
frames=$(mktemp -d)
split -b 4801 "$u64seed" "$frames/u."
/usr/bin/python3 -c 'print("\n".join(str(i * 7 % 61) for i in range(300)))' >"$frames/ids"
split -b 301 "$frames/ids" "$frames/t."
{ printf '\103'; for x in "$frames"/u.*; do zstd -q -c "$x"; done; } >"$c/external/seed-u64-frames-chunks"
{ printf '\101'; for x in "$frames"/t.*; do zstd -q -c "$x"; done; } >"$c/external/seed-text-frames-chunks"
# ... and with a seek table at the end (zstd's seekable format, as meshreuse compress writes it).
[[ -x build/release/cli/meshreuse ]] &&
  build/release/cli/meshreuse compress "$u64seed" -o "$frames/tabled.zst" --frame-kib 1 --quiet >/dev/null &&
  { printf '\103'; cat "$frames/tabled.zst"; } >"$c/external/seed-u64-seek-table-chunks"
rm -rf "$frames" "$u64seed" "$u64seed.pz"
/usr/bin/python3 -c 'print("\n".join(str(i) for i in range(336)))' >"$c/permutation/seed-identity"
# Visit orders: the 21 x 16 grid's inner points row by row (the synthetic mesh's interior if its
# ids are row-major; a near miss otherwise, which the fuzzer mends), with a comment.
/usr/bin/python3 -c 'print("# pi\n" + "\n".join(str(j * 21 + i) for j in range(1, 15) for i in range(1, 20)))' >"$c/visit_order/seed-rows"
printf '0\n1\n1\n' >"$c/visit_order/seed-repeat"
# Mesh files: good ones as they are (\000) and to be rehashed (\001), and the broken fixtures.
if [[ -x build/release/cli/meshreuse ]]; then
  for m in two_interior.node plate41.msh; do
    build/release/cli/meshreuse mesh convert "tests/data/$m" -o "$c/mesh_file/good.mrm" --quiet >/dev/null 2>&1 || continue
    { printf '\000'; cat "$c/mesh_file/good.mrm"; } >"$c/mesh_file/seed-${m%.*}"
    { printf '\001'; cat "$c/mesh_file/good.mrm"; } >"$c/mesh_file/seed-${m%.*}-rehash"
    rm -f "$c/mesh_file/good.mrm"
  done
fi
for f in tests/data/broken/*.mrm; do { printf '\001'; cat "$f"; } >"$c/mesh_file/seed-$(basename "$f")"; done
# Summaries: their payloads (the harness writes the header), from chunks of a mesh trace.
if [[ -x build/release/cli/meshreuse && -s $c/trace/seed-two_interior.trace ]]; then
  for k in 0/1 1/2; do
    build/release/cli/meshreuse analyze "$c/trace/seed-two_interior.trace" --chunk $k \
      --summary-out "$c/summary/whole" --quiet 2>/dev/null &&
      tail -c +33 "$c/summary/whole" >"$c/summary/seed-${k/\//-of-}" && rm -f "$c/summary/whole"
  done
fi

run() {  # run HARNESS: one libFuzzer session, its log and exit code
  local h=$1 rc=0
  ASAN_OPTIONS=detect_leaks=1:quarantine_size_mb=32 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "build/fuzz/tests/fuzz/fuzz_$h" -max_total_time="$secs" -rss_limit_mb=512 -malloc_limit_mb=64 \
    -timeout=10 -print_final_stats=1 -artifact_prefix="build/fuzz/artifacts/$h-" "$c/$h" \
    >"build/fuzz/logs/$h.log" 2>&1 || rc=$?
  echo "$rc" >"build/fuzz/logs/$h.rc"
}
# Option values and output paths (tests/cli/fuzz_options.sh) against the release program, for
# as long as one harness runs and beside them (the harnesses are odd in number: alone at the end,
# it left a core idle): batches of 200 seeded cases, a new seed each.
options() {
  local rc=0 s=1 end=$((SECONDS + secs))
  while ((SECONDS < end)); do
    bash tests/cli/fuzz_options.sh build/release/cli/meshreuse tests/data 200 "$s" \
      >>build/fuzz/logs/options.log 2>&1 || rc=1
    s=$((s + 1))
  done
  echo "$rc" >build/fuzz/logs/options.rc
}
[[ -x build/release/cli/meshreuse ]] && harnesses+=(options)
echo "== fuzzing ${#harnesses[@]} harnesses, ${secs} s each, two at a time" >&2
running=0
for h in "${harnesses[@]}"; do
  if [[ $h == options ]]; then options & else run "$h" & fi
  running=$((running + 1))
  if ((running == 2)); then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true

failed=0
printf '%-12s %12s %8s %8s %8s  %s\n' harness executions cov features corpus result
for h in "${harnesses[@]}"; do
  log=build/fuzz/logs/$h.log
  rc=$(cat "build/fuzz/logs/$h.rc")
  execs=$(awk '/stat::number_of_executed_units/ {print $2}' "$log" | tail -n 1)
  [[ $h == options ]] && execs=$(awk '/^option fuzz:/ {n += $3} END {print n}' "$log")
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -n 1 || true)
  cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(sed -n 's/.*corp: \([0-9]*\).*/\1/p' <<<"$last")
  result=ok
  if [[ $rc != 0 ]]; then
    result="FINDING (exit $rc; $log, build/fuzz/artifacts/$h-*)"
    failed=1
  fi
  printf '%-12s %12s %8s %8s %8s  %s\n' "$h" "${execs:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}" "$result"
done
if ((failed)); then
  for h in "${harnesses[@]}"; do
    [[ $(cat "build/fuzz/logs/$h.rc") == 0 ]] || { echo "--- $h"; grep -B6 -A30 -m1 -E "ERROR|runtime error|==[0-9]+==" "build/fuzz/logs/$h.log" | awk 'NR <= 46'; }
  done
  exit 1
fi
echo "fuzz: ${#harnesses[@]} passed, 0 failed"
