# Shared by the shell tests (sourced): pass/fail counting, commands checked for their exit status
# and output, and the small traces of every format the chunk and MPI tests compare on.
# The caller sets $tmp (a scratch folder; `scratch` makes one) and reads $pass and $fail at the
# end. MPI tests call mpi_setup first.
pass=0 fail=0
scratch() {  # scratch : $tmp, a new folder removed when the script exits
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
}
mpi_setup() {  # mpi_setup MPIEXEC : Open MPI as root, oversubscribed, yielding; run NP ARGS...
  if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
  export OMPI_MCA_mpi_yield_when_idle=1 OMPI_MCA_rmaps_base_oversubscribe=1
  export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0  # Open MPI's own allocations
  mpiexec=$1
  run() { timeout 120 "$mpiexec" --oversubscribe -np "$@"; }
}
check() {  # check NAME EXPECTED_RC COMMAND... ; stdout+stderr in $tmp/out
  local name=$1 want=$2
  shift 2
  "$@" >"$tmp/out" 2>&1
  local rc=$?
  if [[ $rc -eq $want ]]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $name: exit $rc, expected $want"; sed 's/^/    /' "$tmp/out" | head -20; fi
}
contains() {  # contains NAME TEXT : the last output contains TEXT
  if grep -qF -- "$2" "$tmp/out"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1: output lacks '$2'"; sed 's/^/    /' "$tmp/out" | head -20; fi
}
outputs() {  # outputs PREFIX COMMAND... : an analysis's table and histogram, profile, MRC files
  # (the table without a sampled run's *_ci95 bounds: a merged or distributed run keeps no per-id
  # counts to compute them from, so only the serial one has them)
  local p=$1
  shift
  "$@" --csv --quiet --histogram-csv "$p.h" --profile-csv "$p.p" --mrc-csv "$p.m" >"$p.full" 2>"$p.err"
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) keep[i] = $i !~ /_ci95$/ }
           { s = ""; for (i = 1; i <= NF; i++) if (keep[i]) s = s (s == "" ? "" : ",") $i; print s }' "$p.full" >"$p.t"
}
same() {  # same NAME A B : the outputs at prefixes A and B identical, and A's not empty
  local x ok=1
  [[ -s "$2.t" && -s "$2.h" ]] || { ok=0; echo "FAIL $1: no reference output"; cat "$2.err"; }
  for x in t h p m; do
    [[ -e "$2.$x" || -e "$3.$x" ]] || continue
    cmp -s "$2.$x" "$3.$x" || { ok=0; echo "FAIL $1: .$x differs"; diff "$2.$x" "$3.$x" | head -5; head -5 "$3.err"; }
  done
  if ((ok)); then pass=$((pass + 1)); else fail=$((fail + 1)); fi
}
# make_traces MESHREUSE DATA : in $tmp, a meshreuse trace (2 threads, 3 sweeps) and a zstd one,
# and scan, uniform, hashed 64-bit, 3-access (u64), u32, oracle, text (a BOM, comments, blank
# lines, CRLF, hex) and lackey traces; $trace_specs lists "FILE FORMAT GRANULARITY" for each
# foreign one.
make_traces() {
  "$1" trace "$2/plate41.msh" --ordering rdr -k 3 -t 2 -o "$tmp/mesh.trace" --quiet &>/dev/null
  "$1" trace "$2/plate41.msh" -k 2 -o "$tmp/mesh.trace.zst" --compress --quiet &>/dev/null
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
with open(f"{d}/ids.txt", "wb") as f:
    lines = ["\ufeff# ids"] + [("0x%x" if i % 5 == 0 else "%d") % rng.randrange(700) +
                               ("  # c" if i % 7 == 0 else "") for i in range(4001)]
    lines[100:100] = ["", "   ", "# comment"]
    f.write(("\r\n".join(lines[:2000]) + "\n" + "\n".join(lines[2000:])).encode())
PY
  zstd -q -d -c "$2/lackey/transpose.lackey.zst" >"$tmp/transpose.lackey"
  trace_specs=("scan.u64 u64 element" "uniform.u64 u64 element" "hashed.u64 u64 element"
               "tiny.u64 u64 element" "ids.u32 u32 line" "cache.oracle oracle element"
               "ids.txt text element" "transpose.lackey lackey line")
}
framed() {  # framed SRC DST BYTES : SRC in zstd frames of BYTES (the zstd tool, no seek table)
  rm -f "$tmp"/fr.*
  split -b "$3" -a 4 "$1" "$tmp/fr."
  for x in "$tmp"/fr.*; do zstd -q -c "$x"; done >"$2"
}
