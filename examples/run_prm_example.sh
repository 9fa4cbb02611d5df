#!/usr/bin/env bash
# Usage: run_prm_example.sh PERIDEAL NPROCS EXAMPLE.prm MAX_L2_ERROR
# Runs a .prm example in a fresh directory and checks that it finishes, writes
# its PVTU record, and that its relative L2 error stays below MAX_L2_ERROR.
set -u
perideal="$1"; nprocs="$2"; input="$3"; limit="$4"
work="$(pwd)/$(basename "$input" .prm).np$nprocs"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun --oversubscribe -np "$nprocs" "$perideal" "$input" > log 2>&1 \
  || { cat log; echo "FAIL: exit code"; exit 1; }
cat log
error=$(sed -n 's/.*relative L2 \([0-9.e+-]*\),.*/\1/p' log)
[ -n "$error" ] || { echo "FAIL: no error reported"; exit 1; }
ls output/*.pvtu > /dev/null 2>&1 || { echo "FAIL: no PVTU written"; exit 1; }
awk -v e="$error" -v l="$limit" 'BEGIN { exit !(e < l) }' \
  || { echo "FAIL: relative L2 error $error >= $limit"; exit 1; }
echo "OK: relative L2 error $error < $limit"
