#!/usr/bin/env bash
# Usage: bad_input.sh PERIDEAL [GROUP]
#
# Kind of test: bad input. Bad input to load-stepped quasi-static fracture
# (issue 24): each case must exit non-zero on 1 and on 2 processes (without
# hanging), print a message that names the offending entry, its value and
# the fix, and leave no output that looks complete (the load-displacement
# CSV and the PVD record are removed with the rest of out/). The cases edit
# bad_input/base.prm, a 20 x 20 centre-cracked plate that runs to failure
# in about a second. GROUP: a function group_<name> below (each is a ctest
# of its own), or 'all' (the default).
set -u
perideal="$1"; group="${2:-all}"
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../bad_input_checks.sh"
left_behind="out/solution.pvd out/load_displacement.csv"
enter_work "bad_input.$group"
cp "$here/bad_input/base.prm" base.prm

# The valid input runs; the load path: load steps and end time.
group_load_path() {
  expect_valid 1 base.prm "the valid base input" out/solution.pvd out/load_displacement.csv
  rm -rf out
  for np in 1 2; do
    expect_error 's/set Load steps = 10/set Load steps = 0/' \
      "Invalid value '0' for the parameter 'quasi-static/Load steps': give at least 1 step" $np
    expect_error 's/set End time = 1/set End time = 0/' \
      "Invalid value '0' for the parameter 'quasi-static/End time': give a time > 0" $np
  done
  expect_error 's/set Load steps = 10/set Load steps = -3/' \
    "Invalid value '-3' for the parameter 'quasi-static/Load steps': give at least 1 step"
  expect_error 's/set End time = 1/set End time = -1/' \
    "Invalid value '-1' for the parameter 'quasi-static/End time': give a time > 0"
}

# Runs that cannot give the answer asked for: a load that never reaches the
# critical stretch (the largest stretch is reported instead of looping),
# step cutting below the minimum (the step and the load named; here at the
# second step), NaN in the prescribed displacement at the second step, no
# critical stretch, a reaction boundary that nothing holds.
group_during_run() {
  for np in 1 2; do
    expect_error 's/set End time = 1/set End time = 0.01/' \
      "Invalid value '0.01' for the parameter 'quasi-static/End time': 'Bond breaking = all beyond critical', but no bond reached its critical stretch up to t = 0.01: the largest stretch is 0.149" $np
    expect_error 's/set End time = 1/set End time = 1\n  set Minimum load step = 0.05/' \
      "Invalid value '0.05' for the parameter 'quasi-static/Minimum load step': load step 2 to t = 0.1 cannot be cut further, and 45 bonds are past their critical stretch" $np
    expect_error 's/2e-5\*t\*sign(y)/2e-5*t*sign(y) + 0*sqrt(0.08-t)/; s/set Load steps = 10/set Load steps = 20/' \
      "Invalid value '0; 2e-5*t*sign(y) + 0*sqrt(0.08-t)' for the parameter 'Boundary conditions/Dirichlet displacement/Function expression': component 1 is -nan at the node (-0.0475 -0.0475) at t = 0.1" $np
    expect_error 's/    set Fracture energy = 3.8//' \
      "Invalid value 'all beyond critical' for the parameter 'quasi-static/Bond breaking': the material model has no critical stretch, so no bond can break" $np
    expect_error 's/set Reaction boundary ids = 3/set Reaction boundary ids = 1/' \
      "Invalid value '1' for the parameter 'quasi-static/Reaction boundary ids': boundary id 1 has no Dirichlet layer, so nothing holds it and it has no reaction" $np
  done
  expect_error 's/set Reaction boundary ids = 3/set Reaction boundary ids = 7/' \
    "Invalid value '7' for the parameter 'quasi-static/Reaction boundary ids': boundary id 7 has no Dirichlet layer"
}

# 'Nonlinear solver = dynamic relaxation': the entries it does not use, its
# own entries under Newton, a bad tolerance, too few iterations (a solve
# that fails down to the minimum load step), a boundary treatment without
# it.
group_dynamic_relaxation() {
  local dr='s/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  set Nonlinear solver = dynamic relaxation/'
  local dr_only="$dr"'; /subsection Linear solver/,/^end/d'
  sed "$dr_only" base.prm > relax.prm
  expect_valid 2 relax.prm "dynamic relaxation" out/solution.pvd out/load_displacement.csv
  rm -rf out
  for np in 1 2; do
    expect_error "$dr" \
      "Invalid value 'CG' for the parameter 'Linear solver/Method': this entry has no effect here: 'quasi-static/Nonlinear solver = dynamic relaxation' solves no linear system" $np
    expect_error "$dr_only"'; s/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  subsection dynamic relaxation\n    set Maximum iterations = 20\n  end/' \
      "Invalid value '9.765625e-05' for the parameter 'quasi-static/Minimum load step': load step 1 to t = 9.765625e-05 did not converge and cannot be cut further" $np
  done
  expect_error "$dr_only"'; s/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  subsection dynamic relaxation\n    set Relative tolerance = 0\n  end/' \
    "Invalid value '0' for the parameter 'quasi-static/dynamic relaxation/Relative tolerance': give a tolerance in (0, 1)"
  expect_error 's/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  subsection dynamic relaxation\n    set Maximum iterations = 20\n  end/' \
    "Invalid value '20' for the parameter 'quasi-static/dynamic relaxation/Maximum iterations': this entry has no effect here: 'Nonlinear solver = Newton' does not relax"
  expect_error 's/  set No-fail boundary ids = 2, 3/  set Nonlinear solver = dynamic relaxation/; /subsection Linear solver/,/^end/d; s/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = surface nodes\nend/; s/set Bond breaking = all beyond critical/set Bond breaking = off/; /Pre-cracks/d; /Fracture energy/d; /Reaction boundary/d; s/set Load steps = 10/set Load steps = 1/' \
    "Invalid value 'dynamic relaxation' for the parameter 'quasi-static/Nonlinear solver': the boundary treatment 'surface nodes' does not offer it yet"
}

# 'Kinematics = finite deformation': it runs (and breaks the plate); the
# Newton entries where they do nothing (small strain, dynamic relaxation),
# a bad tolerance, the combinations it does not solve (the assembled
# operator, the surface node method); load steps with the surface node
# method.
group_finite_deformation() {
  local finite='s/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  set Kinematics = finite deformation/'
  local newton='s/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  subsection Newton\n    set Relative tolerance = 1e-9\n  end/'
  sed "$finite" base.prm > finite.prm
  expect_valid 2 finite.prm "finite deformation" out/solution.pvd out/load_displacement.csv
  rm -rf out
  for np in 1 2; do
    expect_error "$newton" \
      "Invalid value '1e-9' for the parameter 'quasi-static/Newton/Relative tolerance': this entry has no effect here: with 'Kinematics = small strain' each equilibrium is one linear solve" $np
    expect_error "$finite"'; s/set Operator = matrix-free/set Operator = assembled/; s/set Preconditioner = local elasticity/set Preconditioner = AMG/' \
      "Invalid value 'finite deformation' for the parameter 'quasi-static/Kinematics': its Newton corrections run on the matrix-free operator" $np
  done
  expect_error "$finite; $(echo "$newton" | sed 's/1e-9/0/')" \
    "Invalid value '0' for the parameter 'quasi-static/Newton/Relative tolerance': give a tolerance between 0 and 1"
  expect_error "$finite"'; s/  set No-fail boundary ids = 2, 3/  set No-fail boundary ids = 2, 3\n  set Nonlinear solver = dynamic relaxation\n  subsection Newton\n    set Maximum iterations = 5\n  end/; /subsection Linear solver/,/^end/d' \
    "Invalid value '5' for the parameter 'quasi-static/Newton/Maximum iterations': this entry has no effect here: 'Nonlinear solver = dynamic relaxation' has its own test of convergence"
  local surface='/subsection Linear solver/,/^end/d; s/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = surface nodes\nend/; s/set Bond breaking = all beyond critical/set Bond breaking = off/; /Pre-cracks/d; /Fracture energy/d; /Reaction boundary/d; s/  set No-fail boundary ids = 2, 3//'
  expect_error "$surface; s/set Load steps = 10/set Load steps = 1\n  set Kinematics = finite deformation/" \
    "Invalid value 'finite deformation' for the parameter 'quasi-static/Kinematics': the boundary treatment 'surface nodes' solves small strains only"
  # Load stepping itself needs a system that can step (was an internal
  # error with the surface node method).
  expect_error "$surface" \
    "Invalid value '10' for the parameter 'quasi-static/Load steps': the boundary treatment 'surface nodes' solves one load only; set 'Load steps = 1'"
}

# Boxes: per-box Dirichlet components that do not match the boxes, name no
# component or one the run lacks, or come without boxes; a reaction box
# that holds no prescribed node or no node at all; the box named by its
# place in the list.
group_boxes() {
  local box='s/set Dirichlet components = x, y/set Dirichlet components = x, y\n  set Dirichlet boxes = -0.05, -0.003, -0.045, 0.003/'
  for np in 1 2; do
    expect_error "$box"'; s/set Dirichlet components = x, y/set Dirichlet components = x, y\n  set Dirichlet box components = x; y/' \
      "Invalid value 'x; y' for the parameter 'Boundary conditions/Dirichlet box components': it gives 2 component lists for 1 Dirichlet boxes; give one list per box, separated by ';'" $np
    expect_error 's/set Reaction boundary ids = 3/set Reaction boundary ids = 3\n  set Reaction boxes = -0.01, 0.02, 0.01, 0.03/' \
      "Invalid value '-0.01, 0.02, 0.01, 0.03' for the parameter 'quasi-static/Reaction boxes': box 1 holds no prescribed node, so nothing holds it and it has no reaction" $np
  done
  expect_error 's/set Reaction boundary ids = 3/set Reaction boundary ids = 3\n  set Reaction boxes = -0.05, 0.045, 0.05, 0.05; -0.01, 0.02, 0.01, 0.03/' \
    "Invalid value '-0.05, 0.045, 0.05, 0.05; -0.01, 0.02, 0.01, 0.03' for the parameter 'quasi-static/Reaction boxes': box 2 holds no prescribed node"
  expect_error "$box"'; s/set Dirichlet boxes = -0.05, -0.003, -0.045, 0.003/set Dirichlet boxes = -0.05, -0.003, -0.045, 0.003; 0.3, 0.3, 0.31, 0.31/' \
    "Invalid value '-0.05, -0.003, -0.045, 0.003; 0.3, 0.3, 0.31, 0.31' for the parameter 'Boundary conditions/Dirichlet boxes': box 2 holds no node centre"
  expect_error "$box"'; s/set Dirichlet components = x, y/set Dirichlet components = x, y\n  set Dirichlet box components = z/' \
    "Invalid value 'z' for the parameter 'Boundary conditions/Dirichlet box components': 'z' is not a displacement component of this 2D run; use x, y"
  expect_error 's/set Dirichlet components = x, y/set Dirichlet components = x, y\n  set Dirichlet box components = y/' \
    "Invalid value 'y' for the parameter 'Boundary conditions/Dirichlet box components': there are no 'Dirichlet boxes', so these components would prescribe nothing"
  expect_error 's/set Reaction boundary ids = 3/set Reaction boundary ids = 3\n  set Reaction boxes = 0.2, 0.2, 0.3, 0.3/' \
    "Invalid value '0.2, 0.2, 0.3, 0.3' for the parameter 'quasi-static/Reaction boxes'"
}

run_case_group "$group"
finish "all bad inputs rejected with clear messages"
