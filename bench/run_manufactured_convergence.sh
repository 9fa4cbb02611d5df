#!/usr/bin/env bash
# Whole-body manufactured-solution study of the PD operator with the
# perideal driver: LPS (E = 1, nu = 1/4, Gaussian influence, exact partial
# volumes) on the unit square (plane strain) and the unit cube, with the
# displacement prescribed in a layer two horizons thick on every face, so
# that every free node's neighbours have full neighbourhoods and the error
# is that of the discrete PD operator. Fields:
#   quadratic  2D: u = c (x^2 + 2y^2, xy + y^2)
#              3D: u = c (x^2 + 2y^2 + yz, xy + z^2, xz + y^2)
#   linear     a general affine field, zero body force (patch test)
# with the body force b = -[(kappa or K + mu/3) grad div u + mu Laplace u].
# Studies: refinement at fixed m-ratio (horizon shrinks with h) and at fixed
# horizon (m-ratio grows), in 2D and 3D.
#
#   bash bench/run_manufactured_convergence.sh [--quick] [--output-dir DIR]
#
# Writes DIR/summary.csv (the driver's summary columns plus study, field),
# DIR/logs/*.log, and with matplotlib DIR/error_vs_time.png and
# DIR/error_vs_h.png. DIR defaults to results/manufactured_convergence.
# Solver: CG + Jacobi to 1e-13 (the free region's systems are well
# conditioned; direct MUMPS gives the same errors but more memory).
set -euo pipefail
cd "$(dirname "$0")/.."

source bench/driver_study.sh
driver_study_setup results/manufactured_convergence "$@"

# Studies: "name dim field horizon-spec value N..."
if [ $quick -eq 1 ]; then
  studies=(
    "fixed_m_2d 2 quadratic m-ratio 3 20 40"
    "fixed_delta_2d 2 quadratic length 0.1 20 30"
    "fixed_m_3d 3 quadratic m-ratio 2 12"
    "patch_2d 2 linear m-ratio 3 20"
  )
else
  studies=(
    "fixed_m_2d 2 quadratic m-ratio 3 20 40 80 160 320"
    "fixed_delta_2d 2 quadratic length 0.1 20 30 40 60 80 120"
    "fixed_m_3d 3 quadratic m-ratio 3 16 20 24 28 32"
    "fixed_delta_3d 3 quadratic length 0.15 10 14 20 26 30"
    "patch_2d 2 linear m-ratio 3 20 80 320"
    "patch_3d 3 linear m-ratio 3 16 24 32"
  )
fi

write_input() { # dim field spec value N summary
  local dim=$1 field=$2 spec=$3 value=$4 n=$5 summary=$6
  local vars subdiv corner ids u b consts
  if [ "$dim" -eq 2 ]; then
    vars="x,y"; subdiv="$n, $n"; corner="1, 1"; ids="0, 1, 2, 3"
    consts="c=1e-3, kappa=0.8, mu=0.4"
    if [ "$field" = quadratic ]; then
      u="c*(x^2 + 2*y^2); c*(x*y + y^2)"
      b="-c*(3*kappa + 6*mu); -c*(2*kappa + 2*mu)"
    else
      u="c*(x - 0.4*y) + 1e-4; c*(0.6*x + 0.3*y)"; b="0; 0"
    fi
  else
    vars="x,y,z"; subdiv="$n, $n, $n"; corner="1, 1, 1"; ids="0, 1, 2, 3, 4, 5"
    consts="c=1e-3, K=0.6666666666666666, mu=0.4"
    if [ "$field" = quadratic ]; then
      u="c*(x^2 + 2*y^2 + y*z); c*(x*y + z^2); c*(x*z + y^2)"
      b="-c*(4*(K + mu/3) + 6*mu); -2*c*mu; -2*c*mu"
    else
      u="c*(x + 0.2*y - 0.1*z) + 1e-4; c*(0.3*x - 0.5*y + 0.4*z); c*(-0.2*x + 0.1*y + 0.7*z)"
      b="0; 0; 0"
    fi
  fi
  local horizon_entry plane=""
  # 'Plane model' is a 2D entry (3D input with it is refused).
  [ "$dim" = 2 ] && plane="set Plane model     = plane strain"
  if [ "$spec" = m-ratio ]; then horizon_entry="set m-ratio = $value"; else horizon_entry="set Length = $value"; fi
  cat <<PRM
set Dimension = $dim
subsection Geometry
  set Upper corner = $corner
  set Lower corner = $(echo "$corner" | sed 's/1/0/g')
  set Subdivisions = $subdiv
end
subsection Horizon
  set Specification = $spec
  $horizon_entry
end
subsection Material model
  subsection linear peridynamic solid
    set Young's modulus = 1
    set Poisson's ratio = 0.25
    $plane
  end
end
subsection Boundary conditions
  set Dirichlet boundary ids    = $ids
  set Dirichlet layer thickness = 2
  subsection Dirichlet displacement
    set Variable names      = $vars
    set Function constants  = $consts
    set Function expression = $u
  end
  subsection Body force
    set Variable names      = $vars
    set Function constants  = $consts
    set Function expression = $b
  end
end
subsection Analytical solution
  set Compare with analytical solution = true
  subsection Displacement
    set Variable names      = $vars
    set Function constants  = $consts
    set Function expression = $u
  end
end
subsection Linear solver
  set Method             = CG
  set Preconditioner     = Jacobi
  set Relative tolerance = 1e-13
end
subsection Output
  set Write VTU    = false
  set Summary file = $summary
end
PRM
}

csv="$out/summary.csv"
rm -f "$csv" "$out"/runs_*.csv
for study in "${studies[@]}"; do
  read -r name dim field spec value sizes <<<"$study"
  for n in $sizes; do
    summary="$out/runs_${name}.csv"
    write_input "$dim" "$field" "$spec" "$value" "$n" "$summary" > "$out/logs/${name}_$n.prm"
    printf '%-16s N = %-4s ' "$name" "$n"
    "$perideal" "$out/logs/${name}_$n.prm" > "$out/logs/${name}_$n.log" 2>&1 \
      || { cat "$out/logs/${name}_$n.log"; exit 1; }
    grep "error against" "$out/logs/${name}_$n.log" | sed 's/^ *error against the analytical solution: //' | tr -d '\n'
    echo "  ($(sed -n 's/^total wall time \([0-9.e+-]*\) s.*/\1/p' "$out/logs/${name}_$n.log") s)"
  done
  # Prefix the study and field to each line of this study's summary.
  if [ ! -f "$csv" ]; then
    echo "study,field,$(head -1 "$summary")" > "$csv"
  fi
  tail -n +2 "$summary" | sed "s/^/$name,$field,/" >> "$csv"
  rm -f "$summary"
done
echo "wrote $csv"

plot_if_possible bench/plot_manufactured_convergence.py "$csv" "$out"

# The patch tests must be exact to round-off.
awk -F, 'NR > 1 && $2 == "linear" && ($18 > 1e-11 || $19 > 1e-11) { bad = 1;
         print "patch test failed: " $0 } END { exit bad }' "$csv"
