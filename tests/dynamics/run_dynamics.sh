#!/usr/bin/env bash
# Usage: run_dynamics.sh PERIDEAL NUMDIFF NPROCS INPUT.prm EXPECTED.output
#
# Runs an explicit-dynamics input on NPROCS MPI processes in a fresh
# directory and checks:
#  - exit code 0, a PVD time series whose every record exists with one VTU
#    piece per process, no temporary file left;
#  - the assertions written in the input as comment lines
#      # check: max_energy_drift <tolerance>
#          max |balance - balance(0)| / max (kinetic + elastic) over all rows
#          (balance = kinetic + elastic - external work: velocity Verlet
#          keeps it constant up to its O(dt^2) oscillation)
#      # check: min_new_broken_bonds <n>
#          bonds broken during the run (beyond the pre-crack) >= n
#      # check: crack_angle <x0> <y0> <min_deg> <max_deg>
#          the tracked crack tip (columns tip_x, tip_y) at the end lies in
#          the direction atan2(tip_y - y0, tip_x - x0) within [min, max]
#          degrees, at least two cells away from (x0, y0)
#  - the energy history (energies.csv: energies to 1e-8 relative, broken
#    bonds exactly) against EXPECTED.output, the same file for 1 and 2
#    processes: the partition must not change the answer (a snapshot for
#    regressions and the 1-vs-2-process check; the assertions above are the
#    verification).
set -u
perideal="$1"; numdiff="$2"; nprocs="$3"; input="$4"; expected="$5"
name=$(basename "$input" .prm)
work="$(pwd)/${name}.np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cp "$input" input.prm
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "$nprocs" -eq 1 ]; then
  "$perideal" input.prm > log 2>&1
else
  mpirun --oversubscribe -np "$nprocs" "$perideal" input.prm --threads 1 > log 2>&1
fi
rc=$?
[ $rc -eq 0 ] || { cat log; echo "FAIL: perideal exited with $rc"; exit 1; }

dir=$(sed -n 's/^ *set Directory *= *//p' input.prm); dir=${dir:-output}
pvd="$dir/solution.pvd"
[ -f "$pvd" ] || { cat log; echo "FAIL: no $pvd"; exit 1; }
for record in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' "$pvd"); do
  [ -f "$dir/$record" ] || { echo "FAIL: $record named in $pvd is missing"; exit 1; }
  pieces=$(grep -c "<Piece" "$dir/$record")
  [ "$pieces" -eq "$nprocs" ] || { echo "FAIL: $record has $pieces pieces"; exit 1; }
done
ls "$dir"/*.tmp > /dev/null 2>&1 && { echo "FAIL: temporary files remain"; exit 1; }
csv="$dir/energies.csv"
[ -f "$csv" ] || { echo "FAIL: no $csv"; exit 1; }

drift=$(sed -n 's/^# check: max_energy_drift *//p' input.prm)
if [ -n "$drift" ]; then
  awk -F, -v tol="$drift" 'NR == 2 { b0 = $6 } NR > 1 { d = $6 - b0; if (d < 0) d = -d; if (d > m) m = d; if ($3 + $4 > e) e = $3 + $4 }
    END { m = m / e; printf "largest energy drift %.3e (tolerance %s)\n", m, tol; exit !(m <= tol) }' "$csv" \
    || { cat "$csv"; echo "FAIL: energy balance drifts"; exit 1; }
fi
min_new=$(sed -n 's/^# check: min_new_broken_bonds *//p' input.prm)
if [ -n "$min_new" ]; then
  awk -F, -v n="$min_new" 'NR == 2 { b0 = $7 } END { printf "bonds broken during the run: %d (at least %d)\n", $7 - b0, n; exit !($7 - b0 >= n) }' "$csv" \
    || { cat "$csv"; echo "FAIL: too few bonds broke"; exit 1; }
fi

angle=$(sed -n 's/^# check: crack_angle *//p' input.prm)
if [ -n "$angle" ]; then
  awk -F, -v spec="$angle" 'NR == 1 { for (k = 1; k <= NF; ++k) col[$k] = k; next }
    { x = $col["tip_x"]; y = $col["tip_y"] }
    END { split(spec, a, " "); dx = x - a[1]; dy = y - a[2]
          deg = atan2(dy, dx) * 45 / atan2(1, 1); r = sqrt(dx * dx + dy * dy)
          printf "crack tip at (%g, %g): %.1f deg from (%s, %s), %g away (expected %s to %s deg)\n", x, y, deg, a[1], a[2], r, a[3], a[4]
          exit !(deg >= a[3] && deg <= a[4] && r > 0) }' "$csv" \
    || { echo "FAIL: crack angle"; exit 1; }
fi

# Energies to 1e-8 relative; the broken-bond counts (integers) exactly.
if ! "$numdiff" -q -r 1e-8 -a 1e-14 -s ' \t\n,' "$csv" "$expected" > /dev/null; then
  echo "FAIL: energy history differs from $expected"; diff "$csv" "$expected"; exit 1
fi
if ! diff <(cut -d, -f2,7 "$csv") <(cut -d, -f2,7 "$expected") > /dev/null; then
  echo "FAIL: broken bonds differ from $expected"; exit 1
fi
grep "step .*/" log | tail -1
echo "OK"
