#!/usr/bin/env bash
# Partial-volume benchmark and the data and plots of Figs. 10 and 11 of
# Scabbia et al. (2022), in one command (see bench/README.md):
#
#   bash bench/run_partial_volumes.sh [--quick]
#
# Builds the two programs in build/ if needed (configuring build/ first if
# scripts/setup.sh has not), runs them, and writes everything under
# results/partial_volumes/ and results/partial_volume_figures/.
# BUILD_DIR=... selects another build directory, REFERENCE_DIR=... another
# directory holding the mpmath reference beta_3d.csv (default: the one in
# tests/quadrature/reference).
set -euo pipefail
cd "$(dirname "$0")/.."

quick=()
case "${1:-}" in
  "") ;;
  --quick) quick=(--quick) ;;
  *) echo "usage: bash bench/run_partial_volumes.sh [--quick]" >&2; exit 2 ;;
esac

build="${BUILD_DIR:-build}"
reference=()
[ -n "${REFERENCE_DIR:-}" ] && reference=(--reference-dir "$REFERENCE_DIR")
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j2 --target perideal-bench-partial-volumes \
  perideal-partial-volume-figures

bench_dir=results/partial_volumes
figures_dir=results/partial_volume_figures
mkdir -p "$bench_dir" "$figures_dir"

# The timings are single-threaded; other load on the machine shows in them.
"$build/bin/perideal-bench-partial-volumes" "${quick[@]}" "${reference[@]}" \
  --output-dir "$bench_dir" | tee "$bench_dir/stdout.txt"
echo
"$build/bin/perideal-partial-volume-figures" "${quick[@]}" \
  --output-dir "$figures_dir" | tee "$figures_dir/stdout.txt"
echo

if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  /usr/bin/python3 bench/plot_partial_volumes.py \
    --benchmark-dir "$bench_dir" --figures-dir "$figures_dir"
else
  echo "matplotlib is not importable by /usr/bin/python3 (Debian package" \
       "python3-matplotlib): CSV files written, plots skipped." >&2
fi
