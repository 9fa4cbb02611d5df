#!/usr/bin/env bash
# The paper's Example 2 (2D transient nonlocal diffusion with a manufactured
# quartic solution, tests/diffusion/manufactured_2d.prm) run to t = 1:
#  - time schemes at dx = 1/39, m = 4: forward Euler with dt = 1e-5 (the
#    paper's setting), Crank-Nicolson and backward Euler with dt = 1e-3 and
#    1e-2 (CG with AMG on the local Laplacian, tolerance 1e-12);
#  - grid spacing: forward Euler, dt = 1e-5, to t = 0.2 at dx = 1/39, 1/78
#    (and 1/156 in the full variant), m = 4 (delta = 4 dx).
# Records the relative l2 error over the free nodes (history column
# relative_l2_error, the paper's Eq. 66) and the largest nodal error
# (max_error) against time, and the wall time of each run. The exact
# solution passes through zero at t = pi/5 = 0.628 (sin 5t = 0), where the
# relative error is not meaningful (it peaks there); the nodal error is not
# affected.
#
# Usage: bench/diffusion/run_manufactured.sh BUILD_DIR [--quick]
#   --quick: a few hundred steps per run (t = 0.005 explicit, t = 0.1
#   implicit, t = 0.002 for the grid study) and no dx = 1/156.
#   THREADS=N (default 1): threads per run (--threads N).
#   CALIBRATION=lattice: 'Micro-diffusivity calibration = lattice' (kappa
#   matched on the discrete stencil) instead of continuum (the paper's);
#   the results then go to results/diffusion/lattice/.
# Writes results/diffusion/manufactured.csv (one row per run: case, scheme,
# dt, dx, m, nodes, end time, final relative l2 error, the largest over
# the recorded times, final largest nodal error |C_h - C|, the largest over
# the recorded times, wall seconds, seconds in the time loop, steps, mean solver
# iterations of the recorded steps), manufactured_<case>.csv (the history of
# each run) and manufactured_error_time.png, manufactured_error_wall.png,
# manufactured_error_dx.png (plot_manufactured.py).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../dynamics/log_fields.sh"
build=$(cd "${1:?usage: run_manufactured.sh BUILD_DIR [--quick]}" && pwd)
quick=${2:-}
threads=${THREADS:-1}
calibration=${CALIBRATION:-continuum}
case "$calibration" in continuum|lattice) ;; *) echo "CALIBRATION: continuum or lattice"; exit 1 ;; esac
perideal="$build/bin/perideal"
[ -x "$perideal" ] || { echo "no $perideal: build the target perideal first"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/diffusion"
[ "$calibration" = continuum ] || out="$out/$calibration"
mkdir -p "$out"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

# case: name stepping scheme dt cells_per_unit m end history_every
if [ "$quick" = "--quick" ]; then
  cases="fe_dt1e-5 explicit - 1e-5 39 4 0.005 50
cn_dt1e-3 implicit Crank-Nicolson 1e-3 39 4 0.1 1
be_dt1e-3 implicit backward_Euler 1e-3 39 4 0.1 1
cn_dt1e-2 implicit Crank-Nicolson 1e-2 39 4 0.1 1
be_dt1e-2 implicit backward_Euler 1e-2 39 4 0.1 1
dx39 explicit - 1e-5 39 4 0.002 20
dx78 explicit - 1e-5 78 4 0.002 20"
else
  cases="fe_dt1e-5 explicit - 1e-5 39 4 1 1000
cn_dt1e-3 implicit Crank-Nicolson 1e-3 39 4 1 10
be_dt1e-3 implicit backward_Euler 1e-3 39 4 1 10
cn_dt1e-2 implicit Crank-Nicolson 1e-2 39 4 1 1
be_dt1e-2 implicit backward_Euler 1e-2 39 4 1 1
dx39 explicit - 1e-5 39 4 0.2 200
dx78 explicit - 1e-5 78 4 0.2 200
dx156 explicit - 1e-5 156 4 0.2 200"
fi

summary="$out/manufactured.csv"
echo "case,scheme,dt,dx,m,nodes,end_time,final_error,max_error_over_time,final_max_nodal_error,max_nodal_error_over_time,wall_seconds,loop_seconds,steps,mean_iterations" > "$summary"
echo "$cases" | while read -r name stepping scheme dt n m end every; do
  scheme=${scheme//_/ }
  # Explicit runs solve nothing: their input must not set the solver's
  # tolerance (an entry without effect is an error).
  [ "$stepping" = explicit ] && { scheme_name="forward Euler"; scheme="backward Euler"; drop="set Solver tolerance"; } \
    || { scheme_name="$scheme"; drop="@NOTHING@"; }
  lower=$(awk -v n=$n -v m=$m 'BEGIN { printf "%.16g", -0.5 - m / n }')
  upper=$(awk -v n=$n -v m=$m 'BEGIN { printf "%.16g", 0.5 + m / n }')
  delta=$(awk -v n=$n -v m=$m 'BEGIN { printf "%.16g", m / n }')
  cells=$((n + 2 * m))
  sed -e "/$drop/d" \
      -e "s/@LOWER@/$lower/g; s/@UPPER@/$upper/g; s/@N@/$cells/g; s/@M@/$m/" \
      -e "s/@DELTA@/$delta/; s/@STEPPING@/$stepping/; s/@SCHEME@/$scheme/" \
      -e "s/@DT@/$dt/; s/@END@/$end/; s/@TOLERANCE@/1e-12/; s/@HISTORY@/$every/" \
      -e "s/@CALIBRATION@/$calibration/" \
      -e "s|@DIR@|$name|" "$here/manufactured_2d.prm.in" > "$work/$name.prm"
  ( cd "$work" && "$perideal" --threads "$threads" "$name.prm" < /dev/null ) > "$work/$name.log" 2>&1 \
    || { tail -20 "$work/$name.log"; echo "FAILED: $name"; exit 1; }
  cp "$work/$name/history.csv" "$out/manufactured_$name.csv"
  cp "$work/$name.log" "$out/manufactured_$name.log"
  nodes=$(sed -n 's/.*diffusion: \([0-9]*\) nodes.*/\1/p' "$work/$name.log")
  steps=$(log_field "$work/$name.log" steps)
  wall=$(log_field "$work/$name.log" wall)
  loop=$(log_field "$work/$name.log" loop)
  # Final and largest relative error and largest nodal error over the
  # rows, mean solver iterations of the recorded steps.
  read -r final largest final_abs largest_abs iterations <<< "$(awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) c[$k] = k; next }
    { e = $c["relative_l2_error"]; if (e > m) m = e; a = $c["max_error"]; if (a > l) l = a
      if ($c["step"] > 0) { it += $c["iterations"]; ++r } }
    END { printf "%.6e %.6e %.6e %.6e %.2f", e, m, a, l, (r > 0 ? it / r : 0) }' \
    "$work/$name/history.csv")"
  dx=$(awk -v n=$n 'BEGIN { printf "%.10g", 1 / n }')
  echo "$name,$scheme_name,$dt,$dx,$m,$nodes,$end,$final,$largest,$final_abs,$largest_abs,$wall,$loop,$steps,$iterations" >> "$summary"
  echo "$name: $scheme_name dt $dt dx 1/$n, $nodes nodes, $steps steps, final error $final, max $largest, $wall s"
done
if /usr/bin/python3 -c 'import matplotlib' 2> /dev/null; then
  /usr/bin/python3 "$here/plot_manufactured.py" "$out"
else
  echo "matplotlib not importable by /usr/bin/python3: no plots"
fi
