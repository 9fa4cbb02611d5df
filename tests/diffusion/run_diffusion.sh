#!/usr/bin/env bash
# Usage: run_diffusion.sh PERIDEAL NUMDIFF NPROCS INPUT.prm EXPECTED.output
#
# Runs a diffusion input on NPROCS MPI processes in a fresh directory and
# checks:
#  - exit code 0, a PVD time series whose every record exists with one VTU
#    piece per process, no temporary file left;
#  - the assertions written in the input as comment lines (the
#    verification; each input says what its reference is):
#      # check: final_relative_error <tol>   relative l2 error (paper Eq. 66,
#                                            free nodes) in the last row
#      # check: final_max_error <tol>        largest nodal error, last row
#      # check: max_iterations <n>           every implicit solve took <= n
#      # check: conserved_total <tol>        |total - total(0)| <= tol |total(0)|
#                                            in every row (closed systems)
#      # check: final_column <name> <min> <max>   last value of a column
#  - the history (history.csv, without the iteration counts) against
#    EXPECTED.output by numdiff (relative 1e-7, absolute 1e-12), the same
#    file for 1 and 2 processes: the
#    partition must not change the answer beyond round-off (a snapshot for
#    regressions and the 1-vs-2-process check).
set -u
perideal="$1"; numdiff="$2"; nprocs="$3"; input="$4"; expected="$5"
. "$(cd "$(dirname "$0")" && pwd)/../run_checks.sh"
name=$(basename "$input" .prm)
work="$(pwd)/${name}.np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cp "$input" input.prm
run_perideal "$perideal" "$nprocs"
rc=$?
[ $rc -eq 0 ] || { cat log; echo "FAIL: perideal exited with $rc"; exit 1; }
check_output_series "$nprocs"
csv="$dir/history.csv"
[ -f "$csv" ] || { echo "FAIL: no $csv"; exit 1; }
grep "step\|steady" log | tail -1

column() { awk -F, -v name="$1" 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == name) c = k } END { if (!c) exit 1 }' "$csv" \
  || { echo "FAIL: no column $1 in $csv"; exit 1; }; }
check_last() { # name column tolerance
  column "$2"
  awk -F, -v name="$2" -v tol="$3" 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == name) c = k; next } { v = $c }
    END { printf "%s at the end: %.6e (at most %s)\n", name, v, tol; exit !(v <= tol) }' "$csv" \
    || { cat "$csv"; echo "FAIL: $1"; exit 1; }
}
tol=$(sed -n 's/^# check: final_relative_error *//p' input.prm)
[ -z "$tol" ] || check_last "error too large" relative_l2_error "$tol"
tol=$(sed -n 's/^# check: final_max_error *//p' input.prm)
[ -z "$tol" ] || check_last "error too large" max_error "$tol"
tol=$(sed -n 's/^# check: max_iterations *//p' input.prm)
if [ -n "$tol" ]; then
  awk -F, -v n="$tol" 'NR > 1 && $6 > m { m = $6 } END { printf "largest solver iterations %d (at most %d)\n", m, n; exit !(m <= n && m > 0) }' "$csv" \
    || { cat "$csv"; echo "FAIL: too many iterations"; exit 1; }
fi
tol=$(sed -n 's/^# check: conserved_total *//p' input.prm)
if [ -n "$tol" ]; then
  awk -F, -v tol="$tol" 'NR == 2 { t0 = $3 } NR > 1 { d = ($3 - t0) / t0; if (d < 0) d = -d; if (d > m) m = d }
    END { printf "largest relative change of the total %.3e (at most %s)\n", m, tol; exit !(m <= tol) }' "$csv" \
    || { cat "$csv"; echo "FAIL: the total amount is not conserved"; exit 1; }
fi
while read -r name low high; do
  [ -n "$name" ] || continue
  column "$name"
  awk -F, -v name="$name" -v lo="$low" -v hi="$high" 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == name) c = k; next } { v = $c }
    END { printf "%s at the end: %.6e (in [%s, %s])\n", name, v, lo, hi; exit !(v >= lo && v <= hi) }' "$csv" \
    || { cat "$csv"; echo "FAIL: $name out of range"; exit 1; }
done < <(sed -n 's/^# check: final_column *//p' input.prm)
# Solver iterations (column 6) may differ by one between partitions: left
# out of the comparison (the max_iterations check bounds them).
drop_iterations() { awk -F, -v OFS=, '{ $6 = ""; print }' "$1"; }
drop_iterations "$csv" > history.compare
drop_iterations "$expected" > expected.compare
"$numdiff" -q -s ', \t\n' -r 1e-7 -a 1e-12 history.compare expected.compare > /dev/null 2>&1 \
  || { "$numdiff" -s ', \t\n' -r 1e-7 -a 1e-12 history.compare expected.compare | tail -20; echo "FAIL: history differs from $expected"; exit 1; }
echo "PASS"
