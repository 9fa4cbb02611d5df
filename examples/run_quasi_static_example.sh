#!/usr/bin/env bash
# Usage: run_quasi_static_example.sh PERIDEAL NPROCS EXAMPLE.prm LEFM TOL SED_EDITS
# Runs a quasi-static fracture example, made cheap by SED_EDITS, in a fresh
# directory and checks that it finishes, reports complete failure, writes
# its load-displacement CSV and damage series, that bonds first break
# beyond the pre-crack (at the first equilibrium of that step) at a reaction
# within the relative TOL of LEFM, and
# (with matplotlib) that the example's plot script draws the curve.
set -u
perideal="$1"; nprocs="$2"; input="$3"; lefm="$4"; tol="$5"; edits="$6"
work="$(pwd)/$(basename "$input" .prm).np$nprocs"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
sed -e "$edits" "$input" > input.prm
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun --oversubscribe -np "$nprocs" "$perideal" input.prm --threads 1 > log 2>&1 \
  || { cat log; echo "FAIL: exit code"; exit 1; }
grep "complete failure at t" log || { cat log; echo "FAIL: no complete failure"; exit 1; }
csv=output/load_displacement.csv
[ -f "$csv" ] && [ -f output/solution.pvd ] || { echo "FAIL: no $csv or PVD"; exit 1; }
awk -F, -v lefm="$lefm" -v tol="$tol" 'NR == 2 { b0 = $5; k = $4 / $2 } NR > 1 && !found && $5 > b0 { found = 1; r = k * $2 }
  END { d = r / lefm - 1; printf "bonds first break at a reaction of %.4g, LEFM %.4g: %+.2f %% (tolerance %g %%)\n", r, lefm, 100 * d, 100 * tol
        if (d < 0) d = -d; exit !(found && d <= tol) }' "$csv" \
  || { cat "$csv"; echo "FAIL: initiation against LEFM"; exit 1; }
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  /usr/bin/python3 "$(dirname "$input")/plot_load_displacement.py" "$csv" "$lefm" \
    && [ -f output/load_displacement.png ] || { echo "FAIL: no plot"; exit 1; }
fi
echo "OK"
