#!/usr/bin/env bash
# Peridigm's fragmenting cylinder (examples/fragmenting_cylinder) for
# throughput: a steel tube (R 20/25 mm, H 100 mm) of cubic cells, LPS with
# critical stretch 0.02, horizon 4.17462 mm, thrown apart by the initial
# velocity field of that example; it shatters within microseconds, so most
# of the run is spent on damaged nodes. Reports time per step, bond visits
# per second per core, broken bonds, peak memory and memory per node.
#
# Usage: bench/dynamics/run_fragmenting_cylinder.sh [BUILD_DIR] [--quick]
#   --quick: 2.5 mm cells, horizon 7.5 mm, 50 us, on 1 and 2 processes: a
#   cheap check (ctest) that the run completes with the same broken bonds
#   on both, that bonds break, and that no energy is created (kinetic +
#   elastic never exceeds its initial value by more than 1e-9 relative:
#   broken bonds only dissipate, and there is no external work).
# Writes results/dynamics/fragmenting_cylinder.csv (and energies_<case>.csv).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/log_fields.sh"
build=$(cd "${1:-build}" && pwd)
quick=${2:-}
perideal="$build/bin/perideal"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "$quick" = "--quick" ]; then
  out="$(pwd)/fragmenting_cylinder_quick"
  # case: cell size, horizon, end time, output interval, ranks, threads
  cases="0.0025 0.0075 5e-5 2.5e-5 1 1
0.0025 0.0075 5e-5 2.5e-5 2 1"
else
  out="$(pwd)/results/dynamics"
  cases="0.001 0.00417462 2.5e-4 2.5e-5 1 2
0.001 0.00417462 2.5e-4 2.5e-5 2 1"
fi
rm -rf "$out/cylinder_work" && mkdir -p "$out/cylinder_work"
work="$out/cylinder_work"
csv="$out/fragmenting_cylinder.csv"
echo "h,horizon,nodes,bonds,ranks,threads,steps,time_steps_seconds,seconds_per_step,bond_visits_per_step,bond_visits_per_second_per_core,broken_bonds,broken_fraction,wall_seconds,peak_memory_mb,kb_per_node" > "$csv"
echo "$cases" | while read -r h horizon end every ranks threads; do
  name="cyl_h${h}_np${ranks}"
  /usr/bin/python3 "$here/make_cylinder_mesh.py" 0.02 0.025 0.1 "$h" "$work/$name.inp" > /dev/null
  sed -e "s|@MESH@|$name.inp|; s/@H@/$h m/; s/@END@/$end/; s/@OUTPUT@/$every/" \
      -e "s/set Length = 0.00417462/set Length = $horizon/" \
      -e "s|set Directory = output|set Directory = $name|" \
      "$here/fragmenting_cylinder.prm.in" > "$work/$name.prm"
  ( cd "$work" && mpirun --oversubscribe --bind-to none -np "$ranks" "$perideal" --threads "$threads" "$name.prm" < /dev/null ) \
    > "$work/$name.log" 2>&1 || { tail -20 "$work/$name.log"; echo "FAILED: $name"; exit 1; }
  log="$work/$name.log"
  nodes=$(log_field "$log" nodes)
  bonds=$(log_field "$log" bonds)
  visits=$(log_field "$log" visits)
  steps=$(log_field "$log" steps)
  loop=$(log_field "$log" loop)
  wall=$(log_field "$log" wall)
  mem=$(log_field "$log" memory)
  broken=$(tail -1 "$work/$name/energies.csv" | cut -d, -f7)
  cp "$work/$name/energies.csv" "$out/energies_$name.csv"
  awk -v h=$h -v d=$horizon -v n=$nodes -v b=$bonds -v r=$ranks -v t=$threads -v s=$steps \
      -v loop=$loop -v v=$visits -v br=$broken -v w=$wall -v m=$mem 'BEGIN {
    printf "%s,%s,%d,%d,%d,%d,%d,%.4g,%.4g,%d,%.4g,%d,%.4f,%.4g,%.4g,%.3f\n", h, d, n, b, r, t, s, loop,
      loop / s, v, v * s / loop / (r * t), br, br / b, w, m, m * 1024 / n }' >> "$csv"
  echo "$name: $nodes nodes, $steps steps, $loop s in the time loop, $broken of $bonds bonds broken"
  # No energy is created: kinetic + elastic <= its value at t = 0.
  awk -F, 'NR == 2 { e0 = $3 + $4 } NR > 1 { if ($3 + $4 > e0 * (1 + 1e-9)) bad = $1 }
    END { if (bad != "") { print "FAIL: energy grows at t = " bad; exit 1 } }' "$work/$name/energies.csv"
done
awk -F, -f "$here/../csv_table.awk" "$csv"
if [ "$quick" = "--quick" ]; then
  a="$out/energies_cyl_h0.0025_np1.csv"; b="$out/energies_cyl_h0.0025_np2.csv"
  diff <(cut -d, -f2,7 "$a") <(cut -d, -f2,7 "$b") > /dev/null \
    || { echo "FAIL: broken bonds differ between 1 and 2 processes"; exit 1; }
  awk -F, 'NR == 2 { b0 = $7 } END { if ($7 - b0 < 1000) { print "FAIL: fewer than 1000 bonds broke"; exit 1 } }' "$a"
  echo "OK"
fi
