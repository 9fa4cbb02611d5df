#!/usr/bin/env bash
# Usage: bad_input.sh PERIDEAL [GROUP]
#
# Bad input to the diffusion problem type: each case must exit non-zero (on
# 1 and on 2 processes, without hanging), print a message that names the
# offending entry and its value, and leave no output that looks complete. A
# run whose concentration turns non-finite must stop with the step and the
# node named and keep the output written before it.
# GROUP: the group of cases to run (a function group_<name> below; each is
# a ctest of its own), or all of them (the default, 'all').
set -u
perideal="$1"; group="${2:-all}"
. "$(cd "$(dirname "$0")" && pwd)/../bad_input_checks.sh"
left_behind="out/solution.pvd out/history.csv"
enter_work "bad_input.$group"

cat > base.prm <<'PRM'
set Dimension = 2
set Problem type = diffusion
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 0.5
  set Subdivisions = 20, 10
end
subsection diffusion
  set Diffusivity = 1
  set End time = 1e-3
  set Dirichlet boundary ids = 0
  subsection Initial concentration
    set Function expression = x
  end
  subsection Source
    set Function expression = 1
  end
end
subsection Output
  set Directory = out
end
PRM

# Corrosion.
cat > corrosion.prm <<'PRM'
set Dimension = 2
set Problem type = diffusion
subsection Geometry
  set Lower corner = 0, -10e-6
  set Upper corner = 20e-6, 10e-6
  set Subdivisions = 20, 20
end
subsection diffusion
  set Model = corrosion
  set Diffusivity = 8.6e-10
  set End time = 0.1
  set Dirichlet boundary ids = 3
  subsection corrosion
    set Saturation concentration = 4600
    set Current density = 5.1e3
    subsection Initial phase
      set Function expression = y > 0 ? 0 : 1
    end
  end
end
subsection Output
  set Directory = out
end
PRM

# 1D corrosion: points and directions have one coordinate.
cat > corrosion_1d.prm <<'PRM'
set Dimension = 1
set Problem type = diffusion
subsection Geometry
  set Lower corner = -45e-6
  set Upper corner = 11e-6
  set Subdivisions = 56
end
subsection diffusion
  set Model = corrosion
  set Diffusivity = 8.6e-10
  set Flux exponent = 1
  set End time = 1e-3
  set Dirichlet boundary ids = 1
  subsection corrosion
    set Saturation concentration = 4600
    set Current density = 1e6
    set Pit depth direction = -1
    subsection Initial phase
      set Function expression = x > 0 ? 0 : 1
    end
  end
end
subsection Output
  set Directory = out
end
PRM

# The valid input runs; entries of the diffusion problem; output names; 1D
# corrosion.
group_basic() {
  expect_valid 1 base.prm "the valid base input" out/solution.pvd out/history.csv
  rm -rf out

  for np in 1 2; do
    expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set Time step = 1e-2/' \
      "Invalid value '0.01' for the parameter 'diffusion/Time step': forward Euler is stable only up to" $np
    expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Dirichlet layer thickness = 0.01/' \
      "Invalid value '0.01' for the parameter 'diffusion/Dirichlet layer thickness': the layer of boundary id 0 holds no node centre" $np
  done
  expect_error 's/set Diffusivity = 1/set Diffusivity = -2/' \
    "Invalid value '-2' for the parameter 'diffusion/Diffusivity': give a diffusivity > 0"
  expect_error 's/set Diffusivity = 1/set Diffusivity = 1\n  set Flux exponent = 4/' \
    "Invalid value '4' for the parameter 'diffusion/Flux exponent': q must be 0, 1, 2 or 3"
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0, 9/' \
    "Invalid value '0, 9' for the parameter 'diffusion/Dirichlet boundary ids': boundary id 9 does not occur in the mesh"
  expect_error 's/set Dirichlet boundary ids = 0/set Time stepping = steady state/' \
    "Invalid value '' for the parameter 'diffusion/Dirichlet boundary ids': a steady state needs prescribed values"
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Time stepping = implicit/' \
    "Invalid value '0' for the parameter 'diffusion/Time step': implicit time stepping needs a time step > 0"
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Dirichlet layer values = mirror\n  set Time stepping = implicit\n  set Time step = 1e-4/' \
    "Invalid value 'mirror' for the parameter 'diffusion/Dirichlet layer values': mirror layers need 'Time stepping = explicit'"
  expect_error 's/set End time = 1e-3/set End time = -1/' \
    "Invalid value '-1' for the parameter 'diffusion/End time'"
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Safety factor = 1.5/' \
    "Invalid value '1.5' for the parameter 'diffusion/Safety factor'"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = fictitious layer\nend/' \
    "Invalid value 'fictitious layer' for the parameter 'Boundary treatment/Treatment': the diffusion problem steps the body's own nodes only"

  # Output names that meet: one output would overwrite or delete another. 1D
  # corrosion.
  for np in 1 2; do
    expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set History file = solution.pvd/' \
      "Invalid value 'solution.pvd' for the parameter 'diffusion/History file': it puts the history file at 'out/solution.pvd', where the run also writes the time series ('Output/Base name' = 'solution')" $np
  done
  expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set History file = solution_0.pvtu/' \
    "Invalid value 'solution_0.pvtu' for the parameter 'diffusion/History file': it puts the history file at 'out/solution_0.pvtu'"
  expect_error 's|set Directory = out|set Directory = out\n  set Summary file = out/history.csv|' \
    "Invalid value 'out/history.csv' for the parameter 'Output/Summary file': it puts the summary file at 'out/history.csv', where the run also writes the history file" 2
  expect_error 's|set Directory = out|set Directory = out\n  set Summary file = out/solution.pvd.tmp|' \
    "Invalid value 'out/solution.pvd.tmp' for the parameter 'Output/Summary file'"

  rm -rf out
  expect_valid 1 corrosion_1d.prm "1D corrosion with 'Pit depth direction = -1'"
  rm -rf out
  base_prm=corrosion_1d.prm
  expect_error 's/set Pit depth direction = -1/set Pit depth direction = -1, 0, 0/' \
    "Invalid value '-1, 0, 0' for the parameter 'diffusion/corrosion/Pit depth direction': a point is 'x' in this 1D run" 2
  base_prm=base.prm
}

# Corrosion; mirror flux layers; 1D.
# The collocation quadrature ('Quadrature/Scheme = collocation'): it runs
# with plain diffusion and the continuum micro-diffusivity, and refuses the
# rest by entry.
group_collocation() {
  col='s/set Problem type = diffusion/set Problem type = diffusion\nsubsection Quadrature\n  set Scheme = collocation\nend/'
  sed "$col" base.prm > collocation.prm
  expect_valid 1 collocation.prm "plain diffusion with collocation" out/solution.pvd out/history.csv
  rm -rf out
  expect_error "$col; s/  set Diffusivity = 1/  set Diffusivity = 1\n  set Micro-diffusivity calibration = lattice/" \
    "Invalid value 'lattice' for the parameter 'diffusion/Micro-diffusivity calibration': the collocation quadrature integrates the kernel over the ball exactly"
  # The paper's order-4 row has growing modes at m = 3 (doc/collocation.md
  # Sect. 7): refused for explicit stepping before the run starts; the
  # stabilised one (the default, Sect. 7.1) runs.
  expect_error "$col; s/  set Diffusivity = 1/  set Diffusivity = 1\n  set Time step = 1e-5/; s/  set Scheme = collocation/  set Scheme = collocation\n  subsection collocation\n    set Order = 4\n    set Stabilisation = none\n  end/" \
    "Invalid value '4' for the parameter 'Quadrature/collocation/Order': the bulk collocation row of this order at this m-ratio has growing modes"
  sed "$col; s/  set Scheme = collocation/  set Scheme = collocation\n  subsection collocation\n    set Order = 4\n  end/" base.prm > collocation_c4.prm
  expect_valid 1 collocation_c4.prm "plain diffusion with stabilised order-4 collocation" out/solution.pvd out/history.csv
  rm -rf out
  # The order-2 lattice row stabilised too (doc/collocation.md Sect. 7.3):
  # runs in 2D, refused in 1D, where it has growing modes.
  all_orders="s/  set Scheme = collocation/  set Scheme = collocation\n  subsection collocation\n    set Stabilisation = all orders\n  end/"
  sed "$col; $all_orders" base.prm > collocation_all_orders.prm
  expect_valid 1 collocation_all_orders.prm "plain diffusion with the stabilised order-2 lattice row" out/solution.pvd out/history.csv
  rm -rf out
  expect_error "$col; s/  set Scheme = collocation/  set Scheme = collocation\n  subsection collocation\n    set Stabilisation = none\n  end/" \
    "Invalid value 'none' for the parameter 'Quadrature/collocation/Stabilisation': on a uniform grid 'automatic' leaves the order-2 row as the paper gives it"
  expect_error "$col; $all_orders; s/set Dimension = 2/set Dimension = 1/; s/set Lower corner = 0, 0/set Lower corner = 0/; s/set Upper corner = 1, 0.5/set Upper corner = 1/; s/set Subdivisions = 20, 10/set Subdivisions = 20/" \
    "Invalid value 'all orders' for the parameter 'Quadrature/collocation/Stabilisation': in 1D the stabilised order-2 row has growing modes"
  base_prm=corrosion.prm
  expect_error "$col" \
    "Invalid value 'collocation' for the parameter 'Quadrature/Scheme': the diffusion model 'corrosion' sets phases, and a collocation row has no phase factors"
  # The hybrid scheme (doc/collocation.md, "Hybrid diffusion"): adaptive
  # with corrosion, fixed with every model; adaptive switches nothing
  # without phase changes, and 'Critical stretch fraction' has no effect.
  hyb='s/set Problem type = diffusion/set Problem type = diffusion\nsubsection Quadrature\n  set Scheme = hybrid\nend/'
  sed "$hyb" corrosion.prm > corrosion_hybrid.prm
  expect_valid 1 corrosion_hybrid.prm "corrosion with the adaptive hybrid" out/solution.pvd out/history.csv
  rm -rf out
  expect_error "$hyb; s/  set Scheme = hybrid/  set Scheme = hybrid\n  subsection hybrid\n    set Critical stretch fraction = 0.5\n  end/" \
    "Invalid value '0.5' for the parameter 'Quadrature/hybrid/Critical stretch fraction': this entry has no effect here: the diffusion problem has no bond stretch"
  base_prm=base.prm
  fixed="s/  set Scheme = hybrid/  set Scheme = hybrid\n  subsection hybrid\n    set Configuration = fixed\n    set Standard boxes = 0.3, 0.1, 0.6, 0.4\n  end/"
  sed "$hyb; $fixed" base.prm > hybrid_fixed.prm
  expect_valid 1 hybrid_fixed.prm "plain diffusion with the fixed hybrid" out/solution.pvd out/history.csv
  rm -rf out
  expect_error "$hyb" \
    "Invalid value 'adaptive' for the parameter 'Quadrature/hybrid/Configuration': the diffusion model 'none' changes no phases"
  expect_error "$hyb; $fixed; s/set Dimension = 2/set Dimension = 1/; s/set Lower corner = 0, 0/set Lower corner = 0/; s/set Upper corner = 1, 0.5/set Upper corner = 1/; s/set Subdivisions = 20, 10/set Subdivisions = 20/; s/    set Standard boxes = 0.3, 0.1, 0.6, 0.4//" \
    "Invalid value 'hybrid' for the parameter 'Quadrature/Scheme': the hybrid scheme of the diffusion problem runs in 2D and 3D"
  expect_error "$hyb; s/  set Scheme = hybrid/  set Scheme = hybrid\n  subsection hybrid\n    set Configuration = fixed\n    set Standard boxes = 2, 2, 3, 3\n  end/" \
    "Invalid value '2, 2, 3, 3' for the parameter 'Quadrature/hybrid/Standard boxes'"
  # Irregular nodes: both schemes run on them (collocation with a row per
  # node).
  sed "s/  set Subdivisions = 20, 10/  set Subdivisions = 20, 10\n  set Node perturbation = 0.35/" base.prm > perturbed.prm
  expect_valid 1 perturbed.prm "plain diffusion on perturbed nodes (standard scheme)" out/solution.pvd out/history.csv
  rm -rf out
  sed "$col; s/  set Subdivisions = 20, 10/  set Subdivisions = 20, 10\n  set Node perturbation = 0.35/" base.prm > perturbed_collocation.prm
  expect_valid 1 perturbed_collocation.prm "plain diffusion on perturbed nodes (collocation, a row per node)" out/solution.pvd out/history.csv
  rm -rf out
}

group_corrosion() {
  expect_valid 1 corrosion.prm "the valid corrosion input"
  rm -rf out
  base_prm=corrosion.prm
  for np in 1 2; do
    expect_error 's/      set Function expression = y > 0 ? 0 : 1/      set Function expression = 1/' \
      "Invalid value '1' for the parameter 'diffusion/corrosion/Initial phase/Function expression': no node starts as electrolyte" $np
    expect_error 's/      set Function expression = y > 0 ? 0 : 1/      set Function expression = y > 0 ? 0 : 3/' \
      "Invalid value 'y > 0 ? 0 : 3' for the parameter 'diffusion/corrosion/Initial phase/Function expression': the initial phase must be 0 (electrolyte), 1 (metal) or 2 (passive film) at every node" $np
  done
  expect_error 's/set Saturation concentration = 4600/set Saturation concentration = 2e5/' \
    "Invalid value '2e5' for the parameter 'diffusion/corrosion/Saturation concentration': give 0 < C_sat < 'Solid concentration' (142900)"
  expect_error 's/set Current density = 5.1e3/set Current density = -1/' \
    "Invalid value '-1' for the parameter 'diffusion/corrosion/Current density': give a current density > 0"
  expect_error 's/set Current density = 5.1e3/set Interface model = interface diffusivity/' \
    "Invalid value '0' for the parameter 'diffusion/corrosion/Interface diffusivity': give K_LS > 0"
  expect_error 's/set End time = 0.1/set End time = 0.1\n  set Time stepping = implicit\n  set Time step = 1e-3/' \
    "Invalid value 'implicit' for the parameter 'diffusion/Time stepping': the model 'corrosion' runs with explicit time stepping only"
  expect_error 's/set Model = corrosion/set Model = none/' \
    "The entry 'diffusion/corrosion/Saturation concentration' (line 14) belongs to 'corrosion', but 'diffusion/Model' selects 'none'"
  expect_error 's/set End time = 0.1/set End time = 0.1\n  set Time step = 0.05/' \
    "Invalid value '0.05' for the parameter 'diffusion/Time step'"
  base_prm=base.prm

  # Mirror flux layers: explicit only, at most one horizon thick, and a face
  # carries either a value or a flux.
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Flux boundary ids = 1\n  set Flux layer values = mirror\n  set Time stepping = implicit\n  set Time step = 1e-4/' \
    "Invalid value 'mirror' for the parameter 'diffusion/Flux layer values': mirror layers need 'Time stepping = explicit'"
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Flux boundary ids = 1\n  set Flux layer values = mirror\n  set Flux layer thickness = 1.5/' \
    "Invalid value '1.5' for the parameter 'diffusion/Flux layer thickness': mirror layers reach nodes up to two layer thicknesses away" 2
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Flux boundary ids = 0, 1/' \
    "Invalid value '0, 1' for the parameter 'diffusion/Flux boundary ids': boundary id 0 is also in 'Dirichlet boundary ids'" 2
  # 1D: only the problem types registered for 1D, and 1D points.
  expect_error 's/set Dimension = 2/set Dimension = 1/; s/set Problem type = diffusion/set Problem type = explicit dynamics/' \
    "Invalid value 'explicit dynamics' for the parameter 'Problem type': 1D runs ('Dimension = 1') offer only diffusion" 2
  expect_error 's/set Dimension = 2/set Dimension = 1/' \
    "Invalid value '0, 0' for the parameter 'Geometry/Lower corner': it does not match the allowed form" 2
}

# A concentration that turns non-finite stops the run with the step and the
# node named; what was written before stays complete. The time loop.
group_time_loop() {
  for np in 1 2; do
    sed -e 's/set End time = 1e-3/set End time = 8e-3\n  set Time step = 1e-3\n  set Output every steps = 2\n  set History every steps = 2/' \
        -e 's/    set Function expression = 1/    set Function expression = t > 3e-3 ? 0\/0 : 1/' base.prm > nan.prm
    stops_during_run $np nan.prm "the non-finite run on $np processes"
    grep -qE "not finite at step [0-9]+ .* at the node at" <<<"$out" || { echo "$out" | tail -5; fail "non-finite run: no step and node named"; }
  done

  # The time loop (issue 26). A run that would need an absurd number of steps
  # is refused before it starts, with the count and the entry that set it (the
  # count was a 32-bit integer that wrapped, and the step taken was never held
  # against the bound); an output interval below the step, which looped for
  # ever, is refused; a non-finite input function is named by its entry; a
  # syntax error names the subsection. Explicit and implicit, corrosion, 1D.
  for np in 1 2; do
    expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set Time step = 1e-300/' \
      "Invalid value '1e-300' for the parameter 'diffusion/Time step': a step of 1e-300 takes 1e+297 steps" $np
    expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set Safety factor = 1e-300/' \
      "Invalid value '1e-300' for the parameter 'diffusion/Safety factor': a step of" $np
    expect_error 's/set End time = 1e-3/set End time = 1e7/' \
      "Invalid value '1e7' for the parameter 'diffusion/End time': a step of 0.00168891 (" $np
    expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set Output interval = 1e-22/' \
      "Invalid value '1e-22' for the parameter 'diffusion/Output interval': it is shorter than the time step" $np
    expect_error 's/    set Function expression = x/    set Function expression = x > 0.5 ? 0\/0 : x/' \
      "Invalid value 'x > 0.5 ? 0/0 : x' for the parameter 'diffusion/Initial concentration/Function expression': its value" $np
  done
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Time stepping = implicit\n  set Time step = 1e-300/' \
    "Invalid value '1e-300' for the parameter 'diffusion/Time step': a step of 1e-300 takes"
  expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set Output interval = 1e-300/' \
    "Invalid value '1e-300' for the parameter 'diffusion/Output interval'"
  expect_error 's/    set Function expression = x/    set Function expression = x +* 2/' \
    "Invalid value 'x +* 2' for the parameter 'diffusion/Initial concentration/Function expression': it cannot be parsed"
  expect_error 's/    set Function expression = 1/    set Function expression = 1; 2/' \
    "Invalid value '1; 2' for the parameter 'diffusion/Source/Function expression': give one expression"
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  subsection Boundary concentration\n    set Function expression = 1\/0\n  end/' \
    "Invalid value '1/0' for the parameter 'diffusion/Boundary concentration/Function expression': its value, inf, is not finite at t = 0"
  # 1D.
  expect_error 's/set Dimension = 2/set Dimension = 1/; s/set Lower corner = 0, 0/set Lower corner = 0/; s/set Upper corner = 1, 0.5/set Upper corner = 1/; s/set Subdivisions = 20, 10/set Subdivisions = 20/; s/set End time = 1e-3/set End time = 1e-3\n  set Time step = 1e-300/' \
    "Invalid value '1e-300' for the parameter 'diffusion/Time step': a step of 1e-300 takes" 2
  # Corrosion: the model's limit of the step is named by the entry that sets it.
  base_prm=corrosion.prm
  for np in 1 2; do
    expect_error 's/set Current density = 5.1e3/set Current density = 1e300/' \
      "Invalid value '1e300' for the parameter 'diffusion/corrosion/Current density'" $np
  done
  expect_error 's/set End time = 0.1/set End time = 1e7/' \
    "Invalid value '1e7' for the parameter 'diffusion/End time': a step of"
  base_prm=base.prm
}

# Values that turn bad during the run (expect_error_later) and non-finite
# data in the linear solves (expect_stop).
group_later() {
  for np in 1 2; do
    # Values that become non-finite at t > 3e-3: the entry and the time, not
    # the time step.
    expect_error_later 's/set End time = 1e-3/set End time = 8e-3\n  set Time step = 1e-3\n  set Output every steps = 2/; s/    set Function expression = 1/    set Function expression = t > 3e-3 ? 0\/0 : 1/' \
      "Invalid value 't > 3e-3 ? 0/0 : 1' for the parameter 'diffusion/Source/Function expression': its value" $np
    expect_error_later 's/set End time = 1e-3/set End time = 8e-3\n  set Time step = 1e-3\n  set Output every steps = 2/; s/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  subsection Boundary concentration\n    set Function expression = t > 3.5e-3 ? 1\/0 : 0\n  end/' \
      "Invalid value 't > 3.5e-3 ? 1/0 : 0' for the parameter 'diffusion/Boundary concentration/Function expression': its value, inf, is not finite at step 4 (evaluated at t = 0.004)" $np
  done
  # Non-finite data in the linear solves of implicit and steady runs: named
  # with its entry and value. deal.II's CG "converged" on a NaN right-hand side
  # in 0 iterations, left the field as it was and the run exited with 0.
  implicit='set End time = 1e-3\n  set Time stepping = implicit\n  set Time step = 2.5e-4'
  for np in 1 2; do
    expect_stop "s/set End time = 1e-3/$implicit/; s/    set Function expression = 1/    set Function expression = x > 0.5 ? sqrt(-1) : 1/" \
      "Invalid value 'x > 0.5 ? sqrt(-1) : 1' for the parameter 'diffusion/Source/Function expression': it is NaN at the node at" $np
    expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Time stepping = steady state/; /set End time = 1e-3/d; s/    set Function expression = 1/    set Function expression = x > 0.5 ? sqrt(-1) : 1/' \
      "Invalid value 'x > 0.5 ? sqrt(-1) : 1' for the parameter 'diffusion/Source/Function expression'" $np
  done
  expect_stop "s/set End time = 1e-3/$implicit\n  set Implicit scheme = Crank-Nicolson\n  set Flux boundary ids = 1\n  subsection Boundary flux\n    set Function expression = y > 0.25 ? 1\/0 : 0\n  end/" \
    "Invalid value 'y > 0.25 ? 1/0 : 0' for the parameter 'diffusion/Boundary flux/Function expression'" 2
  expect_stop "s/set End time = 1e-3/$implicit\n  subsection Boundary concentration\n    set Function expression = y > 0.25 ? sqrt(-1) : 0\n  end/" \
    "Invalid value 'y > 0.25 ? sqrt(-1) : 0' for the parameter 'diffusion/Boundary concentration/Function expression'" 1
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Time stepping = steady state/; /set End time = 1e-3/d; s/    set Function expression = x/    set Function expression = sqrt(x - 0.5)/' \
    "Invalid value 'sqrt(x - 0.5)' for the parameter 'diffusion/Initial concentration/Function expression'" 2
  # A solve that needs no iteration (zero data) reports 0 iterations, not
  # 4294967295 (an unsigned -1).
  sed -e 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Time stepping = steady state/' -e '/set End time = 1e-3/d' \
      -e 's/    set Function expression = 1/    set Function expression = 0/' base.prm > zero.prm
  rm -rf out
  expect_valid 1 zero.prm "the zero steady state"
  grep -q "4294967295" <<<"$out" && fail "a solve without iterations logs 4294967295 iterations"
  grep -qF ", 0 iterations" <<<"$out" || fail "the zero steady state does not report 0 iterations"
  [ "$(awk -F, 'NR == 2 { print $6 }' out/history.csv)" = "0" ] || fail "history.csv: iterations of the zero steady state are not 0"

  # A diffusivity that overflows with the horizon is named as the cause (it
  # was "the operator has no bonds?").
  for np in 1 2; do
    expect_error 's/set Diffusivity = 1/set Diffusivity = 1e308/' \
      "Invalid value '1e308' for the parameter 'diffusion/Diffusivity': with the horizon" $np
  done
  expect_error 's/set Diffusivity = 1/set Diffusivity = 1e308/; s/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Time stepping = steady state/; /set End time = 1e-3/d' \
    "Invalid value '1e308' for the parameter 'diffusion/Diffusivity'"
}

# Entries that would be ignored or do nothing: each an error naming the
# entry and its value (issue 26, class 9), checked before any output.
group_no_effect() {
  ed='s/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0'
  for np in 1 2; do
    expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  set Dirichlet boundary ids = 1\nend/' \
      "Invalid value '1' for the parameter 'Boundary conditions/Dirichlet boundary ids': this entry has no effect here: the diffusion problem takes its boundary values" $np
    expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Material model\n  set Model = bond-based\nend/' \
      "Invalid value 'bond-based' for the parameter 'Material model/Model': this entry has no effect here: the problem type 'diffusion' uses no elastic material model" $np
    # Every node prescribed: nothing left to compute.
    expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0, 1, 2, 3\n  set Dirichlet layer thickness = 2/' \
      "Invalid value '2' for the parameter 'diffusion/Dirichlet layer thickness': every node lies in a Dirichlet layer" $np
  done
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Analytical solution\n  set Compare with analytical solution = true\nend/' \
    "Invalid value 'true' for the parameter 'Analytical solution/Compare with analytical solution': this entry has no effect here"
  expect_error "$ed"'\n  set Implicit scheme = Crank-Nicolson/' \
    "Invalid value 'Crank-Nicolson' for the parameter 'diffusion/Implicit scheme': this entry has no effect here: 'Time stepping = explicit' uses no implicit scheme"
  expect_error "$ed"'\n  set Solver tolerance = 1e-6/' \
    "Invalid value '1e-6' for the parameter 'diffusion/Solver tolerance': this entry has no effect here: 'Time stepping = explicit' solves no linear system"
  expect_error "$ed"'\n  set Time stepping = steady state\n  set End time = 2/; s/set End time = 1e-3//' \
    "Invalid value '2' for the parameter 'diffusion/End time': this entry has no effect here: 'Time stepping = steady state' takes no time steps"
  expect_error "$ed"'\n  set Time step = 1e-5\n  set Safety factor = 0.5/' \
    "Invalid value '0.5' for the parameter 'diffusion/Safety factor': this entry has no effect here: 'Time step' is given"
  expect_error "$ed"'\n  set Allow unstable time step = true/' \
    "Invalid value 'true' for the parameter 'diffusion/Allow unstable time step': this entry has no effect here"
  expect_error "$ed"'\n  subsection Boundary flux\n    set Function expression = 2\n  end/' \
    "Invalid value '2' for the parameter 'diffusion/Boundary flux/Function expression': this entry has no effect here: no 'Flux boundary ids' are given"
  expect_error "$ed"'\n  set Flux layer thickness = 2/' \
    "Invalid value '2' for the parameter 'diffusion/Flux layer thickness': this entry has no effect here"
  expect_error "$ed"'\n  subsection Analytical concentration\n    set Function expression = x\n  end/' \
    "Invalid value 'x' for the parameter 'diffusion/Analytical concentration/Function expression': this entry has no effect here: 'diffusion/Compare with analytical solution' is false"
  base_prm=corrosion.prm
  for np in 1 2; do
    expect_error 's/set Dirichlet boundary ids = 3/set Dirichlet boundary ids = 3\n  subsection Initial concentration\n    set Function expression = 100\n  end/' \
      "Invalid value '100' for the parameter 'diffusion/Initial concentration/Function expression': this entry has no effect here: with 'Model = corrosion' the initial concentration follows from 'corrosion/Initial phase'" $np
  done
  expect_error 's/set Current density = 5.1e3/set Current density = 5.1e3\n    set Interface diffusivity = 1e-9/' \
    "Invalid value '1e-9' for the parameter 'diffusion/corrosion/Interface diffusivity': this entry has no effect here: 'Interface model = dissolution rate'"
  expect_error 's/set Current density = 5.1e3/set Current density = 5.1e3\n    set Damage seed = 7/' \
    "Invalid value '7' for the parameter 'diffusion/corrosion/Damage seed': this entry has no effect here: 'Mechanical damage' is false"
  base_prm=base.prm
}

run_case_group "$group"
finish "all bad inputs rejected with clear messages"
