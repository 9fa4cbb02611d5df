#!/usr/bin/env bash
# Kind of test: convergence rate (independent of earlier output).
# The 2D plane-strain LPS case of lps_2d_plane_strain_quadratic.prm
# (manufactured quadratic field, Dirichlet layers, exact partial volumes)
# at a fixed horizon delta = 0.1 and m = 2, 4, i.e. h = delta / m: the
# error against the analytical (classical) solution must fall as m grows.
# For a quadratic field the continuous LPS operator equals the classical
# one, so what remains is the quadrature error of the partial-volume rule,
# which vanishes as h / delta -> 0. Measured order in m (relative L2 error):
# 4.6 from m = 2 to 4 and 4.3 from 4 to 8 (errors 6.9e-4, 2.9e-5, 1.4e-6).
# The test requires an order of at least 3.5 and errors that are finite.
#
# Usage: m_convergence.sh PERIDEAL SOURCE_DIR
set -u
perideal="$1"; src="$2"
work="$(pwd)/m_convergence"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
error() { # m -> relative L2 error
  local n=$((10 * $1))
  sed -e "s/set Subdivisions = 30, 30/set Subdivisions = $n, $n/" \
      -e "s/set m-ratio = 3/set m-ratio = $1/" \
      -e "s/set Write VTU = true/set Write VTU = false/" \
      "$src/lps_2d_plane_strain_quadratic.prm" > m$1.prm
  "$perideal" m$1.prm > m$1.log 2>&1 || { cat m$1.log; echo "FAIL: m = $1 exited non-zero" >&2; return 1; }
  sed -n 's/.*relative L2 \([0-9.e+-]*\),.*/\1/p' m$1.log
}
e2=$(error 2) && e4=$(error 4) || exit 1
echo "m = 2: relative L2 error $e2"
echo "m = 4: relative L2 error $e4"
awk -v a="$e2" -v b="$e4" 'BEGIN {
  if (!(a > 0 && b > 0)) { print "FAIL: errors not positive and finite"; exit 1 }
  order = log(a / b) / log(2);
  printf "observed order in m: %.2f (required >= 3.5)\n", order;
  exit !(order >= 3.5) }' || { echo "FAIL: convergence order below 3.5"; exit 1; }
echo OK
