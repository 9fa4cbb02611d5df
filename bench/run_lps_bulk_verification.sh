#!/usr/bin/env bash
# The LPS bulk-node verification of Sect. 4 of Scabbia et al. (2022) (Figs.
# 11-13; doc/verification-bulk.md) in one command:
#
#   bash bench/run_lps_bulk_verification.sh [--quick]
#
# Builds perideal-lps-bulk-verification in build/ (configuring it first if
# needed; BUILD_DIR=... selects another build directory), runs it and plots
# the results: results/lps_bulk_verification/lps_bulk_verification.csv,
# stdout.txt, fig11_lps.png, fig12.png and fig13.png.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=()
case "${1:-}" in
  "") ;;
  --quick) quick=(--quick) ;;
  *) echo "usage: bash bench/run_lps_bulk_verification.sh [--quick]" >&2; exit 2 ;;
esac

build="${BUILD_DIR:-build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j2 --target perideal-lps-bulk-verification

out=results/lps_bulk_verification
mkdir -p "$out"
# The timings are single-threaded; other load on the machine shows in them.
"$build/bin/perideal-lps-bulk-verification" "${quick[@]}" --output-dir "$out" \
  | tee "$out/stdout.txt"
echo

if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  /usr/bin/python3 bench/plot_lps_bulk_verification.py --input-dir "$out"
else
  echo "matplotlib is not importable by /usr/bin/python3 (Debian package" \
       "python3-matplotlib): CSV file written, plots skipped." >&2
fi
