#!/usr/bin/env bash
# Kind of test: convergence rate (independent of earlier output).
# The manufactured quadratic cases of lps_2d_plane_strain_quadratic.prm
# (2D, direct solver) and lps_3d_quadratic_cg_amg.prm (3D, here matrix-free
# CG with the local elasticity preconditioner to 1e-12) at a fixed horizon
# (delta = 0.1 in 2D, 0.125 in 3D) and m = 2, 4, i.e. h = delta / m: the
# error against the analytical (classical) solution must fall as m grows.
# For a quadratic field the continuous LPS operator equals the classical
# one, so what remains is the quadrature error of the partial-volume rule,
# which vanishes as h / delta -> 0. Measured orders in m (relative L2
# error): 2D 4.6 from m = 2 to 4 (6.9e-4 -> 2.9e-5) and 4.3 from 4 to 8
# (-> 1.4e-6); 3D 4.3 from m = 2 to 4 (4.6e-5 -> 2.3e-6). The test
# requires an order of at least 3.5 in both and errors that are finite.
#
# Usage: m_convergence.sh PERIDEAL SOURCE_DIR
set -u
perideal="$1"; src="$2"
work="$(pwd)/m_convergence"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
failures=0

# error DIM M: relative L2 error of the case at m-ratio M.
error() {
  local dim=$1 m=$2 input
  if [ "$dim" = 2 ]; then
    local n=$((10 * m))
    sed -e "s/set Subdivisions = 30, 30/set Subdivisions = $n, $n/" \
        -e "s/set m-ratio = 3/set m-ratio = $m/" \
        -e "s/set Write VTU = true/set Write VTU = false/" \
        "$src/lps_2d_plane_strain_quadratic.prm" > case$dim.$m.prm
  else
    local n=$((8 * m))
    sed -e "s/set Subdivisions = 14, 14, 14/set Subdivisions = $n, $n, $n/" \
        -e "s/set m-ratio = 2/set m-ratio = $m/" \
        -e "s/set Method *= CG/set Method = CG\n  set Operator = matrix-free\n  set Preconditioner = local elasticity/" \
        -e '/set Preconditioner *= AMG/d' \
        "$src/lps_3d_quadratic_cg_amg.prm" > case$dim.$m.prm
  fi
  "$perideal" case$dim.$m.prm > case$dim.$m.log 2>&1 \
    || { cat case$dim.$m.log >&2; echo "FAIL: ${dim}D m = $m exited non-zero" >&2; return 1; }
  sed -n 's/.*relative L2 \([0-9.e+-]*\),.*/\1/p' case$dim.$m.log
}

for dim in 2 3; do
  e2=$(error $dim 2) && e4=$(error $dim 4) || { failures=$((failures + 1)); continue; }
  echo "${dim}D m = 2: relative L2 error $e2; m = 4: $e4"
  awk -v a="$e2" -v b="$e4" -v d="$dim" 'BEGIN {
    if (!(a > 0 && b > 0)) { print "FAIL: " d "D errors not positive and finite"; exit 1 }
    order = log(a / b) / log(2);
    printf "%dD observed order in m: %.2f (required >= 3.5)\n", d, order;
    exit !(order >= 3.5) }' || { echo "FAIL: ${dim}D convergence order below 3.5"; failures=$((failures + 1)); }
done
[ "$failures" -eq 0 ] && echo OK
exit "$failures"
