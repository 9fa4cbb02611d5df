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

# case: dim h m velocity ranks threads scheme
# scheme: standard, or hybrid (the adaptive hybrid quadrature of issue 23,
# study 5: 'Quadrature/Scheme = hybrid' with the order-2 lattice row
# stabilised as examples/step-6 runs it and the default critical stretch
# fraction 0.8; the runs CSV gets its standard nodes at the end and its
# late switches).
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
3 0.001 3 16 2 1 hybrid"
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
echo "case,dim,h,m,velocity,nodes,ranks,threads,steps,wall_seconds,peak_memory_mb,scheme,standard_nodes_percent,late_switches" > "$summary"
echo "$cases" | while read -r dim h m v ranks threads scheme; do
  scheme=${scheme:-standard}
  name="kw_${dim}d_h${h}_m${m}_v${v}"
  [ "$scheme" = standard ] || name="${name}_$scheme"
  nx=$(awk -v h=$h 'BEGIN { printf "%d", 0.1 / h + 0.5 }')
  ny=$((2 * nx)); nz=$(awk -v h=$h 'BEGIN { printf "%d", 0.009 / h + 0.5 }')
  impact=$(awk -v h=$h 'BEGIN { printf "%.6g", 3 * h }')
  sed -e "s/@NX@/$nx/; s/@NY@/$ny/; s/@NZ@/$nz/; s/@M@/$m/; s/@V@/$v/g" \
      -e "s/@IMPACT@/$impact/; s/@END@/90e-6/; s/@OUTPUT@/90e-6/; s/@H@/$h/" \
      "$here/kalthoff_winkler_${dim}d.prm.in" > "$work/$name.prm"
  [ "$scheme" = hybrid ] && echo "$hybrid_block" >> "$work/$name.prm"
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
  echo "$name,$dim,$h,$m,$v,$nodes,$ranks,$threads,$steps,$wall,$mem,$scheme,$standard_percent,$late" >> "$summary"
  echo "$name: $nodes nodes, $steps steps, $wall s"
done
/usr/bin/python3 "$here/plot_kalthoff_winkler.py" "$out"
