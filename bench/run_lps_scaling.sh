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
# overrides the cells per direction. Fails unless 1 and 2 processes give the
# same error.
set -euo pipefail
cd "$(dirname "$0")/.."

source bench/driver_study.sh
driver_study_setup results/lps_scaling "$@"

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

plot_if_possible bench/plot_lps_scaling.py "$csv" "$out"

# 1 and 2 processes must give the same answer: relative L2 errors equal to
# 1e-8 (CG stops at 1e-10; the partition changes only round-off).
awk -F, 'NR > 1 { e[$5 "," $4] = $16; n[$5] = 1 }
         END { for (k in n) { a = e[k ",1"]; b = e[k ",2"];
                 if (a == "" || b == "" || (a - b > 1e-8 * a) || (b - a > 1e-8 * a)) {
                   print "1 and 2 processes differ for N = " k ": " a " vs " b; bad = 1 } }
               exit bad }' "$csv"
