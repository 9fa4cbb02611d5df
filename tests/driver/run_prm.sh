#!/usr/bin/env bash
# Usage: run_prm.sh PERIDEAL NUMDIFF NPROCS INPUT.prm EXPECTED.output
#
# Runs `perideal INPUT.prm` (with @TEST_SOURCE_DIR@ replaced by the
# directory of INPUT.prm) on NPROCS MPI processes in a fresh directory and
# compares the run's figures (node and bond counts, nonzeros, constrained
# nodes, errors against the analytical solution) with EXPECTED.output by
# numdiff: relative 1e-8 or absolute 1e-12, so that errors at round-off
# level (patch tests) pass only while they stay below 1e-12. The same
# expected output serves 1 and 2 processes: answers must not depend on the
# partition. Also checks that the run exits with 0 and wrote its PVTU
# record with one VTU piece per process.
set -u
perideal="$1"; numdiff="$2"; nprocs="$3"; input="$4"; expected="$5"
name=$(basename "$input" .prm)
work="$(pwd)/${name}.np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
# Inputs name files next to them as @TEST_SOURCE_DIR@/...
sed "s|@TEST_SOURCE_DIR@|$(cd "$(dirname "$input")" && pwd)|g" "$input" > input.prm

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "$nprocs" -eq 1 ]; then
  "$perideal" input.prm > log 2>&1
else
  mpirun --oversubscribe -np "$nprocs" "$perideal" input.prm > log 2>&1
fi
rc=$?
if [ $rc -ne 0 ]; then
  cat log; echo "FAIL: perideal exited with $rc"; exit 1
fi

# The figures that must not depend on the number of processes.
sed -n -e 's/^\[ *[0-9.]* s\] //' \
       -e 's/ ([0-9]* ghost copies)//' \
       -e 's/, weights by .*//' \
       -e 's/; [0-9]* bond visits per application, [0-9.]* MB, [0-9]* thread(s) per process//' \
       -e '/^nodes:/p' -e '/^quadrature /p' -e '/^assembled:/p' -e '/^matrix-free operator:/p' \
       -e 's/^ *error against/error against/p' log > figures
grep -q "equilibrium check" log || { cat log; echo "FAIL: no equilibrium check"; exit 1; }
equilibrium=$(sed -n 's/.*|F_int + F_ext| \/ |F_int| = //p' log)
awk -v r="$equilibrium" 'BEGIN { exit !(r < 1e-8) }' \
  || { cat log; echo "FAIL: equilibrium residual $equilibrium >= 1e-8"; exit 1; }

if grep -q "wrote " log; then
  pvtu=$(sed -n 's/.*wrote //p' log)
  [ -f "$pvtu" ] || { echo "FAIL: $pvtu missing"; exit 1; }
  pieces=$(ls "$(dirname "$pvtu")"/*.vtu | wc -l)
  [ "$pieces" -eq "$nprocs" ] || { echo "FAIL: $pieces VTU pieces for $nprocs processes"; exit 1; }
fi

if ! "$numdiff" -q -r 1e-8 -a 1e-12 -s ' \t\n:,=()' figures "$expected" > /dev/null; then
  echo "FAIL: figures differ from $expected"; diff figures "$expected"; cat log; exit 1
fi
cat figures
echo "OK"
