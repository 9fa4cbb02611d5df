#!/usr/bin/env bash
# Two processes against two threads (issue 25, item 3): the cube of
# run_lammps_comparison.sh (lammps_cube.prm.in: h = 1 mm, delta = 3.0001 h,
# 'lammps' partial volumes, dt = 5e-8 s) at N^3 nodes, PMB and LPS, without
# failure (s0 = 1) and with it (s0 = 5e-4), run back to back as 1 process x
# 2 threads and 2 processes x 1 thread. Reports the time-loop seconds of
# both, their ratio (the target: 2x1 within 10 % of 1x2), the broken bonds
# (the same on both, bitwise partition invariance) and the 2x1 run's
# communication line (ghost and broken-bond exchange per step, mean over
# the processes; that time includes waiting for the other process).
#
# Usage: bench/dynamics/run_mpi_vs_threads.sh [BUILD_DIR] [STEPS] [SIZES...]
#   (default: build 200 "40 60")
# Writes results/dynamics/mpi_vs_threads.csv and .png.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/log_fields.sh"
. "$here/cube_input.sh"
build=$(cd "${1:-build}" && pwd)
steps=${2:-200}
shift 2 || true
sizes=${*:-40 60}
perideal="$build/bin/perideal"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
csv="$out/mpi_vs_threads.csv"
tmp="$csv.tmp"
echo "model,N,s0,steps,loop_1x2_s,loop_2x1_s,ratio_1x2_over_2x1,broken_1x2,broken_2x1,ghost_exchange_ms,bond_exchange_ms,step_ms_2x1" > "$tmp"

broken() { sed -n 's/.*broken bonds \([0-9]*\),.*/\1/p' "$1" | tail -1; }
for N in $sizes; do
  for model in pmb lps; do
    for s0 in 1 5e-4; do
      cube_input $model "$N" $s0 "$steps" "$steps" > "$work/cube.prm"
      (cd "$work" && "$perideal" --threads 2 cube.prm) > "$work/threads.log" 2>&1 ||
        { tail "$work/threads.log"; exit 1; }
      (cd "$work" && mpirun -np 2 --bind-to none "$perideal" --threads 1 cube.prm) \
        > "$work/processes.log" 2>&1 || { tail "$work/processes.log"; exit 1; }
      cp "$work/processes.log" "$out/mpi_vs_threads_${model}_${N}_${s0}_2x1.log"
      cp "$work/threads.log" "$out/mpi_vs_threads_${model}_${N}_${s0}_1x2.log"
      mpi=$(grep "MPI, per step" "$work/processes.log")
      step_ms=$(echo "$mpi" | sed -n 's/.*per step of \([0-9.e+-]*\) ms.*/\1/p')
      ghost_ms=$(echo "$mpi" | sed -n 's/.*ghost exchange \([0-9.e+-]*\) ms.*/\1/p')
      bond_ms=$(echo "$mpi" | sed -n 's/.*broken-bond exchange \([0-9.e+-]*\) ms.*/\1/p')
      awk -v m=$model -v N=$N -v s0=$s0 -v s=$steps \
          -v a=$(log_field "$work/threads.log" loop) \
          -v b=$(log_field "$work/processes.log" loop) \
          -v ba=$(broken "$work/threads.log") -v bb=$(broken "$work/processes.log") \
          -v g=$ghost_ms -v bo=$bond_ms -v st=$step_ms 'BEGIN {
        printf "%s,%d,%s,%d,%.4g,%.4g,%.3f,%d,%d,%.3g,%.3g,%.3g\n",
          m, N, s0, s, a, b, a / b, ba, bb, g, bo, st }' | tee -a "$tmp"
    done
  done
done
mv "$tmp" "$csv"
/usr/bin/python3 - "$csv" "$out/mpi_vs_threads.png" <<'PY'
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
rows = list(csv.DictReader(open(sys.argv[1])))
labels = [f'{r["model"].upper()} {r["N"]}^3\ns0={r["s0"]}' for r in rows]
ratio = [float(r["ratio_1x2_over_2x1"]) for r in rows]
comm = [(float(r["ghost_exchange_ms"]) + float(r["bond_exchange_ms"])) /
        float(r["step_ms_2x1"]) for r in rows]
fig, ax = plt.subplots(figsize=(max(6, 1.1 * len(rows)), 4))
x = range(len(rows))
ax.bar([i - 0.2 for i in x], ratio, 0.4, label="2x1 throughput / 1x2")
ax.bar([i + 0.2 for i in x], comm, 0.4,
       label="2x1: share of the step in exchanges (incl. waiting)")
ax.axhline(0.9, color="k", ls="--", lw=1, label="target 0.9")
ax.set_xticks(list(x))
ax.set_xticklabels(labels, fontsize=7)
ax.set_ylim(0, 1.2)
ax.legend(fontsize=8)
ax.set_title("Two processes against two threads (time loop)")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
print("wrote", sys.argv[2])
PY
