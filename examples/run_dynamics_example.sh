#!/usr/bin/env bash
# Usage: run_dynamics_example.sh PERIDEAL NPROCS EXAMPLE.prm MIN_NEW_BROKEN SED_EDITS
# Runs an explicit-dynamics example, made cheap by SED_EDITS (a coarser
# mesh, a shorter time), in a fresh directory and checks that it finishes,
# writes its PVD time series with every record present, and that at least
# MIN_NEW_BROKEN bonds break beyond the pre-crack (the crack grows); with
# the hybrid quadrature scheme, that the standard region grows and no
# switch comes late.
set -u
perideal="$1"; nprocs="$2"; input="$3"; min_new="$4"; edits="$5"
work="$(pwd)/$(basename "$input" .prm).np$nprocs"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
sed -e "$edits" "$input" > input.prm
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun --oversubscribe -np "$nprocs" "$perideal" input.prm --threads 1 > log 2>&1 \
  || { cat log; echo "FAIL: exit code"; exit 1; }
grep "step .*/" log | tail -1
[ -f output/solution.pvd ] || { echo "FAIL: no output/solution.pvd"; exit 1; }
for record in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' output/solution.pvd); do
  [ -f "output/$record" ] || { echo "FAIL: $record missing"; exit 1; }
done
awk -F, -v n="$min_new" 'NR == 2 { b0 = $7 } END { d = $7 - b0; printf "bonds broken during the run: %d (at least %d)\n", d, n; exit !(d >= n) }' \
  output/energies.csv || { echo "FAIL: the crack did not grow"; exit 1; }
# With the hybrid quadrature scheme: the standard region grows with the
# crack (column standard_nodes), and no switch came late.
if head -1 output/energies.csv | grep -q standard_nodes; then
  c=$(head -1 output/energies.csv | tr ',' '\n' | grep -nx standard_nodes | cut -d: -f1)
  awk -F, -v c="$c" 'NR == 2 { s0 = $c } END { printf "standard nodes: %d at the start, %d at the end\n", s0, $c; exit !($c > s0) }' \
    output/energies.csv || { echo "FAIL: the standard region did not grow"; exit 1; }
  grep -q "hybrid: .* 0 late switches" log ||
    { grep "hybrid:" log; echo "FAIL: late switches"; exit 1; }
fi
echo "OK"
