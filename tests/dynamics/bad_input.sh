#!/usr/bin/env bash
# Usage: bad_input.sh PERIDEAL [GROUP]
#
# Bad input to the explicit dynamics problem type: each case must exit
# non-zero (on 1 and on 2 processes, without hanging), print a message that
# names the offending entry and its value, and leave no output that looks
# complete. An unstable run must stop with the step and the node named and
# keep the output written before it. The cases edit bad_input/base.prm.
# GROUP: the group of cases to run (a function group_<name> below; each is
# a ctest of its own), or all of them (the default, 'all').
set -u
perideal="$1"; group="${2:-all}"
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../bad_input_checks.sh"
left_behind="out/solution.pvd out/energies.csv"
enter_work "bad_input.$group"
cp "$here/bad_input/base.prm" base.prm

# The valid input runs; regions, pre-cracks, crack tip, fracture energy;
# output names; 3D pre-cracks.
group_regions() {
  expect_valid 1 base.prm "the valid base input" out/solution.pvd out/energies.csv
  rm -rf out

  for np in 1 2; do
    expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Time step = 1e-3/' \
      "Invalid value '0.001' for the parameter 'explicit dynamics/Time step': the step exceeds the stability bound" $np
    expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 5, 5, 6, 6/' \
      "Invalid value '5, 5, 6, 6' for the parameter 'explicit dynamics/Pre-cracks': no bond crosses the pre-cracks" $np
    # Regions that hold no node: they would silently do nothing.
    expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boxes = 2, 2, 3, 3/' \
      "Invalid value '2, 2, 3, 3' for the parameter 'explicit dynamics/No-fail boxes': box 1 holds no node centre" $np
    expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boundary ids = 2\n  set No-fail layer thickness = 0.01/' \
      "Invalid value '0.01' for the parameter 'explicit dynamics/No-fail layer thickness': the no-fail layer of boundary id 2 holds no node centre" $np
    expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  set Dirichlet boxes = 0, 0, 0.05, 0.5; 0.3, 0.3, 0.31, 0.31\nend/' \
      "Invalid value '0, 0, 0.05, 0.5; 0.3, 0.3, 0.31, 0.31' for the parameter 'Boundary conditions/Dirichlet boxes': box 2 holds no node centre" $np
  done
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boundary ids = 7/' \
    "Invalid value '7' for the parameter 'explicit dynamics/No-fail boundary ids': boundary id 7 does not occur in the mesh"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Crack tip origin = 0.5, 0.25; 0, 0/' \
    "Invalid value '0.5, 0.25; 0, 0' for the parameter 'explicit dynamics/Crack tip origin': give one point"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Crack tip origin = 0.5/' \
    "Invalid value '0.5' for the parameter 'explicit dynamics/Crack tip origin': a point is 'x, y'"
  expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0, 0.25, 0.5/' \
    "Invalid value '0, 0.25, 0.5' for the parameter 'explicit dynamics/Pre-cracks': a 2D pre-crack is a segment"
  expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0, 0.25, half, 0.25/' \
    "Invalid value '0, 0.25, half, 0.25' for the parameter 'explicit dynamics/Pre-cracks': 'half' in '0, 0.25, half, 0.25' is not a number"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boxes = 1, 0, 0, 1/' \
    "Invalid value '1, 0, 0, 1' for the parameter 'explicit dynamics/No-fail boxes': give the lower corner first"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Load history = t +* 2/' \
    "Invalid value 't +* 2' for the parameter 'explicit dynamics/Load history'"
  expect_error 's/    set Critical stretch = 0.01/    set Critical stretch = 0.01\n    set Fracture energy = 10/' \
    "Invalid value '10' for the parameter 'Material model/bond-based/Fracture energy': give either 'Critical stretch' or 'Fracture energy'"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = fictitious layer\nend/' \
    "Invalid value 'fictitious layer' for the parameter 'Boundary treatment/Treatment': explicit dynamics steps the body's own nodes only"

  # Output names that meet: one output would overwrite or delete another; 3D
  # pre-crack polygons.
  for np in 1 2; do
    expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Energy file = solution.pvd/' \
      "Invalid value 'solution.pvd' for the parameter 'explicit dynamics/Energy file': it puts the energy file at 'out/solution.pvd', where the run also writes the time series ('Output/Base name' = 'solution')" $np
  done
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Energy file = checkpoint/' \
    "Invalid value 'checkpoint' for the parameter 'explicit dynamics/Energy file': it puts the energy file at 'out/checkpoint', where the run also writes the checkpoint directory 'checkpoint' ('Output/Directory' = 'out')"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Energy file = solution_0.1.vtu/' \
    "Invalid value 'solution_0.1.vtu' for the parameter 'explicit dynamics/Energy file': it puts the energy file at 'out/solution_0.1.vtu', where the run also writes the solution records" 2
  expect_error 's|set Directory = out|set Directory = out\n  set Summary file = out/energies.csv|' \
    "Invalid value 'out/energies.csv' for the parameter 'Output/Summary file': it puts the summary file at 'out/energies.csv', where the run also writes the energy file"

  # A self-intersecting 3D pre-crack polygon is called so (a symmetric bow tie
  # was called "collinear", an asymmetric one was accepted).
  to_3d='s/set Dimension = 2/set Dimension = 3/; s/set Lower corner = 0, 0/set Lower corner = 0, 0, 0/; s/set Upper corner = 1, 0.5/set Upper corner = 1, 0.5, 0.5/; s/set Subdivisions = 20, 10/set Subdivisions = 8, 4, 4/; s/set Variable names = x,y,t/set Variable names = x,y,z,t/; s/set Function expression = 0; y > 0.25 ? 1 : -1/set Function expression = 0; y > 0.25 ? 1 : -1; 0/'
  expect_error "$to_3d; s/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0.2, 0.1, 0.25, 0.6, 0.4, 0.25, 0.6, 0.1, 0.25, 0.2, 0.4, 0.25/" \
    "Invalid value '0.2, 0.1, 0.25, 0.6, 0.4, 0.25, 0.6, 0.1, 0.25, 0.2, 0.4, 0.25' for the parameter 'explicit dynamics/Pre-cracks': the pre-crack polygon 1 intersects itself (its edges 1-2 and 3-4 meet)"
  expect_error "$to_3d; s/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0.1, 0.1, 0.1, 0.9, 0.1, 0.1, 0.9, 0.4, 0.1; 0.2, 0.1, 0.25, 0.8, 0.4, 0.25, 0.8, 0.1, 0.25, 0.2, 0.3, 0.25/" \
    "Invalid value '0.1, 0.1, 0.1, 0.9, 0.1, 0.1, 0.9, 0.4, 0.1; 0.2, 0.1, 0.25, 0.8, 0.4, 0.25, 0.8, 0.1, 0.25, 0.2, 0.3, 0.25' for the parameter 'explicit dynamics/Pre-cracks': the pre-crack polygon 2 intersects itself (its edges 1-2 and 3-4 meet)" 2
  expect_error "$to_3d; s/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0.1, 0.1, 0.1, 0.5, 0.1, 0.1, 0.9, 0.1, 0.1/" \
    "Invalid value '0.1, 0.1, 0.1, 0.5, 0.1, 0.1, 0.9, 0.1, 0.1' for the parameter 'explicit dynamics/Pre-cracks': the pre-crack polygon 1 has no area (collinear vertices)"
}

# Runs that stop during the time loop, and moduli that overflow. An
# unstable run stops with the step named; what it wrote before stays
# complete (every record the time series names exists). The energy monitor
# stops it first, when the balance rises (issue 26, class 10); with 'Allow
# energy growth' it warns once and the run goes on until a value (or the
# energy) is not finite, named with the step.
group_during_run() {
  for np in 1 2; do
    sed -e 's/  set End time = 1e-4/  set End time = 0.1\n  set Time step = 1e-3\n  set Allow unstable time step = true\n  set Output every steps = 20/' \
        -e 's/set Critical stretch = 0.01/set Critical stretch = 0/' base.prm > unstable.prm
    stops_during_run $np unstable.prm "the unstable run on $np processes"
    grep -qE "The energy balance \(kinetic \+ elastic energy - external work\) rose to .* at step [0-9]+" <<<"$out" \
      || { echo "$out" | tail -5; fail "unstable run: the energy monitor did not stop it"; }
    sed -i 's/  set Allow unstable time step = true/  set Allow unstable time step = true\n  set Allow energy growth = true/' unstable.prm
    stops_during_run $np unstable.prm "the unstable run with 'Allow energy growth' on $np processes"
    [ "$(grep -c "Warning: The energy balance" <<<"$out")" -eq 1 ] || fail "unstable run with 'Allow energy growth': not one warning"
    grep -qE "not finite at step [0-9]+" <<<"$out" || { echo "$out" | tail -5; fail "unstable run: no step named"; }
  done
  # A value that turns bad during the run stops it with the message; the
  # output written before stays complete (expect_error_later).
  for np in 1 2; do
    # A prescribed velocity and a load history that become non-finite at
    # t > 1.2e-4 (steps of 5e-5): the entry, the step and the time, not "the
    # run is unstable".
    expect_error_later 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  set Dirichlet boundary ids = 0\n  subsection Dirichlet displacement\n    set Function expression = t > 1.2e-4 ? 1\/0 : 0; 0\n  end\nend/; s/  set End time = 1e-4/  set End time = 4e-4\n  set Prescribed quantity = velocity\n  set Output every steps = 2/' \
      "Invalid value 't > 1.2e-4 ? 1/0 : 0; 0' for the parameter 'Boundary conditions/Dirichlet displacement/Function expression': its value, inf, is not finite at step 3 (evaluated at t = 0.000125 s)" $np
    expect_error_later 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  subsection Body force\n    set Function expression = 0; 1\n  end\nend/; s/  set End time = 1e-4/  set End time = 4e-4\n  set Load history = t > 1.2e-4 ? 1\/0 : 1\n  set Output every steps = 2/' \
      "Invalid value 't > 1.2e-4 ? 1/0 : 1' for the parameter 'explicit dynamics/Load history': its value, inf, is not finite at step 3 (evaluated at t = 0.00015 s)" $np
  done
  # A modulus or density whose stiffness leaves the range of doubles is named
  # as the cause (it was "the operator has no bonds?").
  for np in 1 2; do
    expect_error "s/    set Density = 1000/    set Density = 1000\n    set Young's modulus = 1e308/" \
      "Invalid value '1e308' for the parameter 'Material model/bond-based/Young's modulus': with the horizon" $np
  done
  expect_error 's/    set Density = 1000/    set Density = 1e-300/' \
    "Invalid value '1e-300' for the parameter 'Material model/bond-based/Density': the stable time step" 2
}

# The time loop (issue 26). A run that would need an absurd number of steps
# is refused before it starts, with the count and the entry that set it (the
# count was a 32-bit integer that wrapped, and the step taken was never held
# against the bound); an output interval below the step, which looped for
# ever, is refused; a non-finite input function is named by its entry; a
# syntax error names the subsection.
group_time_loop() {
  for np in 1 2; do
    expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Time step = 1e-300/' \
      "Invalid value '1e-300' for the parameter 'explicit dynamics/Time step': a step of 1e-300 s takes 1e+296 steps" $np
    expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Safety factor = 1e-300/' \
      "Invalid value '1e-300' for the parameter 'explicit dynamics/Safety factor': a step of 6.33722e-305 s ('Safety factor' 1e-300 times the stability bound" $np
    expect_error 's/  set End time = 1e-4/  set End time = 250000/' \
      "Invalid value '250000' for the parameter 'explicit dynamics/End time'" $np
    expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Output interval = 1e-22/' \
      "Invalid value '1e-22' for the parameter 'explicit dynamics/Output interval': it is shorter than the time step" $np
    expect_error 's/    set Function expression = 0; y > 0.25 ? 1 : -1/    set Function expression = 0; y > 0.25 ? 1 : 0\/0/' \
      "Invalid value '0; y > 0.25 ? 1 : 0/0' for the parameter 'explicit dynamics/Initial velocity/Function expression': its value" $np
    expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  subsection Body force\n    set Function expression = 0; 1\n  end\nend/; s/  set End time = 1e-4/  set End time = 1e-4\n  set Load history = 1\/0/' \
      "Invalid value '1/0' for the parameter 'explicit dynamics/Load history': its value, inf, is not finite" $np
  done
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Output interval = 1e-300/' \
    "Invalid value '1e-300' for the parameter 'explicit dynamics/Output interval'"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Maximum number of steps = 1/' \
    "Invalid value '1e-4' for the parameter 'explicit dynamics/End time': a step of 5.7035e-05 s ('Safety factor' 0.9 times the stability bound 6.33722e-05 s) takes 2 steps"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  subsection Initial displacement\n    set Function expression = 1\/0; 0\n  end/' \
    "Invalid value '1/0; 0' for the parameter 'explicit dynamics/Initial displacement/Function expression': its value, inf, is not finite at the node at"
  expect_error 's/    set Function expression = 0; y > 0.25 ? 1 : -1/    set Function expression = 0; y >* 2/' \
    "Invalid value '0; y >* 2' for the parameter 'explicit dynamics/Initial velocity/Function expression': it cannot be parsed"
  expect_error 's/    set Function expression = 0; y > 0.25 ? 1 : -1/    set Function expression = y > 0.25 ? 1 : -1/' \
    "Invalid value 'y > 0.25 ? 1 : -1' for the parameter 'explicit dynamics/Initial velocity/Function expression': give 2 expressions"
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Energy balance tolerance = 0/' \
    "Invalid value '0' for the parameter 'explicit dynamics/Energy balance tolerance'"
}

# Entries that would be ignored or do nothing: each an error naming the
# entry and its value (issue 26, class 9), checked before any output.
group_no_effect() {
  ed='s/  set End time = 1e-4/  set End time = 1e-4'
  for np in 1 2; do
    expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Analytical solution\n  set Compare with analytical solution = true\nend/' \
      "Invalid value 'true' for the parameter 'Analytical solution/Compare with analytical solution': this entry has no effect here: explicit dynamics compares with no analytical solution" $np
    expect_error "$ed"'\n  set Probe points = 0.5, 0.25; 2, 0.25/' \
      "Invalid value '0.5, 0.25; 2, 0.25' for the parameter 'explicit dynamics/Probe points': point 2 (2 0.25) lies outside the body" $np
    expect_error "$ed"'\n  set Crack tip origin = -0.5, 0.25/' \
      "Invalid value '-0.5, 0.25' for the parameter 'explicit dynamics/Crack tip origin': point 1 (-0.5 0.25) lies outside the body" $np
    expect_error "$ed"'\n  set Crack tip origin = 0.5, 0.25\n  set Crack tip region = 0.5, 0, 1, 0.5; 2, 2, 3, 3/' \
      "Invalid value '0.5, 0, 1, 0.5; 2, 2, 3, 3' for the parameter 'explicit dynamics/Crack tip region': box 2 holds no node centre" $np
    expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0, 0.25, 0.5, 0.25; 2, 0.25, 3, 0.25/' \
      "Invalid value '0, 0.25, 0.5, 0.25; 2, 0.25, 3, 0.25' for the parameter 'explicit dynamics/Pre-cracks': pre-crack 2 crosses no bond" $np
    expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  set Dirichlet boxes = 0, 0, 0.05, 0.5\n  set Dirichlet components =\nend/' \
      "Invalid value '' for the parameter 'Boundary conditions/Dirichlet components': with no component the Dirichlet layers and boxes would prescribe nothing" $np
  done
  expect_error "$ed"'\n  set Crack tip region = 0, 0, 1, 0.5/' \
    "Invalid value '0, 0, 1, 0.5' for the parameter 'explicit dynamics/Crack tip region': this entry has no effect here: no 'Crack tip origin' is given"
  expect_error "$ed"'\n  set Crack tip damage = 0.5/' \
    "Invalid value '0.5' for the parameter 'explicit dynamics/Crack tip damage': this entry has no effect here: no 'Crack tip origin' is given"
  expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0, 0.25, 0.5, 0.25; 0.7, 0.25, 0.7, 0.25/' \
    "Invalid value '0, 0.25, 0.5, 0.25; 0.7, 0.25, 0.7, 0.25' for the parameter 'explicit dynamics/Pre-cracks': the pre-crack segment 2 has zero length"
  expect_error "$ed"'\n  set Load history = x/' \
    "Invalid value 'x' for the parameter 'explicit dynamics/Load history': give a function of t alone"
  expect_error "$ed"'\n  set Load history = t < 1e-5 ? t \/ 1e-5 : 1/' \
    "Invalid value 't < 1e-5 ? t / 1e-5 : 1' for the parameter 'explicit dynamics/Load history': this entry has no effect here: 'Boundary conditions' gives no body force and no 'Traction boundary ids'"
  expect_error "$ed"'\n  set Time step = 1e-7\n  set Safety factor = 0.5/' \
    "Invalid value '0.5' for the parameter 'explicit dynamics/Safety factor': this entry has no effect here: 'Time step' is given"
  expect_error "$ed"'\n  set Allow unstable time step = true/' \
    "Invalid value 'true' for the parameter 'explicit dynamics/Allow unstable time step': this entry has no effect here"
  expect_error "$ed"'\n  set No-fail layer thickness = 2/' \
    "Invalid value '2' for the parameter 'explicit dynamics/No-fail layer thickness': this entry has no effect here"
  expect_error "$ed"'\n  set Prescribed quantity = velocity/' \
    "Invalid value 'velocity' for the parameter 'explicit dynamics/Prescribed quantity': this entry has no effect here"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  subsection Traction\n    set Function expression = 1e6; 0\n  end\nend/' \
    "Invalid value '1e6; 0' for the parameter 'Boundary conditions/Traction/Function expression': this entry has no effect here: no 'Traction boundary ids' are given"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Method = CG\nend/' \
    "Invalid value 'CG' for the parameter 'Linear solver/Method': this entry has no effect here: the problem type 'explicit dynamics' solves no linear system"
  expect_error "s/    set Density = 1000/    set Density = 1000\n    set Bulk modulus = 1e9/" \
    "Invalid value '1e9' for the parameter 'Material model/bond-based/Bulk modulus': this entry has no effect here: 'Elastic constants' selects Young's modulus and Poisson's ratio"
}

# The hybrid quadrature scheme (Quadrature/Scheme = hybrid): alpha outside
# (0, 1), standard regions that hold no node, models and orders it does not
# support, checkpoints (which do not hold the switched nodes yet), entries
# without effect.
group_hybrid() {
  hy() { printf 's/set Dimension = 2/set Dimension = 2\\nsubsection Quadrature\\n  set Scheme = hybrid\\n%s\\nend/' "$1"; }
  sed "$(hy '')" base.prm > hybrid.prm
  expect_valid 1 hybrid.prm "the hybrid scheme" out/solution.pvd
  rm -rf out
  expect_error "$(hy ''); s/  set Subdivisions = 20, 10/  set Subdivisions = 20, 10\n  set Node perturbation = 0.2/" \
    "Invalid value '0.2' for the parameter 'Geometry/Node perturbation': the hybrid scheme of explicit dynamics shares one collocation row over a uniform grid"
  sed "s/  set Subdivisions = 20, 10/  set Subdivisions = 20, 10\n  set Node perturbation = 0.2/" base.prm > perturbed.prm
  expect_valid 1 perturbed.prm "explicit dynamics on perturbed nodes (standard scheme)" out/solution.pvd
  rm -rf out
  for np in 1 2; do
    expect_error "$(hy '  subsection hybrid\n    set Critical stretch fraction = 1\n  end')" \
      "Invalid value '1' for the parameter 'Quadrature/hybrid/Critical stretch fraction': alpha of Eq. 65 lies strictly between 0 and 1" $np
    expect_error "$(hy '  subsection hybrid\n    set Standard boxes = 2, 2, 3, 3\n  end')" \
      "Invalid value '2, 2, 3, 3' for the parameter 'Quadrature/hybrid/Standard boxes': box 1 holds no node centre" $np
    expect_error "$(hy '  subsection hybrid\n    set Standard boundary ids = 2\n    set Standard layer thickness = 0.01\n  end')" \
      "Invalid value '0.01' for the parameter 'Quadrature/hybrid/Standard layer thickness': the standard layer of boundary id 2 holds no node centre" $np
  done
  expect_error "$(hy '  subsection hybrid\n    set Critical stretch fraction = 0\n  end')" \
    "Invalid value '0' for the parameter 'Quadrature/hybrid/Critical stretch fraction': alpha of Eq. 65 lies strictly between 0 and 1"
  expect_error "$(hy '  subsection hybrid\n    set Standard boundary ids = 9\n  end')" \
    "Invalid value '9' for the parameter 'Quadrature/hybrid/Standard boundary ids': boundary id 9 does not occur in the mesh"
  # The paper's order-4 row (doc/collocation.md Sect. 7) is refused; the
  # stabilised one (the default, Sect. 7.1) runs.
  expect_error "$(hy '  subsection collocation\n    set Order = 4\n    set Stabilisation = none\n  end')" \
    "Invalid value '4' for the parameter 'Quadrature/collocation/Order': the bulk collocation row of this order at this m-ratio has a non-positive diagonal"
  sed "$(hy '  subsection collocation\n    set Order = 4\n  end')" base.prm > hybrid_c4.prm
  expect_valid 1 hybrid_c4.prm "the hybrid scheme, stabilised order 4" out/solution.pvd
  rm -rf out
  expect_error "$(hy '')"'; s/  set Model = bond-based/  set Model = linear peridynamic solid/; s/  subsection bond-based/  subsection linear peridynamic solid/' \
    "Invalid value 'hybrid' for the parameter 'Quadrature/Scheme': the collocation rows of state-based models (LPS, doc/collocation.md Sect. 5) run in quasi-static problems only so far"
  expect_error "$(hy '  subsection hybrid\n    set Configuration = fixed\n    set Critical stretch fraction = 0.5\n  end')" \
    "Invalid value '0.5' for the parameter 'Quadrature/hybrid/Critical stretch fraction': this entry has no effect here: with 'Configuration = fixed' no node switches"
  expect_error "$(hy '  subsection hybrid\n    set Standard layer thickness = 2\n  end')" \
    "Invalid value '2' for the parameter 'Quadrature/hybrid/Standard layer thickness': this entry has no effect here"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Quadrature\n  set Scheme = collocation\nend/' \
    "Invalid value 'collocation' for the parameter 'Quadrature/Scheme': the problem type 'explicit dynamics' does not support this quadrature scheme yet"
}

run_case_group "$group"
finish "all bad inputs rejected with clear messages"
