#!/usr/bin/env bash
# Installs what meshreuse needs on a Debian machine, only what is missing, with apt-get (as root).
# Triangle (Shewchuk's mesh generator) is Debian's triangle-bin, in the non-free component: a
# sources entry for non-free is added when no configured source offers it yet.
# Usage: scripts/setup.sh [--report-only] [--with-plots] [--with-tests] [--with-fuzz]
#        (sourced or run; idempotent)
#   --report-only  what scripts/reproduce.sh needs (the `meshreuse` program's build and its report),
#                  without Open MPI, PT-Scotch (meshreuse-mpi) and Gmsh (the tests): 64 packages
#                  and 8 s fewer on a fresh machine
set -euo pipefail

want_plots=0 want_tests=0 want_fuzz=0 report_only=0
for a in "$@"; do
  [[ $a == --report-only ]] && report_only=1
  [[ $a == --with-plots ]] && want_plots=1
  [[ $a == --with-tests ]] && want_tests=1
  [[ $a == --with-fuzz ]] && want_fuzz=1
done

pkgs=(build-essential cmake ninja-build pkg-config libgtest-dev libbenchmark-dev libboost-program-options-dev
      libpapi-dev libzstd-dev zstd zlib1g-dev libmetis-dev libboost-graph-dev triangle-bin time
      nlohmann-json3-dev libopenmpi-dev openmpi-bin libscotch-dev libptscotch-dev gmsh
      pybind11-dev python3-dev python3-numpy)
# (libscotch-dev: the scotch partition; libptscotch-dev: meshreuse-mpi's ptscotch partition;
# gmsh: the tests check that Gmsh reads the split sets that `mesh partition --split` writes;
# pybind11-dev, python3-dev, python3-numpy: the Python module, `import meshreuse`; kept with
# --report-only, as GoogleTest and Google Benchmark are: the default configure wants them, and a
# build folder configured without pybind11 would rebuild everything position-independent later.)
if ((report_only && !want_tests)); then
  keep=()
  for p in "${pkgs[@]}"; do
    case $p in libopenmpi-dev | openmpi-bin | libptscotch-dev | gmsh) ;; *) keep+=("$p") ;; esac
  done
  pkgs=("${keep[@]}")
fi
((want_plots)) && pkgs+=(python3-matplotlib python3-numpy)
# meshio: the tests read the .vtu and .pvtu files meshreuse writes with a reader nobody here wrote.
# pytest and scipy: the Python module's tests and examples (scipy's RCM raced against ours).
((want_tests)) && pkgs+=(python3-meshio python3-numpy python3-pytest python3-scipy python3-matplotlib)
# libFuzzer and clang's OpenMP runtime for the fuzz harnesses (scripts/fuzz.sh)
((want_fuzz)) && pkgs+=(clang libclang-rt-14-dev libomp-14-dev)

missing=()
for p in "${pkgs[@]}"; do
  [[ $(dpkg-query -W -f='${Status}' "$p" 2>/dev/null) == *'install ok installed'* ]] || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
  echo "setup: missing Debian packages: ${missing[*]}" >&2
  echo "setup: run as root, or: sudo apt-get install ${missing[*]}" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
# triangle-bin lives in non-free; add a deb822 entry for it unless one exists already.
if [[ " ${missing[*]} " == *" triangle-bin "* ]] &&
   ! grep -rqsE '^\s*(Components:|deb\s).*\snon-free(\s|$)' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  suite=bookworm
  if [[ -r /etc/os-release ]]; then
    suite=$(. /etc/os-release && echo "${VERSION_CODENAME:-bookworm}")
  fi
  echo "setup: adding Debian non-free component (for triangle-bin) to /etc/apt/sources.list.d/meshreuse-non-free.sources" >&2
  cat > /etc/apt/sources.list.d/meshreuse-non-free.sources <<SRC
Types: deb
URIs: http://deb.debian.org/debian
Suites: ${suite}
Components: non-free
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
fi
echo "setup: installing ${missing[*]} (log: /tmp/meshreuse-apt.log)" >&2
if ! { apt-get update -q && apt-get install -y -q --no-install-recommends "${missing[@]}"; } \
    >/tmp/meshreuse-apt.log 2>&1; then
  tail -n 30 /tmp/meshreuse-apt.log >&2
  echo "setup: apt-get failed; see /tmp/meshreuse-apt.log" >&2
  exit 1
fi
