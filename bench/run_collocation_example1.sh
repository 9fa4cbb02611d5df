#!/usr/bin/env bash
# Example 1 of the hybrid-collocation paper (1D static bond-based PD with
# the manufactured solution u = sin(x/10), Table 1, Fig. 9): the standard
# scheme (exact partial lengths) against the collocation schemes
# Proposed-A/B/C (orders 2, 4, 6), m- and delta-convergence, in one command:
#
#   bash bench/run_collocation_example1.sh [--quick] [--output-dir DIR]
#
# Builds perideal-collocation-example1 in build/ (configuring it first if
# needed; BUILD_DIR=... selects another build directory, and
# PERIDEAL_SKIP_BUILD=1 uses the binary as it is), runs it and plots the
# results: DIR/example1_m_convergence.csv, example1_delta_convergence.csv,
# stdout.txt, and with matplotlib example1_fig9.png and
# example1_error_vs_time.png (default DIR: results/collocation_example1).
# The full run takes about a second; --quick runs three cases per study and
# fails unless the closed-form checks (cosine integral, body force of
# Eq. 69, moments, patch tests, Table 1) and the paper's claims that the
# full run supports hold (bench/collocation_example1.md).
set -euo pipefail
cd "$(dirname "$0")/.."

source bench/driver_study.sh # plot_if_possible

quick=()
out=results/collocation_example1
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=(--quick) ;;
    --output-dir) out="$2"; shift ;;
    *) echo "usage: bash bench/run_collocation_example1.sh [--quick] [--output-dir DIR]" >&2; exit 2 ;;
  esac
  shift
done
mkdir -p "$out"

build="${BUILD_DIR:-build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
[ "${PERIDEAL_SKIP_BUILD:-0}" = 1 ] \
  || cmake --build "$build" -j2 --target perideal-collocation-example1 > /dev/null

# The timings are single-threaded; other load on the machine shows in them.
"$build/bin/perideal-collocation-example1" "${quick[@]}" --output-dir "$out" \
  | tee "$out/stdout.txt"
echo

plot_if_possible bench/plot_collocation_example1.py --input-dir "$out"
