#!/usr/bin/env bash
# Usage: hybrid_quasi_static.sh PERIDEAL NPROCS INPUT.prm
#
# The hybrid quadrature scheme with a fixed standard region in a quasi-
# static solve (Quadrature/Scheme = hybrid, Configuration = fixed), on the
# collocation patch test INPUT.prm (a quadratic field with its exact values
# in Dirichlet layers one horizon thick, so that every free node has a full
# ball; 'Scheme = collocation' in the input). Kinds of check: against
# independent references (the collocation and the standard runs of the same
# input, the closed-form solution) and an exact count:
#  - no standard box: every free node takes the collocation row, so the run
#    is the collocation run, error line to the digit (round-off);
#  - a standard box over the whole body: every node is standard, so the run
#    is the standard run, error line to the digit;
#  - a box over the middle of the plate, [0.4, 0.6]^2: the set-up line
#    reports the nodes whose centre lies in it (36 on the 30 x 30 grid,
#    counted here from the grid), and the error against the closed form
#    lies strictly between the collocation run's (round-off) and the
#    standard run's (the lattice floor of 36 standard nodes is less than
#    that of all);
#  - the same box with the assembled operator and MUMPS: the same error
#    (to the printed digits) as matrix-free GMRES;
#  - a layer along 'Standard boundary ids' instead: two horizons along
#    boundary 0 (the first is the Dirichlet layer, whose nodes are standard
#    anyway; three with LPS), the error again strictly between.
# Each variant runs on NPROCS processes. With a state-based (LPS) INPUT
# (Dirichlet layers two horizons thick, collocation_lps_2d_quadratic.prm)
# the standard nodes' dilatations also enter the collocation nodes' forces.
set -u
perideal="$1"; nprocs="$2"; input="$3"
. "$(cd "$(dirname "$0")" && pwd)/../run_checks.sh"
work="$(pwd)/hybrid_quasi_static.$(basename "$input" .prm).np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; exit 1; }

# run NAME SED_SCRIPT: the input edited by SED_SCRIPT, in directory NAME.
run() {
  local name="$1" edit="$2"
  mkdir -p "$name"
  sed -e "$edit" -e 's/set Write VTU = true/set Write VTU = false/' "$input" > "$name/input.prm"
  run_perideal "$perideal" "$nprocs" "$name" \
    || { cat "$name/log"; fail "the run '$name' failed"; }
}
hybrid() {
  printf 's/set Scheme = collocation/set Scheme = hybrid\\n  subsection hybrid\\n    set Configuration = fixed\\n%s  end/' "$1"
}
error_line() { grep -m1 'error against the analytical solution' "$1/log" | sed 's/^ *//'; }
l2() { error_line "$1" | sed -E 's/.*relative L2 ([0-9.e+-]+),.*/\1/'; }

run collocation ''
run standard 's/set Scheme = collocation/set Scheme = standard/; /subsection collocation/,/^  end/d'
run none "$(hybrid '')"
run all "$(hybrid '    set Standard boxes = -1, -1, 2, 2\n')"
run middle "$(hybrid '    set Standard boxes = 0.4, 0.4, 0.6, 0.6\n')"
# The assembled operator (the rows as Trilinos entries, MUMPS) with the
# box in the middle.
direct='/set Method  *= GMRES/d; /set Operator  *= matrix-free/d; /set Preconditioner  *= Jacobi/d; s/set Relative tolerance = 1e-13/set Method = direct/'
lps=false
grep -q 'set Model = linear peridynamic solid' "$input" && lps=true
run middle_direct "$(hybrid '    set Standard boxes = 0.4, 0.4, 0.6, 0.6\n'); $direct"
# (LPS: the Dirichlet layers are two horizons thick, so three reach one
# horizon into the free nodes; a full-ball standard node's dilatation is
# exact on quadratics, only the standard forces are not.)
thickness=2
$lps && thickness=3
run layer "$(hybrid "    set Standard boundary ids = 0\\n    set Standard layer thickness = $thickness\\n")"

for name in collocation standard none all middle middle_direct layer; do
  [ -n "$(error_line $name)" ] || { cat $name/log; fail "no error line in '$name'"; }
  echo "$name: $(error_line $name)"
done
[ "$(error_line none)" = "$(error_line collocation)" ] ||
  fail "hybrid without a standard region differs from the collocation run"
[ "$(error_line all)" = "$(error_line standard)" ] ||
  fail "hybrid with a standard box over the body differs from the standard run"

# The nodes of the grid (spacing 1/30 from 0 in both inputs) whose centre
# (i + 1/2)/30 lies in [0.4, 0.6] in both coordinates.
n_box=$(awk 'BEGIN { n = 0; for (i = 0; i < 40; ++i) { x = (i + 0.5) / 30; if (x >= 0.4 && x <= 0.6) ++n }; print n * n }')
grep -q "quadrature 'hybrid': .* $n_box standard (fixed region)" middle/log ||
  { grep "quadrature 'hybrid'" middle/log; fail "the set-up line does not report $n_box nodes in the box"; }
awk -v c="$(l2 collocation)" -v h="$(l2 middle)" -v s="$(l2 standard)" \
  'BEGIN { exit !(c < h && h < s && h > 1e-10) }' ||
  fail "the error with a standard box in the middle ($(l2 middle)) is not between collocation ($(l2 collocation)) and standard ($(l2 standard))"
grep -q "solved with direct\|MUMPS\|direct" middle_direct/log ||
  fail "the assembled run did not use the direct solver"
awk -v a="$(l2 middle)" -v b="$(l2 middle_direct)" \
  'BEGIN { d = (a - b) / a; if (d < 0) d = -d; exit !(d < 1e-3) }' ||
  fail "matrix-free ($(l2 middle)) and assembled ($(l2 middle_direct)) hybrid runs differ"
grep -q "quadrature 'hybrid': .* [1-9][0-9]* standard (fixed region)" layer/log ||
  { grep "quadrature 'hybrid'" layer/log; fail "the standard layer holds no node"; }
awk -v c="$(l2 collocation)" -v h="$(l2 layer)" -v s="$(l2 standard)" \
  'BEGIN { exit !(c < h && h < s && h > 1e-10) }' ||
  fail "the error with a standard layer ($(l2 layer)) is not between collocation and standard"
echo "PASS"
