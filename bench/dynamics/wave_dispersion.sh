#!/usr/bin/env bash
# Elastic wave in a plate: pulse speed and shape of PeriDEAL's explicit
# dynamics against the classical solution (d'Alembert) and the PD dispersion
# relation, and energy conservation without damage (doc/explicit-dynamics.md,
# "Elastic wave: dispersion").
#
# Usage: bash bench/dynamics/wave_dispersion.sh BUILD_DIR [OUT_DIR]
#   OUT_DIR defaults to results/dynamics/wave_dispersion. About 2 minutes on
#   one core: every run is 1 MPI process x 1 thread.
#
# Each case is "name m w/delta dt_divisor [energy]": the horizon is fixed
# (delta = 3/1024 m), h = delta/m, the pulse width w = (w/delta) delta, and
# dt = (0.9 x the stability bound, rounded down to a whole number of steps)
# / dt_divisor. wave_dispersion.py sizes the plate, writes the input from
# wave_dispersion.prm.in, and afterwards computes the references and writes
# OUT_DIR/wave_dispersion.csv and wave_dispersion.png.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: wave_dispersion.sh BUILD_DIR [OUT_DIR]}" && pwd)
out=$(mkdir -p "${2:-results/dynamics/wave_dispersion}" && cd "${2:-results/dynamics/wave_dispersion}" && pwd)
perideal="$build/bin/perideal"
python=/usr/bin/python3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

cases="
dt1     3 2 1
dt2     3 2 2
dt4     3 2 4
dt8     3 2 8
w1_dt4  3 1 4
w4_dt4  3 4 4
w8_dt4  3 8 4
m4_dt4  4 2 4
m6_dt4  6 2 4
energy     3 2 1 energy
energy_dt2 3 2 2 energy
"
names=""
while read -r name m wd div kind; do
  [ -n "$name" ] || continue
  names="$names $name"
  work="$out/$name"; rm -rf "$work"; mkdir -p "$work"; cd "$work"
  "$python" "$here/wave_dispersion.py" prm "$here/wave_dispersion.prm.in" . "$m" "$wd" "$div" ${kind:-}
  start=$(date +%s.%N)
  "$perideal" input.prm --threads 1 > log 2>&1 || { cat log; echo "FAIL: $name"; exit 1; }
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f\n", b - a }' > wall_seconds
  echo "$name: $(sed -n 's/.*time step \([^ ]*\) s (\([0-9]*\) steps.*/dt = \1 s, \2 steps/p' log), $(cat wall_seconds) s"
done <<< "$cases"

cd "$out"
"$python" "$here/wave_dispersion.py" report "$out" $names
awk -F, -f "$here/../csv_table.awk" wave_dispersion.csv
echo "Written: $out/wave_dispersion.csv, $out/wave_dispersion.png"
