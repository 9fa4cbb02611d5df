#!/usr/bin/env bash
# PeriDEAL set-up: installs the Debian packages PeriDEAL needs (only those
# missing), configures into build/ and builds with -j2. Then, depending on
# the argument:
#   scripts/setup.sh --run    runs the main job (a small default example)
#   scripts/setup.sh --test   runs the whole test suite (ctest)
#   scripts/setup.sh          only installs and builds
set -euo pipefail
cd "$(dirname "$0")/.."

mode="${1:-}"
case "$mode" in
  ""|--run|--test) ;;
  *) echo "usage: scripts/setup.sh [--run|--test]" >&2; exit 2 ;;
esac

# Build: deal.II 9.4 (with Trilinos, p4est, PETSc, MUMPS), compilers, MPI.
# Tests: numdiff, mpirun (openmpi-bin); the scripts use only what a minimal
# Debian system has besides (bash, sed, mawk, grep, coreutils, diffutils):
# tables are printed by bench/csv_table.awk, not util-linux's column.
# Reference generators, benchmark references and plots: Debian's
# /usr/bin/python3 with numpy, scipy, mpmath and matplotlib. LAMMPS, used
# only by the side-by-side benchmark, is not installed here (that script
# says so and how to get it).
packages=(libdeal.ii-dev cmake make g++ openmpi-bin libopenmpi-dev numdiff
          python3 python3-numpy python3-scipy python3-mpmath python3-matplotlib)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" \
    || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "-- Installing missing Debian packages: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq \
    --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2

# Open MPI refuses to run as root unless told; CI and containers run as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1

case "$mode" in
  --run)
    # A small 3D LPS problem with a manufactured solution: prints the error
    # and the phase timings, writes output/solution_0.pvtu for ParaView.
    build/bin/perideal parameters/default.prm
    ;;
  --test)
    cd build
    ctest -j2 --output-on-failure
    ;;
esac
