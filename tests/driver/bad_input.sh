#!/usr/bin/env bash
# Usage: bad_input.sh PERIDEAL TEST_SOURCE_DIR [GROUP]
#
# Bad input to the perideal driver: each case must exit non-zero, print a
# message that names the offending parameter (and its value), and leave no
# output behind.
# GROUP: the group of cases to run (a function group_<name> below; each is
# a ctest of its own), or all of them (the default, 'all').
set -u
perideal="$1"; source_dir="$2"; group="${3:-all}"
. "$(cd "$(dirname "$0")" && pwd)/../bad_input_checks.sh"
left_behind=out
enter_work "bad_input.$group"

# A valid small 2D problem; each case edits one line of it.
cat > base.prm <<'PRM'
set Dimension = 2
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Subdivisions = 10, 10
end
subsection Horizon
  set m-ratio = 3
end
subsection Material model
  set Model = linear peridynamic solid
  subsection linear peridynamic solid
    set Poisson's ratio = 0.25
  end
end
subsection Boundary conditions
  set Dirichlet boundary ids = 0, 1, 2, 3
  subsection Dirichlet displacement
    set Variable names      = x,y
    set Function expression = 1e-3*x; 0
  end
end
subsection Output
  set Directory = out
end
PRM

# The valid input runs, on 1 and 2 processes; entries, mesh files.
group_entries() {
  expect_valid 1 base.prm "the valid base input" out/solution_0.pvtu
  # Output is renamed into place: a 1-process run after a 2-process run leaves
  # one piece (no stale second piece), and no temporary file remains.
  expect_valid 2 base.prm "the valid base input on 2 processes"
  [ "$(ls out/*.vtu | wc -l)" -eq 2 ] || fail "2 processes did not write 2 pieces"
  expect_valid 1 base.prm "the valid base input, run again,"
  [ "$(ls out/*.vtu | wc -l)" -eq 1 ] || fail "a stale piece of the 2-process run remains: $(ls out)"
  grep -q "solution_0.1.vtu" out/solution_0.pvtu && fail "the record names a stale piece"
  ls out/*.tmp > /dev/null 2>&1 && fail "temporary files remain: $(ls out)"
  rm -rf out

  expect_error 's/set m-ratio = 3/set m-ratio = 0/' \
    "Invalid value '0' for the parameter 'Horizon/m-ratio'"
  expect_error 's/set m-ratio = 3/set m-ratio = -2/' \
    "Invalid value '-2' for the parameter 'Horizon/m-ratio'" 2
  expect_error 's/set m-ratio = 3/set m-ratio = 12/' \
    "Invalid value '12' for the parameter 'Horizon/m-ratio': the horizon 1.2 is not smaller than the smallest extent of the body, 1"
  expect_error 's/set m-ratio = 3/set m-ration = 3/' \
    "The entry 'Horizon/m-ration' = '3' (line 8 of 'case.prm') is not declared"
  expect_error 's/set Subdivisions = 10, 10/set Subdivisions = 10, 10, 10/' \
    "Invalid value '10, 10, 10' for the parameter 'Geometry/Subdivisions': it does not match the allowed form"
  expect_error "s/set Poisson's ratio = 0.25/set Poisson's ratio = 0.5/" \
    "Invalid value '0.5' for the parameter 'Material model/linear peridynamic solid/Poisson's ratio'"
  expect_error "s/set Poisson's ratio = 0.25/set Poisson's ratio = -1.5/" \
    "Invalid value '-1.5' for the parameter 'Material model/linear peridynamic solid/Poisson's ratio'" 2
  expect_error 's/set Model = linear peridynamic solid/set Model = linear peridynamic solidd/' \
    "Invalid value 'linear peridynamic solidd' for the parameter 'Material model/Model': it does not match the allowed form"
  expect_error "s/set Model = linear peridynamic solid/set Model = bond-based/; s/subsection linear peridynamic solid/subsection bond-based/; s/set Poisson's ratio = 0.25/set Poisson's ratio = 0.3/" \
    "Invalid value '0.3' for the parameter 'Material model/bond-based/Poisson's ratio'"
  expect_error 's/set Dirichlet boundary ids = 0, 1, 2, 3/set Dirichlet boundary ids = 0, 7/' \
    "Invalid value '0, 7' for the parameter 'Boundary conditions/Dirichlet boundary ids': boundary id 7 does not occur in the mesh"
  expect_error 's/set Function expression = 1e-3\*x; 0/set Function expression = 1e-3*x/' \
    "Invalid value '1e-3*x' for the parameter 'Boundary conditions/Dirichlet displacement/Function expression': give 2 expressions"
  expect_error 's/set Lower corner = 0, 0/set Lower corner = 0, 0\n  set Mesh = file\n  set Mesh file = no-such-mesh.msh/' \
    "Invalid value 'no-such-mesh.msh' for the parameter 'Geometry/Mesh file'"
  unnamed="source/discretization/node_set.cc (cell_box) names neither 'Geometry/Mesh file' nor the file" \
  expect_error "s|set Lower corner = 0, 0|set Mesh = file\n  set Mesh file = $source_dir/skewed_quad.inp|" \
    "Use a Cartesian mesh"
  expect_error 's/set Dimension = 2/set Dimension = 4/' "Invalid value '4' for the parameter 'Dimension': it does not match the allowed form"
  # Mesh files that GridIn cannot read: the message names the file, the entry
  # and the dimension (a 2D mesh read as 3D used to say "No vertices given").
  printf 'this is not a mesh\n' > garbage.msh
  expect_error 's|set Lower corner = 0, 0|set Mesh = file\n  set Mesh file = garbage.msh|' \
    "Invalid value 'garbage.msh' for the parameter 'Geometry/Mesh file': reading it as a 2D mesh failed"
  expect_error "s/set Dimension = 2/set Dimension = 3/; s|set Lower corner = 0, 0|set Mesh = file\n  set Mesh file = $source_dir/l_shape.inp|; s/set Variable names      = x,y/set Variable names      = x,y,z/; s/set Function expression = 1e-3\\*x; 0/set Function expression = 1e-3*x; 0; 0/; s/set Upper corner = 1, 1/set Upper corner = 1, 1, 1/; s/set Subdivisions = 10, 10/set Subdivisions = 10, 10, 10/" \
    "Invalid value '$source_dir/l_shape.inp' for the parameter 'Geometry/Mesh file': reading it as a 3D mesh failed" 2
}

# Paths and checks that fail on one process only; the direct solver's
# memory; boundary treatments and conditions.
group_paths_and_boundaries() {
  # Checks that fail on one process only (a non-box cell it owns, an output
  # path only some process writes) must stop every process with the message.
  unnamed="source/discretization/node_set.cc (cell_box) names neither 'Geometry/Mesh file' nor the file" \
  expect_error "s|set Lower corner = 0, 0|set Mesh = file\n  set Mesh file = $source_dir/skewed_quad.inp|" \
    "Use a Cartesian mesh" 2
  touch not_a_directory
  expect_error 's|set Directory = out|set Directory = not_a_directory/out|' \
    "Invalid value 'not_a_directory/out' for the parameter 'Output/Directory'" 2
  expect_error 's|set Directory = out|set Directory = out\n  set Node data file = not_a_directory/nodes.csv|' \
    "Invalid value 'not_a_directory/nodes.csv' for the parameter 'Output/Node data file'" 2
  # A node data file holds the errors: without a comparison it is refused.
  expect_error 's|set Directory = out|set Directory = out\n  set Node data file = nodes.csv|' \
    "Invalid value 'nodes.csv' for the parameter 'Output/Node data file'"
  expect_error 's|set Directory = out|set Directory = out\n  set Summary file = not_a_directory/summary.csv|' \
    "Invalid value 'not_a_directory/summary.csv' for the parameter 'Output/Summary file'" 2
  # The direct solver's factors checked against the memory available before
  # MUMPS allocates them (capped here at 1 kB per process).
  export PERIDEAL_MEMORY_LIMIT_MB=0.001
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Method = direct\nend/; s/set Subdivisions = 10, 10/set Subdivisions = 40, 40/' \
    "Invalid value 'direct' for the parameter 'Linear solver/Method': the direct solver (MUMPS) would need an estimated" 2
  unset PERIDEAL_MEMORY_LIMIT_MB
  # A summary file with other columns is not appended to (its rows would be
  # misread); it is left as it was.
  printf 'a,b\n1,2\n' > foreign.csv
  expect_error 's|set Directory = out|set Directory = out\n  set Summary file = foreign.csv|' \
    "Invalid value 'foreign.csv' for the parameter 'Output/Summary file': the file exists with other columns" 2
  [ "$(cat foreign.csv)" = "$(printf 'a,b\n1,2')" ] || fail "the foreign summary file was changed"
  # Boundary treatments: a fictitious layer alone with free faces is singular;
  # surface nodes need equal square cells; the Taylor order is 1..3.
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = fictitious layer\nend/; s/set Dirichlet boundary ids = 0, 1, 2, 3/set Dirichlet boundary ids = 0/' \
    "Invalid value 'fictitious layer' for the parameter 'Boundary treatment/Treatment'"
  unnamed="source/operators/fictitious_layer_operator.cc names 'Boundary treatment/Treatment' only in the fix, without its value 'surface nodes'" \
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = surface nodes\nend/; s/set Subdivisions = 10, 10/set Subdivisions = 10, 8/' \
    "need a uniform grid of equal cubes" 2
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = surface nodes\n  subsection surface nodes\n    set Taylor order = 4\n  end\nend/' \
    "Invalid value '4' for the parameter 'Boundary treatment/surface nodes/Taylor order': it does not match the allowed form"
  # Wrong answers that used to exit with 0: non-finite boundary values or
  # loads, a singular system "solved" by the direct solver, a Dirichlet layer
  # that holds no node, a horizon that reaches no neighbour.
  expect_error 's/set Function expression = 1e-3\*x; 0/set Function expression = 1e-3\/(x - x); 0/' \
    "Invalid value '1e-3/(x - x); 0' for the parameter 'Boundary conditions/Dirichlet displacement/Function expression'" 2
  unnamed="source/boundary/boundary_conditions.cc names two entries ('Body force' or 'Traction') and no value" \
  expect_error 's/  subsection Dirichlet displacement/  subsection Body force\n    set Function expression = sqrt(-1); 0\n  end\n  subsection Dirichlet displacement/' \
    "Boundary conditions/Body force" 2
  expect_error 's/set Dirichlet boundary ids = 0, 1, 2, 3/set Dirichlet boundary ids = 0\n  set Dirichlet components = x/' \
    "Invalid value '0' for the parameter 'Boundary conditions/Dirichlet boundary ids': the Dirichlet layers leave a rigid motion free (translation in y)"
  expect_error 's/set Dirichlet boundary ids = 0, 1, 2, 3/set Dirichlet boundary ids =/; /set Function expression = 1e-3\*x; 0/d; /set Variable names      = x,y/d' \
    "Invalid value '' for the parameter 'Boundary conditions/Dirichlet boundary ids': the Dirichlet layers leave a rigid motion free (translation in x, translation in y, rotation in the x-y plane)" 2
  expect_error 's/set Dirichlet boundary ids = 0, 1, 2, 3/set Dirichlet boundary ids = 0, 1, 2, 3\n  set Dirichlet layer thickness = 0.1/' \
    "Invalid value '0.1' for the parameter 'Boundary conditions/Dirichlet layer thickness': the Dirichlet layer of boundary id 0 (0.03" 2
  expect_error 's/set m-ratio = 3/set m-ratio = 0.4/' \
    "Invalid value '0.4' for the parameter 'Horizon/m-ratio': the horizon 0.04 reaches no neighbour"
}

# Solvers; command-line arguments; entries set twice or in vain; a size
# guard.
group_solvers() {
  # The matrix-free operator: no direct solver and no preconditioner that
  # needs the PD matrix; its own preconditioners need 'matrix-free'; a zero
  # tolerance is unreachable; layer treatments are assembled-only so far.
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\nend/' \
    "Invalid value 'direct' for the parameter 'Linear solver/Method'"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = CG\n  set Preconditioner = ILU\nend/' \
    "Invalid value 'ILU' for the parameter 'Linear solver/Preconditioner'"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Method = CG\n  set Preconditioner = local elasticity\nend/' \
    "Invalid value 'local elasticity' for the parameter 'Linear solver/Preconditioner': 'local elasticity' is a preconditioner of the matrix-free operator: set 'Linear solver/Operator = matrix-free'" 2
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Method = CG\n  set Relative tolerance = 0\nend/' \
    "Invalid value '0' for the parameter 'Linear solver/Relative tolerance'"
  # The layer treatments without a product matrix: non-symmetric, so CG is
  # refused; no diagonal is formed, so Jacobi is refused.
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = CG\n  set Preconditioner = Jacobi\nend\nsubsection Boundary treatment\n  set Treatment = surface nodes\nend/' \
    "Invalid value 'CG' for the parameter 'Linear solver/Method'"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = GMRES\n  set Preconditioner = Jacobi\nend\nsubsection Boundary treatment\n  set Treatment = surface nodes\nend/' \
    "Invalid value 'Jacobi' for the parameter 'Linear solver/Preconditioner'" 2
  # The Jacobi term of 'local elasticity' needs the operator's diagonal,
  # which the layer operators do not form.
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = GMRES\n  set Preconditioner = local elasticity\n  subsection local elasticity\n    set PD Jacobi weight = 0.5\n  end\nend\nsubsection Boundary treatment\n  set Treatment = surface nodes\nend/' \
    "Invalid value '0.5' for the parameter 'Linear solver/local elasticity/PD Jacobi weight': the operator of this boundary treatment has no diagonal" 2
  # 'local elasticity/Coarsening = 2' needs the matrix-free operator of
  # boundary treatment 'none' and a Jacobi term.
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = GMRES\n  set Preconditioner = local elasticity\n  subsection local elasticity\n    set Coarsening = 2\n  end\nend\nsubsection Boundary treatment\n  set Treatment = surface nodes\nend/' \
    "Invalid value '2' for the parameter 'Linear solver/local elasticity/Coarsening': a coarser local grid works only with the matrix-free operator of boundary treatment 'none'" 2
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = CG\n  set Preconditioner = local elasticity\n  subsection local elasticity\n    set Coarsening = 2\n    set PD Jacobi weight = 0\n  end\nend/' \
    "Invalid value '0' for the parameter 'Linear solver/local elasticity/PD Jacobi weight': with 'Coarsening = 2' the Jacobi term"
  unnamed="not an input error: a solve that did not converge (it names 'Linear solver/Relative tolerance' and its value unquoted)" \
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = CG\n  set Preconditioner = Jacobi\n  set Maximum iterations = 3\nend/' \
    "did not converge: after 3 iterations" 2
  run_perideal 1 --threads 0 base.prm; check_clean_exit "$rc" "$out" "--threads 0"
  grep -qF -- "--threads takes a positive integer, not '0'" <<<"$out" || fail "--threads 0: $out"

  # Settings that used to be ignored silently: an entry set twice, entries of
  # a model that is not selected, 'Plane model' in 3D, a file that sets
  # nothing.
  expect_error 's/set m-ratio = 3/set m-ratio = 3\n  set m-ratio = 4/' \
    "The entry 'Horizon/m-ratio' is set twice in 'case.prm' (line 8: '3', line 9: '4')"
  expect_error "s/  subsection linear peridynamic solid/  subsection bond-based\n    set Young's modulus = 2\n  end\n  subsection linear peridynamic solid/" \
    "The entry 'Material model/bond-based/Young's modulus' (line 13) belongs to 'bond-based', but 'Material model/Model' selects 'linear peridynamic solid'"
  unnamed="source/problems/simulator.cc does not quote the value 'plane stress'" \
  expect_error "s/set Dimension = 2/set Dimension = 3/; s/set Lower corner = 0, 0/set Lower corner = 0, 0, 0/; s/set Upper corner = 1, 1/set Upper corner = 1, 1, 1/; s/set Subdivisions = 10, 10/set Subdivisions = 8, 8, 8/; s/set Variable names      = x,y/set Variable names      = x,y,z/; s/set Function expression = 1e-3\*x; 0/set Function expression = 1e-3*x; 0; 0/; s/    set Poisson's ratio = 0.25/    set Poisson's ratio = 0.25\n    set Plane model = plane stress/" \
    "applies to 2D only, and this run is 3D"
  : > empty.prm
  run_perideal 1 empty.prm; check_clean_exit "$rc" "$out" "an empty .prm"
  grep -qF "sets no entry" <<<"$out" || fail "empty .prm: $out"

  # A size guard: a box far beyond the machine's memory is refused with the
  # estimate before anything is allocated.
  expect_error 's/set Subdivisions = 10, 10/set Subdivisions = 100000000, 100000000/' \
    "Invalid value '100000000, 100000000' for the parameter 'Geometry/Subdivisions': with 'Global refinements = 0' this is 1e+16 nodes, which need an estimated"

  # No parameter file, an unreadable one, unknown options.
  run_perideal 1; check_clean_exit "$rc" "$out" "no argument"
  grep -qF "Usage: perideal" <<<"$out" || fail "no usage without arguments"
  run_perideal 1 no-such-file.prm; check_clean_exit "$rc" "$out" "a missing .prm"
  grep -qF "Cannot read the parameter file 'no-such-file.prm'" <<<"$out" || fail "missing .prm: $out"
  run_perideal 1 --frobnicate; check_clean_exit "$rc" "$out" "an unknown option"
  run_perideal 1 --print-parameters 2; [ "$rc" -eq 0 ] || fail "--print-parameters failed"
  # The listing runs as it is, in its own dimension.
  grep -qE "^set Dimension +=  *2( |$)" <<<"$out" || fail "--print-parameters 2 does not say 'set Dimension = 2'"
  for entry in "set Dimension" "subsection Horizon" "set m-ratio" "subsection linear peridynamic solid" \
               "set Dirichlet layer thickness" "set Preconditioner" "set Summary file" "set Operator" \
               "subsection Boundary treatment" "set Taylor order" "set Traction given as"; do
    grep -qF "$entry" <<<"$out" || fail "--print-parameters lacks '$entry'"
  done
}

# The collocation quadrature ('Quadrature'): orders and node counts the
# dimension does not offer, and models, solvers, treatments and problem types
# it does not support (yet).
group_collocation() {
  bb="s/set Model = linear peridynamic solid/set Model = bond-based/; s/subsection linear peridynamic solid/subsection bond-based/"
  gmres='\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = GMRES\n  set Preconditioner = Jacobi\nend'
  col() { printf 's/set Dimension = 2/set Dimension = 2\\nsubsection Quadrature\\n  set Scheme = collocation\\n%s\\nend%s/' "$1" "$2"; }
  sed "$bb; $(col '' "$gmres")" base.prm > collocation.prm
  expect_valid 1 collocation.prm "collocation, bond-based, GMRES" out/solution_0.pvtu
  rm -rf out
  expect_error "$bb; $(col '  subsection collocation\n    set Order = 6\n  end' "$gmres")" \
    "Invalid value '6' for the parameter 'Quadrature/collocation/Order': the collocation scheme offers the orders 2 and 4 in 2D"
  expect_error "$bb; $(col '  subsection collocation\n    set Order = 3\n  end' "$gmres")" \
    "Invalid value '3' for the parameter 'Quadrature/collocation/Order'"
  expect_error "$bb; $(col '  subsection collocation\n    set Collocation nodes = 4\n  end' "$gmres")" \
    "Invalid value '4' for the parameter 'Quadrature/collocation/Collocation nodes': a fit of order 2 in 2D has 6 monomials and needs at least that many collocation nodes; give at least 6"
  # 15 nodes pass the count of monomials of order 4 (15), but the closest
  # auxiliary grid has 13 points.
  expect_error "$bb; $(col '  subsection collocation\n    set Order = 4\n    set Collocation nodes = 15\n  end' "$gmres")" \
    "Invalid value '15' for the parameter 'Quadrature/collocation/Collocation nodes': the auxiliary grid for it gives 13 collocation nodes" 2
  # The paper's order-4 row at m = 3 weighs its own node against its
  # neighbours (doc/collocation.md Sect. 7): an indefinite static operator;
  # the stabilised one (the default, Sect. 7.1) runs.
  expect_error "$bb; $(col '  subsection collocation\n    set Order = 4\n    set Stabilisation = none\n  end' "$gmres")" \
    "Invalid value '4' for the parameter 'Quadrature/collocation/Order': the bulk collocation row of this order at this m-ratio has a non-positive diagonal (its own node weighs against its neighbours), and its Fourier symbol has growing modes"
  sed "$bb; $(col '  subsection collocation\n    set Order = 4\n  end' "$gmres")" base.prm > collocation_c4.prm
  expect_valid 1 collocation_c4.prm "collocation, bond-based, stabilised order 4, GMRES" out/solution_0.pvtu
  rm -rf out
  # LPS collocation rows run (matrix-free GMRES here).
  sed "$(col '' "$gmres")" base.prm > collocation_lps.prm
  expect_valid 1 collocation_lps.prm "collocation, LPS, GMRES" out/solution_0.pvtu
  rm -rf out
  # The order-2 lattice row stabilised too ('Stabilisation = all orders',
  # doc/collocation.md Sect. 7.3): bond-based runs; the LPS rows are not
  # stabilised, so there the entry would have no effect.
  sed "$bb; $(col '  subsection collocation\n    set Stabilisation = all orders\n  end' "$gmres")" base.prm > collocation_all_orders.prm
  expect_valid 1 collocation_all_orders.prm "collocation, bond-based, stabilised order 2, GMRES" out/solution_0.pvtu
  rm -rf out
  # 'none' without effect: the order-2 lattice row and the LPS rows are
  # the paper's under 'automatic' too.
  expect_error "$bb; $(col '  subsection collocation\n    set Stabilisation = none\n  end' "$gmres")" \
    "Invalid value 'none' for the parameter 'Quadrature/collocation/Stabilisation': on a uniform grid 'automatic' leaves the order-2 row as the paper gives it"
  expect_error "$(col '  subsection collocation\n    set Stabilisation = none\n  end' "$gmres")" \
    "Invalid value 'none' for the parameter 'Quadrature/collocation/Stabilisation': the state-based (LPS) rows are not stabilised yet, so the entry has no effect"
  expect_error "$(col '  subsection collocation\n    set Stabilisation = all orders\n  end' "$gmres")" \
    "Invalid value 'all orders' for the parameter 'Quadrature/collocation/Stabilisation': the state-based (LPS) rows are not stabilised yet, so the entry would have no effect; use 'automatic'"
  expect_error "$bb; $(col '' '\nsubsection Linear solver\n  set Method = CG\nend')" \
    "Invalid value 'CG' for the parameter 'Linear solver/Method': the quadrature scheme 'collocation' gives a non-symmetric system"
  expect_error "$bb; $(col '' '\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = CG\n  set Preconditioner = Jacobi\nend')" \
    "Invalid value 'CG' for the parameter 'Linear solver/Method': the quadrature scheme 'collocation' gives a non-symmetric system"
  expect_error "$bb; $(col '' '\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = GMRES\n  set Preconditioner = none\nend\nsubsection Boundary treatment\n  set Treatment = fictitious layer\nend')" \
    "Invalid value 'collocation' for the parameter 'Quadrature/Scheme': the collocation rows are built for the body's own nodes"
  expect_error "$bb; $(col '' '\nset Problem type = explicit dynamics')" \
    "Invalid value 'collocation' for the parameter 'Quadrature/Scheme': the problem type 'explicit dynamics' does not support this quadrature scheme yet ('collocation': quasi-static and diffusion; 'hybrid': explicit dynamics, diffusion, and quasi-static with a fixed standard region); use 'Scheme = standard', or 'hybrid'"
  # A static solve breaks no bonds: the adaptive switch would never fire.
  expect_error "$bb; $(col '' "$gmres"); s/set Scheme = collocation/set Scheme = hybrid/" \
    "Invalid value 'adaptive' for the parameter 'Quadrature/hybrid/Configuration': a quasi-static solve breaks no bonds, so no node would ever switch"
  # A fixed standard box that holds no node.
  expect_error "$bb; $(col '  subsection hybrid\n    set Configuration = fixed\n    set Standard boxes = 5, 5, 6, 6\n  end' "$gmres"); s/set Scheme = collocation/set Scheme = hybrid/" \
    "Invalid value '5, 5, 6, 6' for the parameter 'Quadrature/hybrid/Standard boxes'"
  expect_error "$bb; s/set Dimension = 2/set Dimension = 2\nsubsection Quadrature\n  subsection collocation\n    set Order = 4\n  end\nend/" \
    "The entry 'Quadrature/collocation/Order' (line 4) belongs to 'collocation', but 'Quadrature/Scheme' selects 'standard'"
  # Irregular nodes ('Geometry/Node perturbation'): a fraction outside
  # [0, 0.5), a seed without a perturbation, and the schemes and models
  # that need the nodes at the cell centres so far.
  perturb() { printf 's/  set Subdivisions = 10, 10/  set Subdivisions = 10, 10\\n%s/' "$1"; }
  expect_error "$(perturb '  set Node perturbation = 0.5')" \
    "Invalid value '0.5' for the parameter 'Geometry/Node perturbation': the offset of a node from its cell's centre, as a fraction of the cell's side, lies in [0, 0.5)"
  expect_error "$(perturb '  set Node perturbation = -0.1')" \
    "Invalid value '-0.1' for the parameter 'Geometry/Node perturbation'"
  expect_error "$(perturb '  set Random seed = 3')" \
    "Invalid value '3' for the parameter 'Geometry/Random seed': this entry has no effect here: it seeds 'Geometry/Node perturbation', which is 0"
  expect_error "$(perturb '  set Node perturbation = 0.3'); $(col '' "$gmres")" \
    "Invalid value '0.3' for the parameter 'Geometry/Node perturbation': the collocation rows of the state-based model are built for nodes at the cell centres so far"
  sed "$bb; $(perturb '  set Node perturbation = 0.3'); $(col '' "$gmres")" base.prm > perturbed.prm
  expect_valid 1 perturbed.prm "collocation, bond-based, perturbed nodes" out/solution_0.pvtu
  rm -rf out
  # A heavily perturbed cloud (0.49 h) whose order-2 row, as the paper
  # gives it ('Stabilisation = none'; the stabilised rows of
  # doc/collocation.md Sect. 7.2 have none there), has a non-positive
  # diagonal: with 'fall back' its node is standard and counted, and the run
  # completes; with 'error' the run stops naming the entry, the same count
  # and the node. (Property checks: the count in both modes agrees and is not
  # zero; the field is then no longer exact at round-off. Seed 3: one such
  # cloud.)
  heavy="s/set Random seed = 7/set Random seed = 3/; s/set Node perturbation = 0.35/set Node perturbation = 0.49/; s/set Write VTU = false/set Write VTU = true/; s/    set Order = 2/    set Order = 2\n    set Stabilisation = none/"
  sed "$heavy; s|  set Directory *=.*||; s|^subsection Output|subsection Output\n  set Directory = out|" \
    "$source_dir/collocation_2d_quadratic_perturbed.prm" > heavy.prm
  expect_valid 1 heavy.prm "collocation on 0.49 h perturbed nodes, fall back" out/solution_0.pvtu
  fell_back=$(sed -n 's/.* \([0-9][0-9]*\) standard (ill-conditioned or indefinite cloud).*/\1/p' <<<"$out")
  [ -n "$fell_back" ] && [ "$fell_back" -gt 0 ] ||
    fail "no node fell back on 0.49 h perturbed nodes: $(grep quadrature <<<"$out")"
  rm -rf out
  base_prm=heavy.prm
  expect_error "s/    set Order = 2/    set Order = 2\n    set Ill-conditioned clouds = error/" \
    "Invalid value 'error' for the parameter 'Quadrature/collocation/Ill-conditioned clouds': $fell_back nodes have a collocation cloud with cond(A) > 1e12 or a row with a non-positive diagonal (one at (" 2
  # A stabilised order-4 row with a non-positive diagonal (seed 35: one
  # node of the 30^2 grid at 0.35 h; cond(A) up to 7e4, so a badly shaped cloud,
  # not an ill-conditioned one): with 'fall back' the node takes an order-2
  # row (fit_node_rows_with_fallback()), counted; the field is quadratic,
  # which both orders reproduce, so the error stays at round-off (with the
  # node standard, as before, it did not: a reference by exactness, not a
  # snapshot). With 'error' the run stops; the paper's order-4 rows
  # ('Stabilisation = none') have such rows at hundreds of nodes, the
  # order's fault, and stop.
  c4bad="s/set Random seed = 7/set Random seed = 35/; s/set Write VTU = false/set Write VTU = true/; s/    set Order = 2/    set Order = 4/"
  sed "$c4bad; s|  set Directory *=.*||; s|^subsection Output|subsection Output\n  set Directory = out|" \
    "$source_dir/collocation_2d_quadratic_perturbed.prm" > c4bad.prm
  expect_valid 1 c4bad.prm "stabilised C4 on perturbed nodes, one bad cloud, fall back" out/solution_0.pvtu
  grep -qF "nodes by collocation (1 of them by order 2: bad order-4 cloud)" <<<"$out" &&
    grep -qF " 0 standard (ill-conditioned or indefinite cloud)" <<<"$out" ||
    fail "the bad C4 cloud did not take an order-2 row: $(grep quadrature <<<"$out")"
  c4bad_error=$(sed -n 's/.*error against the analytical solution: relative L2 \([0-9.e+-]*\),.*/\1/p' <<<"$out")
  awk -v e="$c4bad_error" 'BEGIN { exit !(e != "" && e + 0 < 1e-9) }' ||
    fail "the quadratic field is not exact with the order-2 row of the bad C4 cloud (relative L2 error '$c4bad_error')"
  rm -rf out
  base_prm=c4bad.prm
  expect_error "s/    set Order = 4/    set Order = 4\n    set Ill-conditioned clouds = error/" \
    "Invalid value 'error' for the parameter 'Quadrature/collocation/Ill-conditioned clouds': 1 nodes have a collocation cloud with cond(A) > 1e12 or a row with a non-positive diagonal (one at (" 2
  expect_error "s/    set Order = 4/    set Order = 4\n    set Stabilisation = none/" \
    "Invalid value '4' for the parameter 'Quadrature/collocation/Order':" 2
  base_prm=base.prm
  sed "$(perturb '  set Node perturbation = 0.3')" base.prm > perturbed_standard.prm
  expect_valid 1 perturbed_standard.prm "standard LPS, perturbed nodes" out/solution_0.pvtu
  rm -rf out
}

# Overflowing moduli, output names that meet, entries that do nothing.
group_no_effect() {
  # A modulus whose bond stiffness overflows with the horizon is named as the
  # cause, not the solve it spoils.
  expect_error "s/    set Poisson's ratio = 0.25/    set Poisson's ratio = 0.25\n    set Young's modulus = 1e308/" \
    "Invalid value '1e308' for the parameter 'Material model/linear peridynamic solid/Young's modulus': with the horizon" 2
  expect_error "s/    set Poisson's ratio = 0.25/    set Poisson's ratio = 0.25\n    set Young's modulus = 1e308/; s/set Dimension = 2/set Dimension = 2\nsubsection Linear solver\n  set Operator = matrix-free\n  set Method = CG\n  set Preconditioner = Jacobi\nend/" \
    "Invalid value '1e308' for the parameter 'Material model/linear peridynamic solid/Young's modulus'"
  # Output names that meet: the summary among the solution records (it was
  # found out only at the end, after the output was written), or a file
  # where the run needs the output directory.
  expect_error 's|set Directory = out|set Directory = out\n  set Summary file = out/solution_0.pvtu|' \
    "Invalid value 'out/solution_0.pvtu' for the parameter 'Output/Summary file': it puts the summary file at 'out/solution_0.pvtu', where the run also writes the solution records" 2
  expect_error 's|set Directory = out|set Directory = out/sub\n  set Summary file = out|' \
    "Invalid value 'out' for the parameter 'Output/Summary file': 'out' would be the summary file ('Output/Summary file') and a directory of the solution records"
  # Entries that would be ignored or do nothing in a quasi-static run: each
  # an error naming the entry and its value (issue 26, class 9), checked
  # before any output.
  for np in 1 2; do
    expect_error "s/    set Poisson's ratio = 0.25/    set Poisson's ratio = 0.25\n    set Critical stretch = 0.01/" \
      "Invalid value '0.01' for the parameter 'Material model/linear peridynamic solid/Critical stretch': this entry has no effect here: 'quasi-static/Bond breaking = off': no bond breaks" $np
    expect_error 's/  set Dirichlet boundary ids = 0, 1, 2, 3/  set Dirichlet boundary ids = 0, 1, 2, 3\n  set Dirichlet components =/' \
      "Invalid value '' for the parameter 'Boundary conditions/Dirichlet components': with no component the Dirichlet layers and boxes would prescribe nothing" $np
  done
  expect_error "s/    set Poisson's ratio = 0.25/    set Poisson's ratio = 0.25\n    set Density = 7800/" \
    "Invalid value '7800' for the parameter 'Material model/linear peridynamic solid/Density': this entry has no effect here"
  expect_error "s/    set Poisson's ratio = 0.25/    set Poisson's ratio = 0.25\n    set Shear modulus = 1e9/" \
    "Invalid value '1e9' for the parameter 'Material model/linear peridynamic solid/Shear modulus': this entry has no effect here: 'Elastic constants' selects Young's modulus and Poisson's ratio"
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Analytical solution\n  subsection Displacement\n    set Function expression = x; y\n  end\nend/' \
    "Invalid value 'x; y' for the parameter 'Analytical solution/Displacement/Function expression': this entry has no effect here: 'Analytical solution/Compare with analytical solution' is false"
  expect_error 's/  set Dirichlet boundary ids = 0, 1, 2, 3/  set Dirichlet boundary ids = 0, 1, 2\n  subsection Traction\n    set Function expression = 1; 0\n  end/' \
    "Invalid value '1; 0' for the parameter 'Boundary conditions/Traction/Function expression': this entry has no effect here: no 'Traction boundary ids' are given"
  expect_error 's/  set Dirichlet boundary ids = 0, 1, 2, 3/  set Dirichlet boundary ids = 0, 1, 2\n  set Traction boundary ids = 3\n  subsection Traction\n    set Function expression = 1; 0\n  end\n  subsection Boundary stress\n    set Function expression = 1; 0; 0; 1\n  end/' \
    "Invalid value '1; 0; 0; 1' for the parameter 'Boundary conditions/Boundary stress/Function expression': this entry has no effect here: 'Traction given as = vector' takes the traction from 'Traction'"
  expect_error 's/  set Dirichlet boundary ids = 0, 1, 2, 3/  set Dirichlet boxes = 0, 0, 0.3, 1\n  set Dirichlet layer thickness = 2/' \
    "Invalid value '2' for the parameter 'Boundary conditions/Dirichlet layer thickness': this entry has no effect here"
}

run_case_group "$group"
finish "all bad inputs rejected with clear messages"
