#!/usr/bin/env bash
# Centre-cracked plate in tension, quasi-static to failure (issue 24): the
# load at which bonds first break beyond the pre-crack (the first
# equilibrium of that step, before any bond breaks) against LEFM,
# sigma_c = sqrt(E' G0) / (F sqrt(pi a)) with Feddersen's F = sqrt(sec(pi a /
# 2b)), as the grid (and with it delta = 3h) is refined at fixed m = 3; and
# the same problem with adaptive dynamic relaxation against Newton (CG with
# the local-elasticity preconditioner), with the wall time of each run.
#
#   bash bench/run_centre_crack.sh [--quick] [--output-dir DIR]
#
# The inputs are those of tests/fracture (0.1 x 0.1 m plate, a = 0.01,
# G0 = 3.8 J/m^2, E = 72 GPa): PMB in plane stress, LPS in plane stress at
# nu = 0.2 and in plane strain at nu = 0.3. Writes DIR/centre_crack.csv
# (model, solver, cells per side, m, delta/a, nodes, the initiation reaction,
# LEFM's, the gap in %, the peak reaction, wall time, steps, Krylov or
# relaxation iterations), DIR/logs/ and with matplotlib DIR/error_vs_time.png
# and DIR/time_vs_size.png. DIR defaults to results/centre_crack. SIZES
# overrides the cells per side (default 50 100 200; --quick: 30 50), DR_SIZES
# those of the dynamic-relaxation runs (PMB only; default 50 100 200;
# --quick: 30), M_STUDY the m study at delta = 3 mm (pairs m:cells, default
# '4:130 6:200', beside the m = 3 runs at 100^2: multiples of 10, so that
# the pre-crack runs between node rows and its tips lie midway between
# node columns, as at m = 3; --quick: none) for
# M_MODELS (default pmb_plane_stress lps_plane_stress); MODELS the models
# of the refinement at m = 3 (default all three; may be empty); A_STUDY the
# a/W study at m = 4 with the peak load as the measure (pairs cells:a in
# mm on a plate twice as tall, 0.1 x 0.2 m, so that the grips' distance
# leaves Feddersen's infinite strip; default none, e.g. '130:10 130:20
# 130:30': a multiple of h = 0.1 m / cells, so the tips lie midway between
# node columns) for the M_MODELS; FINITE_STUDY pairs m:cells run with
# 'Kinematics = finite deformation' (solver column newton_finite) beside
# the same runs in small strain (default none, e.g. '3:100 4:130'), PMB
# plane stress; TOL_STUDY cells per side at which both solvers run at
# each of TOLERANCES (default '1e-8 1e-6 1e-4'; 'Linear solver/Relative
# tolerance' and 'quasi-static/dynamic relaxation/Relative tolerance'),
# PMB plane stress, each curve against Newton's at the first tolerance
# (peak, critical load, same bonds) in DIR/centre_crack_tolerance.csv:
# which tolerance each solver needs for the curve within 1 %, and at what
# cost (a run that stops, e.g. dynamic relaxation too loose for the step
# control, is a row marked 'stopped'). AMG_SWEEPS sets 'Linear
# solver/AMG smoother sweeps' of the Newton
# runs (default: the input's). Fails unless every
# model is within 5 % of LEFM at the finest grid at m = 3 and dynamic
# relaxation breaks the same bonds at every step as Newton.
set -euo pipefail
cd "$(dirname "$0")/.."

source bench/driver_study.sh
driver_study_setup results/centre_crack "$@"

if [ $quick -eq 1 ]; then
  sizes="${SIZES:-30 50}"; dr_sizes="${DR_SIZES-30}"; m_study="${M_STUDY-}"
else
  sizes="${SIZES:-50 100 200}"; dr_sizes="${DR_SIZES-50 100 200}"
  m_study="${M_STUDY-4:130 6:200}"
fi
m_models="${M_MODELS:-pmb_plane_stress lps_plane_stress}"

csv="$out/centre_crack.csv"
a_study="${A_STUDY-}"
models="${MODELS-pmb_plane_stress lps_plane_stress lps_plane_strain}"
echo "model,solver,cells,m,delta_over_a,nodes,reaction_initiation,reaction_lefm,gap_percent,reaction_peak,wall_seconds,steps,iterations,a_over_b,height_over_width,peak_gap_percent" > "$csv"

# run MODEL SOLVER N [M [A]]: one run (N cells per side, m-ratio M, default
# 3; with A, the half crack length in mm, on the 0.1 x 0.2 m plate), one
# CSV row.
run() {
  local model="$1" solver="$2" n="$3" m="${4:-3}" a_mm="${5:-}"
  local base="tests/fracture/centre_crack_${model}.prm"
  local name="${model}_${solver}_${n}"
  [ "$m" = 3 ] || name="${name}_m$m"
  [ -z "$a_mm" ] || name="${name}_a${a_mm}mm"
  [ -z "$tol" ] || name="${name}_tol$tol"
  local prm="$out/logs/$name.prm" log="$out/logs/$name.log"
  sed -e "s/set Subdivisions = 50, 50/set Subdivisions = $n, $n/" \
      -e "s/set m-ratio = 3/set m-ratio = $m/" \
      -e "s|set Directory = output|set Directory = $out/logs/$name|" "$base" > "$prm"
  if [ -n "$a_mm" ]; then
    local a; a=$(awk -v a="$a_mm" 'BEGIN { printf "%.10g", a / 1000 }')
    sed -i -e "s/set Subdivisions = $n, $n/set Subdivisions = $n, $((2 * n))/" \
      -e "s/set Lower corner = -0.05, -0.05/set Lower corner = -0.05, -0.1/" \
      -e "s/set Upper corner = 0.05, 0.05/set Upper corner = 0.05, 0.1/" \
      -e "s/2e-5\*t\*sign(y)/4e-5*t*sign(y)/" \
      -e "s/set Pre-cracks = -0.01, 0, 0.01, 0/set Pre-cracks = -$a, 0, $a, 0/" \
      -e "s/^# check: lefm_initiation 0.01 /# check: lefm_initiation $a /" "$prm"
  fi
  if [ "$solver" = newton_finite ]; then
    sed -i 's/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  set Kinematics = finite deformation/' "$prm"
  fi
  if [ "$solver" = dynamic_relaxation ]; then
    sed -i -e '/subsection Linear solver/,/^end/d' \
      -e 's/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  set Nonlinear solver = dynamic relaxation/' "$prm"
    [ -z "$tol" ] || sed -i "s/  set Nonlinear solver = dynamic relaxation/&\n  subsection dynamic relaxation\n    set Relative tolerance = $tol\n  end/" "$prm"
  else
    [ -z "$tol" ] || sed -i "s/  set Preconditioner = local elasticity/&\n  set Relative tolerance = $tol/" "$prm"
    [ -z "${AMG_SWEEPS:-}" ] || sed -i "s/  set Preconditioner = local elasticity/&\n  set AMG smoother sweeps = $AMG_SWEEPS/" "$prm"
  fi
  printf '%-24s %-18s %4s^2, m = %s: ' "$model" "$solver" "$n" "$m"
  if ! "$perideal" "$prm" > "$log" 2>&1; then
    # In the tolerance study a loose tolerance may stop the run (the step
    # control cannot resolve the critical stretch): that is a result.
    [ -n "$tol" ] || { tail -20 "$log"; exit 1; }
    echo "stopped: $(grep -A1 '^perideal: error' "$log" | tail -1 | cut -c1-100)..."
    return 0
  fi
  local wall lefm
  wall=$(sed -n 's/^total wall time \([0-9.e+-]*\) s.*/\1/p' "$log")
  lefm=$(sed -n 's/^# check: lefm_initiation *//p' "$prm")
  local label="$solver"
  [ -z "$tol" ] || label="${solver}_tol$tol"
  awk -F, -v spec="$lefm" -v model="$model" -v solver="$label" -v n="$n" -v m="$m" -v wall="$wall" -v tall="${a_mm:+1}" '
    NR == 2 { b0 = $5; k = $4 / $2 }
    NR > 1 { it += $6; steps++; r = $4 < 0 ? -$4 : $4; if (r > peak) peak = r
             if (!found && $5 > b0) { found = 1; init = k * $2 } }
    END { split(spec, p, " "); a = p[1]; b = p[2]; E = p[3]; G = p[4]
          pi = atan2(0, -1); F = sqrt(1 / cos(pi * a / (2 * b)))
          lefm = sqrt(E * G) / (F * sqrt(pi * a)) * 2 * b
          h = 2 * b / n; gap = 100 * (init / lefm - 1)
          hw = (tall ? 2 : 1)
          printf "%s,%s,%d,%d,%.4g,%d,%.6g,%.6g,%.3f,%.6g,%s,%d,%d,%.4g,%d,%.3f\n", model, solver, n, m, m * h / a, n * n * hw, init, lefm, gap, peak, wall, steps, it, a / b, hw, 100 * (peak / lefm - 1) }' \
    "$out/logs/$name/load_displacement.csv" | tee -a "$csv" | awk -F, '{ printf "initiation %s (LEFM %s, %+.2f %%), peak %+.2f %%, %s s\n", $7, $8, $9, $16, $11 }'
}

tol=""
for model in $models; do
  for n in $sizes; do run "$model" newton "$n"; done
done
for n in $dr_sizes; do run pmb_plane_stress dynamic_relaxation "$n"; done
# The m study: delta / a = 0.3 held (delta = 3 mm) while m grows, so that
# the gap left at fixed m is told apart from the gap of a coarse delta.
for model in $m_models; do
  for mn in $m_study; do run "$model" newton "${mn#*:}" "${mn%%:*}"; done
done
# The a/W study at m = 4 on the taller plate (peak load against LEFM).
for model in $m_models; do
  for na in $a_study; do run "$model" newton "${na%%:*}" 4 "${na#*:}"; done
done

# Finite deformation beside small strain.
for mn in ${FINITE_STUDY-}; do
  for solver in newton newton_finite; do
    run pmb_plane_stress "$solver" "${mn#*:}" "${mn%%:*}"
  done
done

# The tolerance study: both solvers at each tolerance, each curve against
# the one of Newton at the first (tightest) tolerance: the peak and the
# critical load of unstable growth, and whether the steps and broken bonds
# are the same.
tol_csv="$out/centre_crack_tolerance.csv"
echo "cells,solver,tolerance,wall_seconds,iterations,peak_difference_percent,critical_difference_percent,same_bonds" > "$tol_csv"
for n in ${TOL_STUDY-}; do
  for tol in ${TOLERANCES:-1e-8 1e-6 1e-4}; do
    for solver in newton dynamic_relaxation; do
      run pmb_plane_stress "$solver" "$n"
    done
  done
  tols=(${TOLERANCES:-1e-8 1e-6 1e-4})
  ref="$out/logs/pmb_plane_stress_newton_${n}_tol${tols[0]}"
  for tol in "${tols[@]}"; do
    for solver in newton dynamic_relaxation; do
      dir="$out/logs/pmb_plane_stress_${solver}_${n}_tol$tol"
      if grep -q '^perideal: error' "$dir.log"; then
        echo "$n,$solver,$tol,,,,,stopped" >> "$tol_csv"; continue
      fi
      same=no
      diff <(cut -d, -f1,2,5 "$ref/load_displacement.csv") <(cut -d, -f1,2,5 "$dir/load_displacement.csv") > /dev/null && same=yes
      critical() { sed -n 's/.*critical load: .*(its magnitude \([0-9.e+-]*\)).*/\1/p' "$1.log" | head -1; }
      awk -F, -v n="$n" -v solver="$solver" -v tol="$tol" -v same="$same" \
          -v wall="$(sed -n 's/^total wall time \([0-9.e+-]*\) s.*/\1/p' "$dir.log")" \
          -v c0="$(critical "$ref")" -v c="$(critical "$dir")" '
        NR == FNR { if (FNR > 1) { r = $4 < 0 ? -$4 : $4; if (r > p0) p0 = r }; next }
        FNR > 1 { r = $4 < 0 ? -$4 : $4; if (r > p) p = r; it += $6 }
        END { printf "%d,%s,%s,%s,%d,%.4f,%s,%s\n", n, solver, tol, wall, it, 100 * (p / p0 - 1),
                (c0 != "" && c != "") ? sprintf("%.4f", 100 * (c / c0 - 1)) : "", same }' \
        "$ref/load_displacement.csv" "$dir/load_displacement.csv" >> "$tol_csv"
    done
  done
done
[ -z "${TOL_STUDY-}" ] || cat "$tol_csv"

# The checks: within 5 % of LEFM at the finest grid; dynamic relaxation on
# the same steps and broken bonds as Newton.
finest=$(echo $sizes | tr ' ' '\n' | sort -n | tail -1)
status=0
awk -F, -v n="$finest" 'NR > 1 && $2 == "newton" && $3 == n && $4 == 3 {
    d = $9 < 0 ? -$9 : $9; printf "%s at %s^2: %+.2f %% of LEFM\n", $1, n, $9; if (d > 5) bad = 1 }
    END { exit bad }' "$csv" || { echo "FAIL: a model is more than 5 % from LEFM at the finest grid"; status=1; }
for n in $dr_sizes; do
  a="$out/logs/pmb_plane_stress_newton_$n/load_displacement.csv"
  b="$out/logs/pmb_plane_stress_dynamic_relaxation_$n/load_displacement.csv"
  [ -f "$a" ] || continue
  if diff <(cut -d, -f1,2,5 "$a") <(cut -d, -f1,2,5 "$b") > /dev/null; then
    awk -F, -v n="$n" 'NR > 1 && $1 == "pmb_plane_stress" && $3 == n && $4 == 3 { t[$2] = $11 }
      END { printf "%s^2: dynamic relaxation breaks the same bonds at every step; Newton %.3g s, dynamic relaxation %.3g s (%.1fx)\n", n, t["newton"], t["dynamic_relaxation"], t["dynamic_relaxation"] / t["newton"] }' "$csv"
  else
    echo "FAIL: at $n^2 dynamic relaxation and Newton break different bonds"; status=1
  fi
done
plot_if_possible bench/plot_centre_crack.py "$csv" "$out"
exit $status
