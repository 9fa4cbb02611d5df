#!/usr/bin/env bash
# Usage: run_diffusion_example.sh PERIDEAL NPROCS EXAMPLE.prm COLUMN MIN SED_EDITS
# Runs a diffusion example, made cheap by SED_EDITS (a shorter time), in a
# fresh directory and checks that it finishes, writes its PVD time series
# with every record present, and that the last value of the history column
# COLUMN is at least MIN (for step-5: the pit grows).
set -u
perideal="$1"; nprocs="$2"; input="$3"; column="$4"; min="$5"; edits="$6"
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
awk -F, -v name="$column" -v min="$min" 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == name) c = k; next } { v = $c }
  END { if (!c) { print "no column " name; exit 1 } printf "%s at the end: %g (at least %g)\n", name, v, min; exit !(v >= min) }' \
  output/history.csv || { echo "FAIL: $column too small"; exit 1; }
echo "OK"
