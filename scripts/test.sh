#!/usr/bin/env bash
# The README's test command: installs what is missing (apt-get, as root), builds a Release and an
# ASan+UBSan build with warnings as errors, and runs every test (GoogleTest suites and CLI checks)
# in both, runs the scale smoke test (scripts/scale_smoke.sh: 10^6 vertices, memory budget) and the
# report pipeline on small meshes (scripts/reproduce.sh --quick: every table in CSV, Markdown and
# LaTeX, every figure in PNG and PDF, the results README, checked well-formed by
# tests/scripts/check_report.py), then fuzzes every reader for 20 s each (scripts/fuzz.sh;
# libFuzzer from clang). Exit 0 only when everything passed.
# Usage: scripts/test.sh [--quick]   (--quick: Release build only, no sanitizers, no fuzzing)
set -euo pipefail
cd "$(dirname "$0")/.."

source scripts/lib.sh
usage() { lib_usage 2 9; }
LIB_USAGE=usage
quick=0
lib_options --quick=quick! -- "$@"
bash scripts/setup.sh --with-plots --with-tests

jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS
stage() { printf '== [%2d:%02d] %s\n' $(((SECONDS - start) / 60)) $(((SECONDS - start) % 60)) "$*" >&2; }
build() {  # build DIR [cmake args...]
  local dir=$1
  shift
  stage "configure $dir"
  # Ninja for a fresh folder (less overhead than make's recursive Makefiles on a fresh clone); a
  # folder configured before keeps the generator it has.
  if [[ ! -f $dir/CMakeCache.txt ]] && command -v ninja >/dev/null; then set -- -G Ninja "$@"; fi
  cmake -S . -B "$dir" -DMESHREUSE_WERROR=ON "$@" >"$dir.configure.log" 2>&1 || { cat "$dir.configure.log"; return 1; }
  stage "build $dir"
  cmake --build "$dir" -j"$jobs"
}
run_tests() {  # run_tests DIR [ctest args...]
  local dir=$1
  shift
  stage "test $dir"
  (cd "$dir" && ctest -j"$jobs" --output-on-failure --timeout 600 "$@")
}

mkdir -p build
build build/release -DCMAKE_BUILD_TYPE=Release
if ((quick == 0)); then
  # The fuzzers' build (clang: about 280 s of CPU on a fresh clone) in the background at the lowest
  # priority, from here to the fuzzing: the tests leave a core idle for minutes while MPI jobs
  # launch and scripts wait on processes (.ci/run: 48 min of CPU in 26 min 51 s on two cores,
  # 5.6 core-minutes idle), and the builds, at normal priority, leave it almost nothing. In its
  # own session, so that a failure here ends it too; where the kernel schedules sessions as
  # groups (autogroup), nice alone does not lower a group against another, so the group's nice
  # is set too (with nice only, the Release tests took 6 min 50 s instead of 3 min 50 s).
  # Measured from fresh clones: .ci/run 26 min 0 s against 26 min 51 s, the tests 16% slower
  # beside the build (caches and memory shared), the fuzzing stage 1:52 against 4:33.
  stage "build build/fuzz in the background (nice 19; log build/fuzz.prebuild.log)"
  setsid bash -c 'echo 19 >/proc/self/autogroup 2>/dev/null; exec nice -n 19 bash scripts/fuzz.sh --build-only' \
    >build/fuzz.prebuild.log 2>&1 &
  fuzz_build=$!
  trap 'kill -- -"$fuzz_build" 2>/dev/null || true' EXIT
fi
run_tests build/release
stage "scale smoke test: a 10^6-vertex mesh through every command, memory checked"
bash scripts/scale_smoke.sh build/release/cli/meshreuse
stage "the report on small meshes: scripts/reproduce.sh --quick, every file checked"
rm -rf build/quick-report
bash scripts/reproduce.sh --quick --quiet --out build/quick-report >/dev/null
/usr/bin/python3 tests/scripts/check_report.py build/quick-report figure1 profile histograms \
  miss-rates time speedup speedup-mean gain meshes smoothing orderings figure11 machine-misses \
  predicted-speedup kernels
if ((quick == 0)); then
  # -O1: ASan's advice for a usable speed (the tests run about 3x faster than at -O0); Debug keeps
  # the assertions. -g1: line tables only, which is what a sanitizer's report needs (file and line
  # of every frame); full debug information doubled the compile time of the heavy files.
  build build/asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DMESHREUSE_SANITIZE=ON
  # The plotting and docs checks run Python alone (no meshreuse code): the Release run has them.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    run_tests build/asan -E '^scripts\.(plots|docs)$'
fi
if ((quick == 0)); then
  # 20 s a reader keeps the whole run near 30 minutes on two cores (the corpora start from the
  # seeds on a fresh clone); scripts/fuzz.sh alone fuzzes 60 s a reader, or as long as asked.
  stage "wait for build/fuzz"
  wait "$fuzz_build" || { tail -n 40 build/fuzz.prebuild.log; exit 1; }
  stage "fuzz every reader, 20 s each"
  bash scripts/fuzz.sh 20
fi
ln -sf build/release/compile_commands.json compile_commands.json
stage "all tests passed"
