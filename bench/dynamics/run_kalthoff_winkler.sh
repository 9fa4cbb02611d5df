#!/usr/bin/env bash
# Kalthoff-Winkler impact: crack propagation angle from the upper notch tip
# against the experiment (about 70 deg) and the PD literature (about 68
# deg), with wall times, in 2D plane strain at several grid spacings and
# m-ratios, and in 3D. The impact is a prescribed velocity of the region
# between the notches: 16 m/s, the contact velocity of a 32 m/s projectile
# of the same steel (equal impedances), and 32 m/s as a variant.
#
# Usage: bench/dynamics/run_kalthoff_winkler.sh [BUILD_DIR] [--quick]
# Writes results/dynamics/kalthoff_winkler.csv, kw_<case>.csv (tip paths)
# and kalthoff_winkler.png (plot_kalthoff_winkler.py).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/log_fields.sh"
build=$(cd "${1:-build}" && pwd)
quick=${2:-}
perideal="$build/bin/perideal"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"; mkdir -p "$out"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

# case: dim h m velocity ranks threads scheme [variant]
# scheme: standard, or hybrid (the adaptive hybrid quadrature of issue 23,
# study 5: 'Quadrature/Scheme = hybrid' with the order-2 lattice row
# stabilised as examples/step-6 runs it and the default critical stretch
# fraction 0.8; the runs CSV gets its standard nodes at the end and its
# late switches).
# variant (2D; issue 24: what the gap to 70 deg comes from), default pmb:
#   pmb        bond-based PMB, nu = 1/4 (fixed by the model), a rigid punch
#              (prescribed velocity), zero-width notches;
#   lps_nu0.25 the linear peridynamic solid at the same nu: the model;
#   lps_nu0.3  the LPS at maraging steel's nu = 0.3: Poisson's ratio;
#   pressure   PMB pushed by the pressure rho c_d v of a plane wave with
#              particle velocity v on the impacted face between the
#              notches, instead of the rigid punch: a load that cannot pull
#              the plate back or hold it;
#   notch<w>mm PMB with notches w mm wide (two pre-crack lines w/2 above
#              and below the notch line, closed at its end; w/(2h) must be
#              a whole number, so that the lines run between node rows; the
#              experiment's notches are 0.3 mm wide with a round end).
cases="2 0.002 3 16 1 2 standard
2 0.001 3 16 1 2 standard
2 0.001 3 16 1 2 hybrid
2 0.001 4 16 1 2 standard
2 0.0005 3 16 1 2 standard
2 0.0005 3 16 1 2 hybrid
2 0.0005 4 16 1 2 standard
2 0.001 3 32 1 2 standard
2 0.0005 4 32 1 2 standard
3 0.001 3 16 2 1 standard
3 0.001 3 16 2 1 hybrid
2 0.0005 3 16 1 2 standard lps_nu0.25
2 0.0005 3 16 1 2 standard lps_nu0.3
2 0.0005 3 16 1 2 standard pressure
2 0.0005 3 16 1 2 standard notch1mm
2 0.00025 3 16 1 2 standard
2 0.00025 3 16 1 2 standard notch1mm
2 0.00025 3 16 1 2 standard notch0.5mm
2 0.001 3 16 1 2 standard lps_nu0.25
2 0.001 3 16 1 2 standard lps_nu0.3
2 0.001 3 16 1 2 standard pressure
2 0.001 3 16 1 2 standard notch2mm"
[ "$quick" = "--quick" ] && cases="2 0.002 3 16 1 2 standard
2 0.001 3 16 1 2 standard"
[ -n "${KW_CASES:-}" ] && cases="$KW_CASES"   # a subset, same format
hybrid_block='subsection Quadrature
  set Scheme = hybrid
  subsection collocation
    set Stabilisation = all orders
  end
end'

summary="$out/kalthoff_winkler_runs.csv"
echo "case,dim,h,m,velocity,nodes,ranks,threads,steps,wall_seconds,peak_memory_mb,scheme,standard_nodes_percent,late_switches,variant" > "$summary"
echo "$cases" | while read -r dim h m v ranks threads scheme variant; do
  scheme=${scheme:-standard}; variant=${variant:-pmb}
  name="kw_${dim}d_h${h}_m${m}_v${v}"
  [ "$scheme" = standard ] || name="${name}_$scheme"
  [ "$variant" = pmb ] || name="${name}_$variant"
  nx=$(awk -v h=$h 'BEGIN { printf "%d", 0.1 / h + 0.5 }')
  ny=$((2 * nx)); nz=$(awk -v h=$h 'BEGIN { printf "%d", 0.009 / h + 0.5 }')
  impact=$(awk -v h=$h 'BEGIN { printf "%.6g", 3 * h }')
  sed -e "s/@NX@/$nx/; s/@NY@/$ny/; s/@NZ@/$nz/; s/@M@/$m/; s/@V@/$v/g" \
      -e "s/@IMPACT@/$impact/; s/@END@/90e-6/; s/@OUTPUT@/90e-6/; s/@H@/$h/" \
      "$here/kalthoff_winkler_${dim}d.prm.in" > "$work/$name.prm"
  [ "$scheme" = hybrid ] && echo "$hybrid_block" >> "$work/$name.prm"
  case "$variant" in
    pmb) ;;
    lps_nu*)
      sed -i -e "s/set Model = bond-based/set Model = linear peridynamic solid/" \
        -e "s/subsection bond-based/subsection linear peridynamic solid/" \
        -e "s/set Poisson's ratio = 0.25/set Poisson's ratio = ${variant#lps_nu}/" "$work/$name.prm" ;;
    pressure)
      # sigma = rho c_d v, c_d the plane-strain dilatational speed of the
      # PMB (nu = 1/4): sqrt(E (1 - nu) / (rho (1 + nu) (1 - 2 nu))).
      p=$(awk -v v=$v 'BEGIN { E = 191e9; nu = 0.25; rho = 8000
        printf "%.6g", rho * sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu))) * v }')
      sed -i -e '/set Dirichlet boxes/d; /set Dirichlet components/d; /set Prescribed quantity/d' \
        -e '/subsection Dirichlet displacement/,/^  end/d' \
        -e "s/^subsection Boundary conditions$/subsection Boundary conditions\n  set Traction boundary ids = 0\n  subsection Traction\n    set Variable names      = x,y,t\n    set Function expression = abs(y) < 0.025 ? $p : 0; 0\n  end/" "$work/$name.prm" ;;
    notch*mm)
      w=${variant#notch}; w=${w%mm}
      awk -v w=$w -v h=$h 'BEGIN { k = w / 2e3 / h; exit !(k >= 1 && k == int(k + 1e-9)) }' \
        || { echo "variant $variant: w/(2h) must be a whole number"; exit 1; }
      sed -i "s/set Pre-cracks .*/set Pre-cracks          = $(awk -v w=$w 'BEGIN {
        for (s = -1; s <= 1; s += 2) { c = 0.025 * s; lo = c - w / 2e3; hi = c + w / 2e3
          printf "0, %.6g, 0.05, %.6g; 0, %.6g, 0.05, %.6g; 0.05, %.6g, 0.05, %.6g%s", lo, lo, hi, hi, lo, hi, s < 0 ? "; " : "" } }')/" "$work/$name.prm" ;;
    *) echo "unknown variant $variant"; exit 1 ;;
  esac
  ( cd "$work" && sed -i "s|set Directory = output|set Directory = $name|" "$name.prm" &&
    if [ "$ranks" -eq 1 ]; then "$perideal" --threads "$threads" "$name.prm"; \
    else mpirun --oversubscribe --bind-to none -np "$ranks" "$perideal" --threads "$threads" "$name.prm" < /dev/null; fi ) > "$work/$name.log" 2>&1 \
    || { tail -20 "$work/$name.log"; echo "FAILED: $name"; exit 1; }
  cp "$work/$name/energies.csv" "$out/$name.csv"
  nodes=$(log_field "$work/$name.log" nodes)
  steps=$(log_field "$work/$name.log" steps)
  wall=$(log_field "$work/$name.log" wall)
  mem=$(log_field "$work/$name.log" memory)
  standard_percent=100; late=0
  if [ "$scheme" = hybrid ]; then
    standard_percent=$(sed -n 's/.*nodes standard at the end (\([0-9.e+-]*\) %).*/\1/p' "$work/$name.log" | head -1)
    late=$(sed -n 's/.* \([0-9][0-9]*\) late switches.*/\1/p' "$work/$name.log" | head -1)
  fi
  echo "$name,$dim,$h,$m,$v,$nodes,$ranks,$threads,$steps,$wall,$mem,$scheme,$standard_percent,$late,$variant" >> "$summary"
  echo "$name: $nodes nodes, $steps steps, $wall s"
done
/usr/bin/python3 "$here/plot_kalthoff_winkler.py" "$out"
