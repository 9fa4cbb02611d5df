#!/usr/bin/env bash
# Dynamic crack branching in soda-lime glass (examples/step-4: Ha & Bobaru
# 2010, Bobaru & Zhang 2015): crack-tip position and speed against time, as
# a fraction of the Rayleigh speed, initiation and branching time and
# position, for a 2 MPa and a 4 MPa traction step, with convergence in the
# horizon (delta = 1 and 0.5 mm at m = 4) and in m (3, 4, 5 at delta = 1 mm),
# and the adaptive hybrid quadrature of examples/step-6 on three of them
# (study 5 of issue 23: branching time and place, hybrid against standard).
# Each run's wall time and peak memory are recorded, and the hybrid's
# standard nodes at the end.
#
# Usage: bench/dynamics/run_branching.sh [BUILD_DIR] [--quick]
# Writes results/dynamics/branching.csv, branch_<case>.csv (tip histories)
# and branching.png (plot_branching.py).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/log_fields.sh"
build=$(cd "${1:-build}" && pwd)
quick=${2:-}
perideal="$build/bin/perideal"
example="$here/../../examples/step-4/step-4.prm"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"; mkdir -p "$out"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

# case: delta (m), m, traction (Pa), quadrature scheme (standard, or
# hybrid: the adaptive hybrid of examples/step-6, alpha = 0.6, stabilised
# C2 rows; study 5 of issue 23). BRANCHING_CASES (lines of the same four
# columns) runs other cases.
cases="0.001 3 2e6 standard
0.001 4 2e6 standard
0.001 5 2e6 standard
0.0005 4 2e6 standard
0.001 4 4e6 standard
0.0005 4 4e6 standard
0.001 4 2e6 hybrid
0.0005 4 2e6 hybrid
0.001 4 4e6 hybrid"
[ "$quick" = "--quick" ] && cases="0.001 3 2e6 standard"
cases=${BRANCHING_CASES:-$cases}

summary="$out/branching_runs.csv"
echo "case,delta,m,traction,scheme,nodes,steps,wall_seconds,peak_memory_mb,standard_nodes_final" > "$summary"
echo "$cases" | while read -r delta m traction scheme; do
  name="branch_d${delta}_m${m}_s${traction}"
  [ "$scheme" = standard ] || name="${name}_$scheme"
  nx=$(awk -v d=$delta -v m=$m 'BEGIN { printf "%d", 0.1 * m / d + 0.5 }')
  ny=$(awk -v d=$delta -v m=$m 'BEGIN { printf "%d", 0.04 * m / d + 0.5 }')
  sed -e "s/set Subdivisions = .*/set Subdivisions = $nx, $ny/" \
      -e "s/set Length = .*/set Length = $delta/" \
      -e "s/set Function expression = 0; 0; 0; 2e6/set Function expression = 0; 0; 0; $traction/" \
      -e "s/set Output interval .*/set Output interval = 46e-6/" \
      -e "s/set Energy every steps .*/set Energy every steps = 5/" \
      -e "s|set Directory = output|set Directory = $name|" \
      "$example" > "$work/$name.prm"
  if [ "$scheme" = hybrid ]; then
    # The quadrature of examples/step-6 (same plate, same loads).
    sed -n '/^subsection Quadrature/,/^end/p' "$here/../../examples/step-6/step-6.prm" >> "$work/$name.prm"
  fi
  ( cd "$work" && "$perideal" --threads 2 "$name.prm" ) > "$work/$name.log" 2>&1 \
    || { tail -20 "$work/$name.log"; echo "FAILED: $name"; exit 1; }
  cp "$work/$name/energies.csv" "$out/$name.csv"
  nodes=$(log_field "$work/$name.log" nodes)
  steps=$(log_field "$work/$name.log" steps)
  wall=$(log_field "$work/$name.log" wall)
  mem=$(log_field "$work/$name.log" memory)
  standard=$(awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "standard_nodes") c = k; next } { v = c ? $c : "all" } END { print v }' "$work/$name/energies.csv")
  echo "$name,$delta,$m,$traction,$scheme,$nodes,$steps,$wall,$mem,$standard" >> "$summary"
  echo "$name: $nodes nodes, $steps steps, $wall s"
done
/usr/bin/python3 "$here/plot_branching.py" "$out"
