#!/usr/bin/env bash
# Usage: finite_deformation.sh PERIDEAL NPROCS
#
# Kind of test: closed forms (rigid motion, objectivity, the affine patch,
# an angular integral) on 'quasi-static/Kinematics = finite deformation'
# (issue 24). A bond-based (PMB) 2D plate, 30 x 30 nodes, m = 3, whose four
# edges are held in Dirichlet layers one horizon thick by an affine field
# u = (R(theta t) U(t) - I) x, U = diag(1 + e t, 1), loaded in 4 steps to
# t = 1; the reaction of the right edge (boundary 1) is written. Checks:
#  - patch: every free node has a full ball and an affine deformation moves
#    each bond and its opposite alike, so the affine field is the exact
#    equilibrium of the finite kinematics too: the error against it must be
#    at the Newton tolerance (relative L2 <= 1e-8), for a rotation of
#    0.5 rad, a stretch e = 0.02 and both together;
#  - rigid rotation (theta = 0.5, e = 0): finite kinematics leave no force,
#    so the reaction must vanish (<= 1e-7 of the reaction of the stretch
#    alone); small-strain kinematics, run on the same input, give the
#    spurious force of the linearised extension n.(R - I)n = cos(theta) - 1
#    (asserted above 1e-2 of it: the check tells the two apart);
#  - objectivity: the reaction of the rotated stretch equals the stretch's
#    reaction rotated by R(0.5), to 1e-7 of its size;
#  - the stretch alone, finite against small strain: the ratio of the
#    reactions against the continuum ratio of a PMB body under the stretch
#    lambda = 1.02 (an angular integral, evaluated in the script), to 10 %
#    of its distance from 1 (small strain gives exactly 1).
# Each variant runs on NPROCS processes.
set -u
perideal="$1"; nprocs="$2"
. "$(cd "$(dirname "$0")" && pwd)/../run_checks.sh"
work="$(pwd)/finite_deformation.np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; exit 1; }

# write NAME THETA E KINEMATICS: the input of one variant in NAME/input.prm.
write() {
  local name="$1" th="$2" e="$3" kin="$4"
  mkdir -p "$name"
  local ux="cos($th*t)*(1+$e*t)*x - sin($th*t)*y - x"
  local uy="sin($th*t)*(1+$e*t)*x + cos($th*t)*y - y"
  local ex="cos($th)*(1+$e)*x - sin($th)*y - x"
  local ey="sin($th)*(1+$e)*x + cos($th)*y - y"
  cat > "$name/input.prm" <<PRM
set Dimension = 2
set Problem type = quasi-static
subsection Geometry
  set Lower corner = -0.05, -0.05
  set Upper corner = 0.05, 0.05
  set Subdivisions = 30, 30
end
subsection Horizon
  set m-ratio = 3
end
subsection Material model
  set Model = bond-based
  subsection bond-based
    set Young's modulus = 72e9
    set Poisson's ratio = 0.3333333333333333
    set Plane model     = plane stress
  end
end
subsection Boundary conditions
  set Dirichlet boundary ids    = 0, 1, 2, 3
  set Dirichlet layer thickness = 1
  subsection Dirichlet displacement
    set Variable names      = x,y,t
    set Function expression = $ux; $uy
  end
end
subsection Analytical solution
  set Compare with analytical solution = true
  subsection Displacement
    set Variable names      = x,y
    set Function expression = $ex; $ey
  end
end
subsection quasi-static
  set End time = 1
  set Load steps = 4
  set Kinematics = $kin
  set Reaction boundary ids = 1
PRM
  if [ "$kin" = "finite deformation" ]; then
    printf '  subsection Newton\n    set Relative tolerance = 1e-10\n  end\n' >> "$name/input.prm"
  fi
  cat >> "$name/input.prm" <<PRM
end
subsection Linear solver
  set Method             = CG
  set Operator           = matrix-free
  set Preconditioner     = local elasticity
  set Relative tolerance = 1e-12
end
subsection Output
  set Directory = output
  set Write VTU = false
end
PRM
}
run() {
  local name="$1"
  run_perideal "$perideal" "$nprocs" "$name" \
    || { cat "$name/log"; fail "the run '$name' failed"; }
}
# The last reaction (x y) of a variant.
reaction() { tail -1 "$1/output/load_displacement.csv" | awk -F, '{ printf "%.17g %.17g", $3, $4 }'; }
l2() { grep -m1 'error against the analytical solution' "$1/log" | sed -E 's/.*relative L2 ([0-9.e+-]+),.*/\1/'; }

write rotation 0.5 0 "finite deformation"; run rotation
write rotation_small 0.5 0 "small strain"; run rotation_small
write stretch 0 0.02 "finite deformation"; run stretch
write stretch_small 0 0.02 "small strain"; run stretch_small
write both 0.5 0.02 "finite deformation"; run both

for v in rotation stretch both; do
  e=$(l2 $v)
  echo "$v: error against the affine field, relative L2 $e (must be <= 1e-8)"
  awk -v e="$e" 'BEGIN { exit !(e != "" && e + 0 <= 1e-8) }' \
    || { cat $v/log; fail "$v: not the affine field"; }
done
read -r sx sy <<< "$(reaction stretch)"
read -r rx ry <<< "$(reaction rotation)"
read -r qx qy <<< "$(reaction rotation_small)"
read -r bx by <<< "$(reaction both)"
read -r lx ly <<< "$(reaction stretch_small)"
awk -v sx="$sx" -v sy="$sy" -v rx="$rx" -v ry="$ry" -v qx="$qx" -v qy="$qy" \
    -v bx="$bx" -v by="$by" -v lx="$lx" 'BEGIN {
  s = sqrt(sx * sx + sy * sy); r = sqrt(rx * rx + ry * ry); q = sqrt(qx * qx + qy * qy)
  printf "stretch e = 0.02: reaction (%.6g, %.6g)\n", sx, sy
  printf "rigid rotation 0.5 rad: |reaction| / |stretch reaction| = %.2e finite (must be <= 1e-7), %.3g small strain (must be >= 1e-2)\n", r / s, q / s
  if (!(r <= 1e-7 * s && q >= 1e-2 * s)) exit 1
  c = cos(0.5); n = sin(0.5); ex = c * sx - n * sy; ey = n * sx + c * sy
  d = sqrt((bx - ex) ^ 2 + (by - ey) ^ 2) / s
  printf "rotated stretch: reaction (%.6g, %.6g), R(0.5) times the stretch reaction (%.6g, %.6g): difference %.2e of its size (must be <= 1e-7)\n", bx, by, ex, ey, d
  if (!(d <= 1e-7)) exit 1
  # Finite against small strain under lambda = 1.02. A bond along phi is
  # stretched by s = sqrt(1 + (lambda^2 - 1) cos^2) - 1 whatever its length
  # and pulls in x with c s lambda cos / (1 + s) (along the deformed bond);
  # linearised, c (lambda - 1) cos^3. The stress sigma_xx = 1/2 int f_x xi_x
  # gives the continuum ratio
  #   int lambda cos^2 (1 - 1/sqrt(1 + (lambda^2 - 1) cos^2)) dphi
  #   / ((lambda - 1) int cos^4 dphi)
  # (Simpson, 2000 intervals on [0, pi/2]). The lattice of m = 3 weighs the
  # bond directions differently from the continuum, so the check allows 10 %
  # of the ratio distance from 1.
  l = 1.02; pi = atan2(0, -1); m = 2000; h = pi / 2 / m; num = 0; den = 0
  for (k = 0; k <= m; ++k) {
    w = (k == 0 || k == m) ? 1 : (k % 2 ? 4 : 2); co = cos(k * h)
    num += w * l * co * co * (1 - 1 / sqrt(1 + (l * l - 1) * co * co))
    den += w * (l - 1) * co ^ 4 }
  expect = num / den; ratio = sx / lx
  printf "finite / small strain reaction_x under lambda = 1.02: %.6f, continuum %.6f (must agree to %.1e)\n", ratio, expect, 0.1 * (expect - 1)
  d = ratio - expect; if (d < 0) d = -d
  exit !(d <= 0.1 * (expect - 1))
}' || fail "rigid motion, objectivity or the stretch ratio"
echo "OK"
