#!/usr/bin/env bash
# Set-up against size (issue 25, item 4): the cube of
# run_lammps_comparison.sh (lammps_cube.prm.in: h = 1 mm, delta = 3.0001 h,
# 'lammps' partial volumes, s0 = 5e-4, 15 steps of 5e-8 s) at N^3 nodes,
# bond-based PMB and LPS, on one process with the given threads. Each set-up
# phase comes from the run's TimerOutput table (mesh; nodes and ghost
# exchange; neighbour search and weights; operator setup; time step bound),
# the whole set-up is the wall time less the time loop, and the target is
# set-up <= the time of 15 steps at 10^6 nodes (and <= 3 minutes at
# 7 10^6). Peak memory is the run's own VmHWM line.
#
# Usage: bench/dynamics/run_setup_scaling.sh [BUILD_DIR] [THREADS] [SIZES...]
#   (default: build 2 "40 60 80 100 128 192"; 192^3 = 7.1 10^6 nodes needs
#   about 16 GB with PMB, LPS only up to 128^3 by default)
# Writes results/dynamics/setup_scaling.csv and .png.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/log_fields.sh"
. "$here/cube_input.sh"
build=$(cd "${1:-build}" && pwd)
threads=${2:-2}
shift 2 || true
sizes=${*:-40 60 80 100 128 192}
perideal="$build/bin/perideal"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
csv="$out/setup_scaling.csv"
echo "model,N,nodes,bonds,threads,mesh_s,nodes_s,neighbours_s,operator_s,time_step_bound_s,setup_s,steps,seconds_per_step,setup_over_15_steps,peak_memory_mb" > "$csv"

steps=15
# The seconds of one TimerOutput section ("| name | calls | 1.23s |").
section() {
  sed -n "s/^| $2 *| *[0-9]* | *\([0-9.e+-]*\)s.*/\1/p" "$1" | head -1
}
run() {
  local model=$1 N=$2
  cube_input $model "$N" 5e-4 $steps 5 > "$work/cube.prm"
  (cd "$work" && "$perideal" --threads "$threads" cube.prm) > "$work/log" 2>&1 ||
    { tail "$work/log"; exit 1; }
  cp "$work/log" "$out/setup_scaling_${model}_$N.log"
  local mesh nodes_s neigh op bound loop wall mem nodes bonds
  mesh=$(section "$work/log" "mesh")
  nodes_s=$(section "$work/log" "nodes and ghost exchange")
  neigh=$(section "$work/log" "neighbour search and weights")
  op=$(section "$work/log" "operator setup")
  bound=$(section "$work/log" "time step bound")
  loop=$(log_field "$work/log" loop)
  wall=$(log_field "$work/log" wall)
  mem=$(log_field "$work/log" memory)
  nodes=$(log_field "$work/log" nodes)
  bonds=$(log_field "$work/log" bonds)
  awk -v m=$model -v N=$N -v n=$nodes -v b=$bonds -v t=$threads -v me=$mesh \
      -v no=$nodes_s -v ne=$neigh -v op=$op -v bo=${bound:-0} -v l=$loop \
      -v w=$wall -v s=$steps -v mem=$mem 'BEGIN {
    setup = w - l
    printf "%s,%d,%d,%d,%d,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%d,%.4g,%.3g,%.6g\n",
      m, N, n, b, t, me, no, ne, op, bo, setup, s, l / s, setup / l, mem }' |
    tee -a "$csv"
}
for N in $sizes; do run pmb "$N"; done
for N in $sizes; do [ "$N" -le 128 ] && run lps "$N"; done
/usr/bin/python3 "$here/plot_setup_scaling.py" "$csv" "$out/setup_scaling.png"
