#!/usr/bin/env bash
# Cost of a 3D LPS solve with the perideal driver as the grid grows: unit
# cube, m-ratio 3, Gaussian influence, exact partial volumes (uniform-grid
# table), quadratic manufactured field with the displacement prescribed in
# a layer one horizon thick, CG + Jacobi to 1e-10; on 1 and 2 MPI processes.
#
#   bash bench/run_lps_scaling.sh [--quick] [--output-dir DIR]
#
# Writes DIR/scaling.csv (the driver's summary: phase times, nonzeros, peak
# memory summed over processes, errors), DIR/logs/, and with matplotlib
# DIR/time_vs_size.png (time of each phase and peak memory against the
# number of nodes). DIR defaults to results/lps_scaling. SIZES="16 24"
# overrides the cells per direction.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0
out=results/lps_scaling
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --output-dir) out="$2"; shift ;;
    *) echo "usage: bash bench/run_lps_scaling.sh [--quick] [--output-dir DIR]" >&2; exit 2 ;;
  esac
  shift
done
mkdir -p "$out/logs"
out=$(cd "$out" && pwd)

build="${BUILD_DIR:-build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
# Under ctest the build is there already (and must not run twice at once).
[ "${PERIDEAL_SKIP_BUILD:-0}" = 1 ] || cmake --build "$build" -j2 --target perideal > /dev/null
perideal="$(cd "$build" && pwd)/bin/perideal"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

if [ $quick -eq 1 ]; then sizes="${SIZES:-8 10}"; else sizes="${SIZES:-10 14 20 26 32 38}"; fi

csv="$out/scaling.csv"
rm -f "$csv"
for n in $sizes; do
  for np in 1 2; do
    prm="$out/logs/cube_${n}_np${np}.prm"
    sed -e "s/set Subdivisions = 20, 20, 20/set Subdivisions = $n, $n, $n/" \
        -e "s/set Dirichlet layer thickness = 2/set Dirichlet layer thickness = 1/" \
        -e "s/set Method                = direct/set Method = CG\n  set Preconditioner = Jacobi\n  set Relative tolerance = 1e-10/" \
        -e "s|set Base name = solution|set Base name = solution\n  set Write VTU = false\n  set Summary file = $csv|" \
        parameters/default.prm > "$prm"
    log="$out/logs/cube_${n}_np${np}.log"
    printf 'N = %3s^3, %d process(es): ' "$n" "$np"
    if [ "$np" -eq 1 ]; then
      "$perideal" "$prm" > "$log" 2>&1 || { cat "$log"; exit 1; }
    else
      mpirun --oversubscribe -np 2 "$perideal" "$prm" > "$log" 2>&1 || { cat "$log"; exit 1; }
    fi
    sed -n 's/^total wall time/total/p' "$log"
  done
done
echo "wrote $csv"

if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  /usr/bin/python3 bench/plot_lps_scaling.py "$csv" "$out"
else
  echo "matplotlib is not importable by /usr/bin/python3: CSV written, plots skipped." >&2
fi
