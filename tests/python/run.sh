#!/usr/bin/env bash
# The Python module's tests (test_meshreuse.py, pytest) and the examples of scripts/examples/, with
# Debian's python3 and the package built in PYDIR. Skipped (77) without pytest. In a sanitizer
# build the module needs the sanitizers' runtimes loaded first (python3 itself is not built with
# them): LD_PRELOAD of libasan and libubsan, leak checking off (the interpreter's own allocations
# at exit read as leaks) and a small quarantine (the memory test measures resident memory).
# Usage: run.sh MESHREUSE_BIN PYDIR TEST_DATA
set -euo pipefail
bin=$1 pydir=$2 data=$3
here=$(cd "$(dirname "$0")" && pwd)
py=/usr/bin/python3
[[ -x $py ]] || py=python3
if ! "$py" -c 'import pytest, numpy' 2>/dev/null; then
  echo "skipped: Debian's python3-pytest and python3-numpy are needed (scripts/setup.sh --with-tests)"
  exit 77
fi
module=$(ls "$pydir"/meshreuse/_meshreuse*.so)
# Not `ldd | grep -q` under pipefail: grep leaving at the first match can kill ldd with SIGPIPE,
# the pipeline then fails, and the module loads without the runtimes (an abort at import, 1 run in 2
# under a loaded `ctest -j2`).
if [[ $(ldd "$module") == *libasan* ]]; then
  export LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)"
  export ASAN_OPTIONS=detect_leaks=0:quarantine_size_mb=4:abort_on_error=1
fi
export PYTHONPATH=$pydir MESHREUSE_BIN=$bin MESHREUSE_TEST_DATA=$data
"$py" -m pytest -q -p no:cacheprovider "$here/test_meshreuse.py"
# The examples, as a user runs them, on small inputs.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
examples=$here/../../scripts/examples
"$py" "$examples/histogram_mrc.py" --out "$tmp/h.png" --ids 200000
"$py" "$examples/race_rcm.py" "$data/plate41.msh" --repeat 3 --out "$tmp/race"
"$py" "$examples/chunked.py" --chunks 3 --ids 100000 --dir "$tmp/chunks"
ls "$tmp/h.png" "$tmp/race/race.csv" >/dev/null
echo "python: tests and examples passed"
