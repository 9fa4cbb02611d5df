#!/usr/bin/env bash
# Side by side with LAMMPS (PERI package) on the same problem: a cube of N^3
# nodes (h = 1 mm), horizon 3.0001 h, LAMMPS's volume reduction ('lammps'
# partial volumes in PeriDEAL), the same material (K = 48 GPa, G = 28.8 GPa),
# initial velocity field, time step and number of steps, for two models:
#   pmb: pair_style peri/pmb against 'bond-based', constant influence;
#   lps: pair_style peri/lps against 'linear peridynamic solid', influence
#        delta/r ('inverse distance'; LAMMPS's 1/r, the same state-based
#        model since it is invariant under a constant factor in omega).
# Two variants each: without failure (s0 = 1: the displacement histories
# must agree to round-off) and with failure (s0 = 5e-4: LAMMPS breaks a bond
# after the force of the step in which it exceeds s0, PeriDEAL in that step,
# so the histories part once bonds break).
#
# LAMMPS is a peer used only here: install it on the benchmark machine
# (apt-get install lammps); the project's setup does not.
#
# Usage: [MODELS="pmb lps"] bench/dynamics/run_lammps_comparison.sh [BUILD_DIR] [SIZES...]
# Writes results/dynamics/lammps_comparison.csv,
# probe_<model>_<N>_<variant>.csv and the plots (plot_lammps_comparison.py).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-build}" && pwd); shift || true
sizes=${*:-20 30 40}
perideal="$build/bin/perideal"
lmp=$(command -v lmp || command -v lmp_serial || true)
[ -n "$lmp" ] || { echo "LAMMPS (lmp) not found: apt-get install lammps"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"; mkdir -p "$out"
csv="$out/lammps_comparison.csv"
echo "code,model,variant,N,nodes,ranks,threads,steps,bonds_per_step,seconds,seconds_per_step,bonds_per_second_per_core,broken_bonds,probe_max_abs_difference,probe_max_displacement" > "$csv"

models=${MODELS:-pmb lps}
h=1e-3; K=48e9; G=28.8e9; rho=2440; steps=200; every=10; dt=5e-8
delta=$(awk -v h=$h 'BEGIN { printf "%.10g", 3.0001 * h }')
# PMB micromodulus 18 K / (pi delta^4) (constant influence, 3D).
c=$(awk -v K=$K -v d=$delta 'BEGIN { printf "%.17g", 18 * K / (3.14159265358979323846 * d^4) }')
V=$(awk -v h=$h 'BEGIN { printf "%.17g", h^3 }')

for N in $sizes; do
  L=$(awk -v N=$N -v h=$h 'BEGIN { printf "%.17g", N * h }')
  xc=$(awk -v L=$L 'BEGIN { printf "%.17g", L / 2 }')
  vx="20*(x-$xc)/$L"; vy="10*(y-$xc)/$L+3*sin(300*x)"; vz="-10*(z-$xc)/$L"
  px=$(awk -v N=$N -v h=$h 'BEGIN { printf "%.17g", (int(0.3 * N) + 0.5) * h }')
  py=$(awk -v N=$N -v h=$h 'BEGIN { printf "%.17g", (int(0.6 * N) + 0.5) * h }')
  pz=$(awk -v N=$N -v h=$h 'BEGIN { printf "%.17g", (int(0.45 * N) + 0.5) * h }')
  for model in $models; do
  case $model in
    pmb) pd_model="bond-based"; influence=constant ;;
    lps) pd_model="linear peridynamic solid"; influence="inverse distance" ;;
    *) echo "unknown model '$model' in MODELS (pmb, lps)"; exit 1 ;;
  esac
  for variant in elastic failure; do
    s0=1; [ $variant = failure ] && s0=5e-4
    work="$out/run_${model}_${N}_${variant}"; rm -rf "$work"; mkdir -p "$work"; cd "$work"

    # LAMMPS, 1 process.
    "$lmp" -in "$here/lammps_$model.in" -log lammps.log -screen none \
      -var N $N -var h $h -var skin $(awk -v h=$h 'BEGIN{print 0.5*h}') -var c $c -var K $K -var G $G -var delta $delta \
      -var s0 $s0 -var rho $rho -var V $V -var vxf "$vx" -var vyf "$vy" -var vzf "$vz" \
      -var px $px -var py $py -var pz $pz -var probe_radius $(awk -v h=$h 'BEGIN{print 0.1*h}') \
      -var dt $dt -var every $every -var steps $steps
    lmp_seconds=$(sed -n 's/^Loop time of \([0-9.e+-]*\) on.*/\1/p' lammps.log | tail -1)
    lmp_broken=$(awk '/^ *Step/ { on = 1; next } on && /^Loop/ { on = 0 } on { last = $4 } END { print last }' lammps.log)

    # PeriDEAL: 1 process with 1 and 2 threads, 2 processes with 1 thread.
    sed -e "s/@N@/$N/g; s/@L@/$L/g; s/@delta@/$delta/g; s/@K@/$K/g; s/@G@/$G/g; s/@rho@/$rho/g; s/@s0@/$s0/g" \
        -e "s/@model@/$pd_model/g; s/@influence@/$influence/g" \
        -e "s/@end_time@/$(awk -v n=$steps -v dt=$dt 'BEGIN { printf "%.17g", n * dt }')/; s/@dt@/$dt/; s/@every@/$every/" \
        -e "s/@px@/$px/; s/@py@/$py/; s/@pz@/$pz/; s|@vx@|$vx|; s|@vy@|$vy|; s|@vz@|$vz|" \
        "$here/lammps_cube.prm.in" > cube.prm
    for config in "1 1" "1 2" "2 1"; do
      set -- $config
      log="perideal_np$1_t$2.log"
      if [ "$1" -eq 1 ]; then "$perideal" cube.prm --threads $2 > "$log" 2>&1
      else mpirun --oversubscribe -np $1 "$perideal" cube.prm --threads $2 > "$log" 2>&1; fi
      cp out/energies.csv "energies_np$1_t$2.csv"
    done

    # The probe's displacement from both codes, and their difference.
    /usr/bin/python3 - "$model" "$N" "$variant" "$px" "$py" "$pz" "$every" "$dt" "$out" <<'PY'
import sys, csv
model, N, variant, px, py, pz, every, dt, out = sys.argv[1:]
p0 = [float(px), float(py), float(pz)]
lmp = {}
lines = open("probe.dump").read().split("ITEM: TIMESTEP")[1:]
for block in lines:
    rows = block.strip().splitlines()
    step = int(rows[0]); data = rows[-1].split()
    lmp[step] = [float(data[1 + c]) - p0[c] for c in range(3)]
pd = {}
for row in csv.DictReader(open("energies_np1_t1.csv")):
    pd[int(float(row["step"]))] = [float(row["probe0_u" + c]) for c in "xyz"]
diff = 0; umax = 0
with open(f"{out}/probe_{model}_{N}_{variant}.csv", "w") as f:
    f.write("step,time,lammps_ux,lammps_uy,lammps_uz,perideal_ux,perideal_uy,perideal_uz\n")
    for step in sorted(set(lmp) & set(pd)):
        a, b = lmp[step], pd[step]
        diff = max(diff, max(abs(a[c] - b[c]) for c in range(3)))
        umax = max(umax, max(abs(x) for x in b))
        f.write(",".join(map(str, [step, step * float(dt)] + a + b)) + "\n")
open("probe_summary", "w").write(f"{diff:.6e} {umax:.6e}\n")
PY
    read probe_diff probe_max < probe_summary
    # Bonds as seen from each end (LAMMPS's partner lists count the same);
    # LPS passes over them twice (dilatation, force), but a bond counts once.
    bonds=$(sed -n 's/.*, bonds: \([0-9]*\) (.*/\1/p' perideal_np1_t1.log)
    nodes=$((N * N * N))
    echo "lammps,$model,$variant,$N,$nodes,1,1,$steps,$bonds,$lmp_seconds,$(awk -v t=$lmp_seconds -v s=$steps 'BEGIN{print t/s}'),$(awk -v b=$bonds -v s=$steps -v t=$lmp_seconds 'BEGIN{print b*s/t}'),$lmp_broken,$probe_diff,$probe_max" >> "$csv"
    for config in "1 1" "1 2" "2 1"; do
      set -- $config
      log="perideal_np$1_t$2.log"
      seconds=$(sed -n 's/^| time steps *| *[0-9]* | *\([0-9.e+-]*\)s.*/\1/p' "$log" | head -1)
      broken=$(tail -1 "energies_np$1_t$2.csv" | cut -d, -f7)
      cores=$(( $1 * $2 ))
      echo "perideal,$model,$variant,$N,$nodes,$1,$2,$steps,$bonds,$seconds,$(awk -v t=$seconds -v s=$steps 'BEGIN{print t/s}'),$(awk -v b=$bonds -v s=$steps -v t=$seconds -v c=$cores 'BEGIN{print b*s/t/c}'),$broken,$probe_diff,$probe_max" >> "$csv"
    done
    cd "$out"
  done
  done
done
/usr/bin/python3 "$here/plot_lammps_comparison.py" "$out" || echo "(no plot: /usr/bin/python3 lacks matplotlib, Debian package python3-matplotlib)"
awk -F, -f "$here/../csv_table.awk" "$csv"
