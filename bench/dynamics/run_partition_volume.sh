#!/usr/bin/env bash
# Strong scaling of the explicit loop, estimated from the communication
# volume (issue 25, item 3): perideal-partition-volume builds the cube of
# run_lammps_comparison.sh (N^3 nodes, delta = 3.0001 h) on P processes as
# the simulator does and reports, per process, the owned and ghost nodes
# and the processes it exchanges with; plot_strong_scaling.py turns that
# into a time per step and a parallel efficiency from a measured
# single-process time per node and stated network parameters.
#
# Usage: bench/dynamics/run_partition_volume.sh [BUILD_DIR] [N] [PROCESSES...]
#   (default: build 100 "1 2 4 8 16 32 64"; the processes are
#   oversubscribed: only the partition is built, nothing is timed)
# Writes results/dynamics/partition_volume.csv.
set -eu
build=$(cd "${1:-build}" && pwd)
N=${2:-100}
shift 2 || true
processes=${*:-1 2 4 8 16 32 64}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"
mkdir -p "$out"
csv="$out/partition_volume.csv"
tmp="$csv.tmp"
echo "processes,n,m,two_horizons,owned_min,owned_max,ghosts_avg,ghosts_max,neighbours_avg,neighbours_max" > "$tmp"
for two in 0 1; do
  for p in $processes; do
    mpirun -np "$p" --oversubscribe --bind-to none \
      "$build/bin/perideal-partition-volume" "$N" 3.0001 "$two" | tail -1 >> "$tmp"
    tail -1 "$tmp"
  done
done
mv "$tmp" "$csv"
echo "wrote $csv"
